#include "reeve/cable/tangent.h"

#include <cmath>

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

}  // namespace reeve
