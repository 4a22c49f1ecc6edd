#include "reeve/cable/tangent.h"

#include <cmath>

namespace reeve {
namespace {

Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }

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
  // t is d's direction e turned by -asin(sine): t = cosine e - sine perp(e),
  // so n = perp(t) = cosine perp(e) + sine e, with no angle formed.
  const Vec2 e = d / dist;
  const double cosine = std::sqrt((1.0 - sine) * (1.0 + sine));
  const Vec2 n = cosine * perp(e) + sine * e;
  return TangentPoints{from.center + s_from * n, to.center + s_to * n};
}

}  // namespace reeve
