// Tangents on sections: from a point (Alg. 3 for circles, the touched hull
// vertex for polygons, paper sec. 3.2) and between two sections by the
// alternating iteration of Fig. 6.
#include <algorithm>
#include <array>

#include "reeve/cable/section.h"

namespace reeve {
namespace {

constexpr int kMaxRounds = 100;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// True if p is outside the counter-clockwise convex polygon v, not on it:
// strictly right of some edge.
bool strictlyOutside(const std::vector<Vec2>& v, const Vec2& p) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (cross(v[(i + 1) % v.size()] - v[i], p - v[i]) < 0.0) return true;
  return false;
}

// The vertex q of the convex polygon v, seen from p outside it, with every
// vertex on the `side` (+1 left, -1 right) of the ray from p through q.
// Seen from outside, the vertices span less than half a turn, so this is an
// extreme of a total order and one scan finds it. Vertices on that ray (an
// edge along it) go to the one nearer to p.
Vec2 extremeVertex(const std::vector<Vec2>& v, const Vec2& p, int side) {
  Vec2 best = v[0];
  for (const Vec2& q : v) {
    const double c = side * cross(best - p, q - p);
    if (c < 0.0 || (c == 0.0 && (q - p).squaredNorm() < (best - p).squaredNorm())) best = q;
  }
  return best;
}

// The point of `section` farthest along `dir` (section coordinates).
Vec2 support(const Section& section, const Vec2& dir) {
  if (section.kind == Section::Kind::Circle) return section.centre + section.radius * dir.normalized();
  return *std::max_element(section.vertices.begin(), section.vertices.end(),
                           [&](const Vec2& a, const Vec2& b) { return a.dot(dir) < b.dot(dir); });
}

// Largest distance (m) of the section's boundary from its origin.
double extent(const Section& section) {
  if (section.kind == Section::Kind::Circle) return section.centre.norm() + section.radius;
  double r = 0.0;
  for (const Vec2& v : section.vertices) r = std::max(r, v.norm());
  return r;
}

// Outer tangent (equal orientations `o`) of sections that may overlap, by
// trying each vertex of the polygon among them as the span's end on it: the
// other end is the tangent point seen from that vertex, and the span is a
// tangent if the whole polygon lies on the orientation's side of it. Of
// several (sections crossing each other have more than one), the shortest.
std::optional<TangentPoints> outerTangentByVertices(const Section& from, const Vec2& c_from,
                                                    const Section& to, const Vec2& c_to, int o) {
  const bool to_is_polygon = to.kind == Section::Kind::Polygon;
  const Section& polygon = to_is_polygon ? to : from;
  const Vec2& c_polygon = to_is_polygon ? c_to : c_from;
  std::optional<TangentPoints> best;
  for (const Vec2& v : polygon.vertices) {
    const Vec2 end = c_polygon + v;
    const auto other = to_is_polygon ? tangentFromPoint(from, end - c_from, o, true)
                                     : tangentFromPoint(to, end - c_to, o, false);
    if (!other) continue;
    const TangentPoints tp =
        to_is_polygon ? TangentPoints{c_from + *other, end} : TangentPoints{end, c_to + *other};
    const Vec2 t = tp.on_to - tp.on_from;
    const double tolerance = 1e-12 * t.norm() * extent(polygon);
    const bool supports = std::all_of(
        polygon.vertices.begin(), polygon.vertices.end(),
        [&](const Vec2& w) { return o * cross(t, c_polygon + w - tp.on_from) >= -tolerance; });
    if (supports && (!best || t.squaredNorm() < (best->on_to - best->on_from).squaredNorm()))
      best = tp;
  }
  return best;
}

}  // namespace

std::optional<Vec2> tangentFromPoint(const Section& section, const Vec2& p, int orientation,
                                     bool leaving) {
  if (section.kind == Section::Kind::Circle) {
    if (!((p - section.centre).norm() > section.radius)) return std::nullopt;  // keeps commonTangent off |d| = 0
    const CableCircle circle{section.centre, section.radius, orientation};
    const CableCircle point{p, 0.0, 1};
    const auto t = leaving ? commonTangent(circle, point) : commonTangent(point, circle);
    if (!t) return std::nullopt;
    return leaving ? t->on_from : t->on_to;
  }
  if (!strictlyOutside(section.vertices, p)) return std::nullopt;
  // Walking along the span the section is on the left for orientation +1.
  // Seen from p, that is the left of the ray p -> q when arriving and the
  // right when leaving (the walk runs q -> p).
  return extremeVertex(section.vertices, p, leaving ? -orientation : orientation);
}

std::optional<TangentPoints> sectionTangent(const Section& from, const Vec2& c_from, int o_from,
                                            const Section& to, const Vec2& c_to, int o_to,
                                            int* rounds) {
  if (rounds) *rounds = 0;
  if (from.kind == Section::Kind::Circle && to.kind == Section::Kind::Circle) {
    const Vec2 a = c_from + from.centre, b = c_to + to.centre;
    if (a == b) return std::nullopt;  // commonTangent divides by |d|
    return commonTangent({a, from.radius, o_from}, {b, to.radius, o_to});
  }
  // Fig. 6, from the point of `from` farthest from `to` along the line of
  // centres. Each step needs its point outside the other section, which
  // holds for sections apart. The point on `from` fixes the rest of the
  // sequence, so it settles when that point stays and cycles when it
  // returns to an earlier one (overlapping sections).
  const double tolerance = 1e-13 * std::max(extent(from), extent(to));
  const Vec2 centres = c_from + from.centre - c_to - to.centre;  // a polygon's centre is 0
  const Vec2 away = centres == Vec2::Zero() ? Vec2::UnitX() : centres;
  std::array<Vec2, kMaxRounds> visited;
  Vec2 a = c_from + support(from, away);
  for (int round = 1; round <= kMaxRounds; ++round) {
    if (rounds) *rounds = round;
    const auto on_to = tangentFromPoint(to, a - c_to, o_to, false);
    if (!on_to) break;
    const Vec2 b = c_to + *on_to;
    const auto on_from = tangentFromPoint(from, b - c_from, o_from, true);
    if (!on_from) break;
    const Vec2 a_new = c_from + *on_from;
    if ((a_new - a).norm() <= tolerance) {
      if (a_new == b) return std::nullopt;  // touching sections: no span direction
      return TangentPoints{a_new, b};
    }
    visited[round - 1] = a;
    if (std::find(visited.begin(), visited.begin() + round, a_new) != visited.begin() + round)
      break;
    a = a_new;
  }
  // Overlapping sections (a point fell inside the other one) can only share
  // an outer tangent, with equal orientations.
  if (o_from != o_to) return std::nullopt;
  return outerTangentByVertices(from, c_from, to, c_to, o_from);
}

}  // namespace reeve
