#include "reeve/cable/tangent.h"

#include <cmath>
#include <numbers>

namespace reeve {
namespace {

Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }

double angleOf(const Vec2& v) { return std::atan2(v.y(), v.x()); }

}  // namespace

std::optional<TangentPoints> commonTangent(const CableCircle& from, const CableCircle& to) {
  // Leaving `from` at a, the span direction t must be the travel direction
  // o perp(m) with m the outward unit normal at a, so m = -o perp(t) and
  // a = c + s perp(t), s = -o r. Collinearity of a_to - a_from with t gives
  // perp(t) . d = s_from - s_to.
  const Vec2 d = to.center - from.center;
  const double dist = d.norm();
  if (dist == 0.0) return std::nullopt;
  const double s_from = -from.orientation * from.radius;
  const double s_to = -to.orientation * to.radius;
  const double sine = (s_from - s_to) / dist;
  if (!(std::abs(sine) < 1.0)) return std::nullopt;
  const double beta = angleOf(d) - std::asin(sine);
  const Vec2 n = perp(Vec2(std::cos(beta), std::sin(beta)));
  return TangentPoints{from.center + s_from * n, to.center + s_to * n};
}

double surfaceDistance(const Vec2& old_point, const Vec2& new_point, double radius,
                       int orientation) {
  // Signed angle from new to old in (-pi, pi], read in the orientation sense.
  const double angle = std::atan2(new_point.x() * old_point.y() - new_point.y() * old_point.x(),
                                  new_point.dot(old_point));
  return orientation * angle * radius;
}

double wrappedArc(const Vec2& arrival, const Vec2& departure, double radius, int orientation) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  double angle = orientation * (angleOf(departure) - angleOf(arrival));
  angle = std::fmod(angle, two_pi);
  if (angle < 0.0) angle += two_pi;
  if (angle >= two_pi) angle = 0.0;  // -0 plus 2 pi rounds up to 2 pi
  return angle * radius;
}

}  // namespace reeve
