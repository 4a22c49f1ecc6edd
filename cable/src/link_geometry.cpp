#include "link_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "links.h"
#include "reeve/cable/tangent.h"
#include "reeve/engine/convex_hull.h"

namespace reeve {
namespace {

// A link's cable plane in world: its normal (planeNormal) and its origin,
// the body's centre moved along it by the link's plane offset and, for a
// circle, in it to the circle's centre.
struct Plane {
  Vec3 normal, origin;
};

Plane planeOf(const BodyState& body, const Link& link) {
  const Vec3 n = planeNormal(body.q);
  const Vec2& c = link.section.centre;  // a polygon's is 0
  const Vec3 origin = body.x + link.plane_offset * n;
  return {n, c == Vec2::Zero() ? origin : Vec3(origin + body.q * Vec3(c.x(), c.y(), 0.0))};
}

bool coplanar(const Plane& a, const Plane& b) {
  return std::abs(a.normal.dot(b.normal)) > 1.0 - 1e-12 && std::abs((b.origin - a.origin).dot(a.normal)) < 1e-9;
}

// Appendix A closed form for two circles in one plane, computed in the
// plane of `from`; `to`'s orientation flips if its normal points the other way.
std::optional<std::pair<Vec3, Vec3>> coplanarCircles(const Link& from, const BodyState& fb, const Plane& from_plane,
                                                     const Link& to, const BodyState& tb, const Plane& to_plane) {
  const int flip = from_plane.normal.dot(to_plane.normal) < 0.0 ? -1 : 1;
  const CableCircle a{from.section.centre, from.section.radius, from.orientation};
  const CableCircle b{toPlane(fb, to_plane.origin), to.section.radius, flip * to.orientation};
  const auto t = commonTangent(a, b);
  if (!t) return std::nullopt;
  const Vec3 on_to = fb.toWorld(fromPlane(from, t->on_to));
  return std::pair{fromPlane(from, t->on_from), fromPlane(to, toPlane(tb, on_to))};
}

// Paper Fig. 6 in 3D: alternate tangent points, projecting each into the
// other link's plane, until the point on `from` stops moving. nullopt if a
// point falls inside the other section or the iteration does not settle.
std::optional<std::pair<Vec3, Vec3>> alternate(const Link& from, const BodyState& fb, const Link& to,
                                               const BodyState& tb, Vec3 on_to) {
  const double tolerance = 1e-13 * std::max(from.section.perimeter(), to.section.perimeter());
  // `to`'s body frame in `from`'s, once: each round maps a point between
  // the two with one matrix product (it took two quaternion products).
  const Mat3 world_a = fb.q.toRotationMatrix().transpose();
  const Mat3 b_to_a = world_a * tb.q.toRotationMatrix();
  const Vec3 b_in_a = world_a * (tb.x - fb.x);
  const auto inA = [&](const Vec3& p) { return Vec2((b_to_a * p + b_in_a).head<2>()); };
  const auto inB = [&](const Vec3& p) { return Vec2((b_to_a.transpose() * (p - b_in_a)).head<2>()); };
  Vec3 on_from = Vec3::Constant(std::numeric_limits<double>::infinity());
  for (int round = 0; round < 100; ++round) {
    const auto a = tangentFromPoint(from.section, inA(on_to), from.orientation, true);
    if (!a) return std::nullopt;
    const Vec3 new_from = fromPlane(from, *a);
    const auto b = tangentFromPoint(to.section, inB(new_from), to.orientation, false);
    if (!b) return std::nullopt;
    on_to = fromPlane(to, *b);
    const bool settled = (new_from - on_from).norm() <= tolerance;
    on_from = new_from;
    if (settled) return std::pair{on_from, on_to};
  }
  return std::nullopt;
}

// Two sections in one plane that the iteration could not settle (they
// overlap): the full search of sectionTangent in the plane of `from`, with
// `to`'s section carried over point by point. Rare, so it may allocate.
std::optional<std::pair<Vec3, Vec3>> coplanarSearch(const Link& from, const BodyState& fb, const Plane& from_plane,
                                                    const Link& to, const BodyState& tb, const Plane& to_plane) {
  const int flip = from_plane.normal.dot(to_plane.normal) < 0.0 ? -1 : 1;
  const Vec2 c_to = toPlane(fb, to_plane.origin);
  Section carried = to.section;
  carried.centre.setZero();  // a circle's is c_to
  if (carried.kind == Section::Kind::Polygon) {
    std::vector<Vec2> points;
    for (const Vec2& v : to.section.vertices) points.push_back(toPlane(fb, tb.toWorld(fromPlane(to, v))) - c_to);
    carried = Section::polygon(std::move(points));
  }
  const auto t = sectionTangent(from.section, Vec2::Zero(), from.orientation, carried, c_to, flip * to.orientation);
  if (!t) return std::nullopt;
  const Vec3 on_to = fb.toWorld(fromPlane(from, t->on_to));
  return std::pair{fromPlane(from, t->on_from), fromPlane(to, toPlane(tb, on_to))};
}

}  // namespace

Vec2 toPlane(const BodyState& body, const Vec3& p) {
  const Vec3 local = body.toLocal(p);
  return Vec2(local.x(), local.y());
}

std::optional<std::pair<Vec3, Vec3>> spanAnchors(const Link& from, const BodyState& fb,
                                                 const Link& to, const BodyState& tb,
                                                 const Vec3& warm_to, double warm_turn) {
  const bool from_rolls = from.rolls(), to_rolls = to.rolls();
  if (!from_rolls && !to_rolls) return std::pair{from.point, to.point};
  if (!to_rolls) {
    const auto a = tangentFromPoint(from.section, toPlane(fb, tb.toWorld(to.point)),
                                    from.orientation, true);
    if (!a) return std::nullopt;
    return std::pair{fromPlane(from, *a), to.point};
  }
  if (!from_rolls) {
    const auto b = tangentFromPoint(to.section, toPlane(tb, fb.toWorld(from.point)),
                                    to.orientation, false);
    if (!b) return std::nullopt;
    return std::pair{from.point, fromPlane(to, *b)};
  }
  const Plane from_plane = planeOf(fb, from), to_plane = planeOf(tb, to);
  const bool same_plane = coplanar(from_plane, to_plane);
  if (from.section.kind == Section::Kind::Circle && to.section.kind == Section::Kind::Circle && same_plane)
    return coplanarCircles(from, fb, from_plane, to, tb, to_plane);
  // A wheel on a fixed axle turning under a span in space keeps its tangent
  // point where it was in space: turned back, the start is the answer, and
  // the alternation settles in two rounds, not seven or eight.
  Vec3 start = warm_to;
  if (warm_turn != 0.0) {
    const double c = std::cos(warm_turn), s = std::sin(warm_turn);
    start = Vec3(c * warm_to.x() + s * warm_to.y(), c * warm_to.y() - s * warm_to.x(), warm_to.z());
  }
  if (auto anchors = alternate(from, fb, to, tb, start)) return anchors;
  if (same_plane) return coplanarSearch(from, fb, from_plane, to, tb, to_plane);
  return std::nullopt;
}

bool spanCutsSection(const Section& section, const BodyState& body, const Vec3& p, const Vec3& q,
                     double margin) {
  const Vec2 a = toPlane(body, p) - section.centre, b = toPlane(body, q) - section.centre;  // a polygon's is 0
  const Vec2 d = b - a;
  if (section.kind == Section::Kind::Circle) {
    const double len2 = d.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp(-a.dot(d) / len2, 0.0, 1.0) : 0.0;
    return (a + t * d).norm() < section.radius - margin;
  }
  // Cyrus-Beck: clip the segment to the polygon shrunk by `margin`.
  const auto& v = section.vertices;
  double t0 = 0.0, t1 = 1.0;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec2 e = v[(i + 1) % v.size()] - v[i];
    const Vec2 n = Vec2(e.y(), -e.x()).normalized();  // outward for a ccw polygon
    const double dist = n.dot(a - v[i]) + margin;       // > 0: outside the shrunk edge
    const double rate = n.dot(d);
    if (rate == 0.0) {
      if (dist > 0.0) return false;
    } else if (rate > 0.0) {
      t1 = std::min(t1, -dist / rate);
    } else {
      t0 = std::max(t0, -dist / rate);
    }
    if (t0 >= t1) return false;
  }
  return true;
}

std::pair<double, double> spanSide(const BodyState& body, const Vec2& centre, const Vec3& p, const Vec3& q) {
  const Vec2 from = toPlane(body, p), d = toPlane(body, q) - from, a = from - centre;
  const double len2 = d.squaredNorm();
  if (!(len2 > 0.0)) return {0.0, 0.0};
  return {(a.y() * d.x() - a.x() * d.y()) / std::sqrt(len2), -a.dot(d) / len2};
}

double spanDepth(const BodyState& body, const Vec2& centre, const Vec3& p, const Vec3& q) {
  const Vec3 a = body.toLocal(p), d = body.toLocal(q) - a;
  const double len2 = d.head<2>().squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((centre - a.head<2>()).dot(d.head<2>()) / len2, 0.0, 1.0) : 0.0;
  return a.z() + t * d.z();
}

double halfDepth(const Shape& shape) {
  switch (shape.type) {
    case Shape::Type::Box:
      return shape.half_extents.z();
    case Shape::Type::Cylinder:
      return shape.half_length;
    case Shape::Type::Sphere:
      return shape.radius;
    case Shape::Type::Hull: {
      double depth = 0.0;
      for (const Vec3& v : shape.hull->vertices) depth = std::max(depth, std::abs(v.z()));
      return depth;
    }
  }
  return 0.0;
}

bool ownSection(const Shape& shape, double offset, Section& out, std::vector<Vec2>& points) {
  const auto circle = [&](double radius) {
    out.kind = Section::Kind::Circle;
    out.radius = radius;
    out.vertices.clear();
    return radius > 0.0;  // a sphere met at its pole, to rounding: none
  };
  switch (shape.type) {
    case Shape::Type::Box: {
      if (std::abs(offset) >= shape.half_extents.z()) return false;
      const double hx = shape.half_extents.x(), hy = shape.half_extents.y();
      points.assign({Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(hx, hy), Vec2(-hx, hy)});
      return out.setPolygon(points);
    }
    case Shape::Type::Cylinder:
      return std::abs(offset) < shape.half_length && circle(shape.radius);
    case Shape::Type::Sphere:
      return std::abs(offset) < shape.radius && circle(std::sqrt(shape.radius * shape.radius - offset * offset));
    case Shape::Type::Hull:
      // Near a corner the slice may be too small to have an area: none.
      planeSection(*shape.hull, offset, points);
      return !points.empty() && out.setPolygon(points);
  }
  return false;
}

std::size_t sectionRoom(const Shape& shape) {
  switch (shape.type) {
    case Shape::Type::Box:
      return 4;
    case Shape::Type::Cylinder:
    case Shape::Type::Sphere:
      return 0;
    case Shape::Type::Hull: {
      std::size_t room = 0;  // planeSection: a point per face edge it crosses
      for (const ConvexHull::Face& face : shape.hull->faces) room += face.vertices.size();
      return room;
    }
  }
  return 0;
}

std::optional<Section> ownSection(const Shape& shape, double offset) {
  Section section;
  std::vector<Vec2> points;
  if (!ownSection(shape, offset, section, points)) return std::nullopt;
  return section;
}

double outerRadius(const Shape& shape) {
  switch (shape.type) {
    case Shape::Type::Box:
      return shape.half_extents.head<2>().norm();
    case Shape::Type::Cylinder:
    case Shape::Type::Sphere:
      return shape.radius;
    case Shape::Type::Hull: {
      double radius = 0.0;
      for (const Vec3& v : shape.hull->vertices) radius = std::max(radius, v.head<2>().norm());
      return radius;
    }
  }
  return 0.0;
}

double payOut(const Link& link, const Vec3& old_anchor, const Vec3& new_anchor, double turn) {
  return sectionSurfaceDistance(link.section, planePoint(old_anchor), planePoint(new_anchor), link.orientation,
                                turn);
}

}  // namespace reeve
