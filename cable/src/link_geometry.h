// Where a link's cable plane lies and where spans touch links: the
// geometry the cable update needs, kept apart from its bookkeeping.
#pragma once

#include <optional>
#include <utility>

#include "reeve/cable/cable.h"

namespace reeve {

/// A body's cable-plane normal in the world: its local z, the third column
/// of its rotation, 2 (xz + wy), 2 (yz - wx), 1 - 2 (x^2 + y^2) for a unit q
/// (one product where a rotated vector takes three).
inline Vec3 planeNormal(const Quat& q) {
  return Vec3(2.0 * (q.x() * q.z() + q.w() * q.y()), 2.0 * (q.y() * q.z() - q.w() * q.x()),
              1.0 - 2.0 * (q.x() * q.x() + q.y() * q.y()));
}

/// Coordinates (m) of the world point `p` in the link's cable plane
/// (body-local x, y; the out-of-plane part is dropped: paper sec. 3.4).
Vec2 toPlane(const BodyState& body, const Vec3& p);

/// Body-local point (m) of the plane point `p`.
inline Vec3 fromPlane(const Link& link, const Vec2& p) { return Vec3(p.x(), p.y(), link.plane_offset); }

/// Body-local anchors (on `from`, on `to`) of the span leaving `from` and
/// arriving at `to`: tangent points on links that roll, the tie points of
/// the others. Coplanar circles use the closed form of Appendix A; other
/// pairs of rolling links the alternating iteration of Fig. 6, each point
/// projected into the other link's plane, started from `warm_to` (a
/// body-local point of `to`, e.g. its current anchor) turned back by
/// `warm_turn` (rad, about `to`'s plane normal: how far `to` turned since
/// warm_to was its tangent point, so that a tangent point fixed in space
/// starts where it is). nullopt when no tangent exists (a point inside a
/// section, overlapping sections).
std::optional<std::pair<Vec3, Vec3>> spanAnchors(const Link& from, const BodyState& from_body,
                                                 const Link& to, const BodyState& to_body,
                                                 const Vec3& warm_to, double warm_turn = 0.0);

/// Where the straight span from world point `p` to `q` passes a section's
/// `centre` (m, body-local x, y: Section::centre), seen in the link's
/// plane: {signed distance of the centre from the span's line (m, + where
/// the centre lies to the right of p -> q), parameter in [0, 1] of the
/// span's point nearest it (unclamped)}.
std::pair<double, double> spanSide(const BodyState& body, const Vec2& centre, const Vec3& p, const Vec3& q);

/// Body-local z (m) of the straight span from world point `p` to `q` at
/// its point nearest `centre` (m, body-local x, y) seen in the local xy
/// plane (clamped to the span): where along the body's axis it passes a
/// link's section about that centre. The split tests see the span
/// projected into the cable plane (sec. 3.4); this says how far out of the
/// plane it really is.
double spanDepth(const BodyState& body, const Vec2& centre, const Vec3& p, const Vec3& q);

/// How far (m) `shape` reaches either side of its local plane z = 0: a
/// box's half extent in z, a cylinder's half length, a sphere's radius, a
/// hull's farthest corner in z.
double halfDepth(const Shape& shape);

/// Arc (m) paid out into a span when its anchor on a rolling link moves
/// from `old_anchor` to `new_anchor` (body-local) while the body turns by
/// `turn` (rad, about the plane normal): Alg. 1 l. 4-5 with the sign of the
/// leaving side; the arriving side uses its negative.
double payOut(const Link& link, const Vec3& old_anchor, const Vec3& new_anchor, double turn);

/// Whether the straight span from world point `p` to `q` cuts into
/// `section` deeper than `margin` (m), seen in the body's local xy plane:
/// the split test of paper sec. 4.2.
bool spanCutsSection(const Section& section, const BodyState& body, const Vec3& p, const Vec3& q,
                     double margin);

/// The body shape's own section in its local plane z = `offset` (m): what
/// a rolling link wraps when the user gives no section, and where a span
/// meets a sphere or hull off its link's plane (Link::Depth::Slice).
/// nullopt where that plane misses the shape (or cuts only a corner or
/// pole of it, to rounding: no area).
std::optional<Section> ownSection(const Shape& shape, double offset);
/// ownSection() into `out`, with `points` for a box's or hull's corners:
/// no heap once both hold the room (sectionRoom). False where ownSection()
/// gives nullopt; `out` is then not a section.
bool ownSection(const Shape& shape, double offset, Section& out, std::vector<Vec2>& points);
/// The most corners ownSection() finds for `shape` at any depth, and so
/// the room `points` needs; the section's vertices need twice that (the
/// monotone chain's stack: Section::setPolygon).
std::size_t sectionRoom(const Shape& shape);

/// Radius (m) of a circle about the body's local z axis that holds the
/// shape's section at every depth, seen along z: a sphere's radius, a
/// hull's farthest corner from the axis (a cylinder's radius, a box's
/// corner). A span that misses it misses every section.
double outerRadius(const Shape& shape);

}  // namespace reeve
