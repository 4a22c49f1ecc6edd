// Cross-sections a cable wraps: a circle or a convex polygon in the 2D
// coordinates of a body's cable plane (body-local x, y). Tangents
// from a point and between two sections (paper sec. 3.1, 3.2 with Fig. 5-6,
// 3.4), distances along the boundary (Alg. 1 surfaceDist, Alg. 2 stored
// cable).
#pragma once

#include <optional>
#include <vector>

#include "reeve/cable/tangent.h"

namespace reeve {

/// The cross-section of a body in its cable plane (paper sec. 3.2, 3.4):
/// a circle of `radius` (m) about `centre`, or a convex polygon with
/// `vertices` (m, counter-clockwise, at least 3, strictly convex: no
/// duplicate or collinear vertices). Build it with circle() or polygon(),
/// which enforce those invariants; every function below assumes them.
struct Section {
  enum class Kind { Circle, Polygon };
  Kind kind = Kind::Circle;
  double radius = 0.0;         ///< m, Circle only
  std::vector<Vec2> vertices;  ///< m, Polygon only: convex, counter-clockwise
  /// m, Circle only: where it lies in the plane (a pulley's axle off its
  /// body's centre of mass, a knuckle at a phalanx's end). A polygon's
  /// vertices carry their own place.
  Vec2 centre = Vec2::Zero();

  /// A circle of `radius` (m) about `centre` (m). Throws
  /// std::invalid_argument unless radius > 0 and both are finite.
  static Section circle(double radius, const Vec2& centre = Vec2::Zero());
  /// The convex hull of any set of `points` (m), by Andrew's monotone chain:
  /// counter-clockwise from the lowest-x (then lowest-y) point, duplicate and
  /// collinear points dropped (paper sec. 3.4: "compute the convex hull of
  /// the cross section"). Throws std::invalid_argument if a point is not
  /// finite or the hull has zero area.
  static Section polygon(std::vector<Vec2> points);
  /// polygon(points) into this section, its vertices' room reused: no heap
  /// once that holds 2 x points.size(). Sorts `points` (not this section's
  /// own vertices) in place. False where polygon() would throw; the
  /// section is then not a valid one.
  bool setPolygon(std::vector<Vec2>& points);

  /// Boundary length (m): 2 pi r, or the sum of the edge lengths.
  double perimeter() const;

  /// The same section: kind, radius, vertices and centre equal.
  bool operator==(const Section&) const = default;
};

/// Section of a box with half extents `hx`, `hy` (m, > 0) in its local
/// z = 0 plane: the rectangle [-hx, hx] x [-hy, hy]. Throws
/// std::invalid_argument unless both are > 0 and finite.
Section boxSection(double hx, double hy);

/// Tangent point (m, section coordinates) of a straight span between
/// `section` and the point `p` (same coordinates): the span LEAVES the
/// section towards p if `leaving`, else ARRIVES on it from p. `orientation`
/// +1: the cable travels counter-clockwise around the section as one walks
/// along it, -1 clockwise; walking along the span, the section lies on the
/// left for +1 and on the right for -1. Circle: the closed form of Alg. 3
/// (equal to commonTangent() with a point). Polygon: the hull vertex the
/// tangent line touches (sec. 3.2); if the line touches an edge, the end of
/// that edge nearer to p. nullopt if p is inside or on the section.
std::optional<Vec2> tangentFromPoint(const Section& section, const Vec2& p, int orientation,
                                     bool leaving);

/// Common tangent of a span leaving `from` and arriving at `to`, two
/// sections given in ONE plane with their origins at `c_from` and `c_to` (m;
/// the sections are not rotated: pass rotated vertices if needed).
/// `o_from`, `o_to` are the link orientations (+1/-1, as in
/// tangentFromPoint()); returned points are in plane coordinates.
/// Circle-circle: commonTangent() (Appendix A, Alg. 4). Otherwise the
/// alternating iteration of Fig. 6: from the point of `from` farthest from
/// `to`, the tangent point on `to` seen from it, from that the tangent point
/// on `from`, until the point on `from` moves by at most 1e-13 times the
/// larger section size (finite for polygons; a circle's point is then fixed
/// by the polygon vertex). The iteration needs each point outside the other
/// section; when sections overlap it may fail or cycle (detected), and with
/// equal orientations the outer tangent is then found by trying each
/// polygon vertex as the span's end. `rounds`, if given, receives the
/// number of rounds of the iteration (0 for circle-circle). nullopt if no
/// such tangent exists: crossed orientations on sections that are not apart,
/// equal ones on sections of which one holds the other, touching points.
std::optional<TangentPoints> sectionTangent(const Section& from, const Vec2& c_from, int o_from,
                                            const Section& to, const Vec2& c_to, int o_to,
                                            int* rounds = nullptr);

/// Position (m, in [0, perimeter)) along the boundary of the boundary point
/// nearest to `p`, measured counter-clockwise from vertex 0 (polygon) or
/// from the +x axis through its centre (circle).
double boundaryPosition(const Section& section, const Vec2& p);

/// The boundary point (m, section coordinates) at `position` (m) measured
/// counter-clockwise as in boundaryPosition(); any real position, wrapped.
Vec2 boundaryPoint(const Section& section, double position);

/// surfaceDist(a, a') of Alg. 1 on the section's boundary (the hull for
/// polygons, sec. 3.2): the length (m) from `new_point` to `old_point` along
/// the boundary, positive when that way runs in the sense of `orientation`.
/// Two points on a boundary are joined both ways round; `turn_rad` picks
/// the way: how far (rad, counter-clockwise about the plane normal, not
/// wrapped) the section turned since `old_point` was its tangent point,
/// which carries `old_point` that far ahead of a tangent point that stays
/// put. A circle takes the way nearest r x turn_rad, exact while the
/// tangent point itself moves less than half a turn; a polygon the shorter
/// way plus one perimeter per whole turn (round(turn_rad / 2 pi)), exact
/// while the rest of the turn moves the tangent point less than half the
/// boundary. turn_rad = 0 (a section that did not turn): the shorter way.
/// Points off the boundary count as their nearest boundary point.
double sectionSurfaceDistance(const Section& section, const Vec2& old_point, const Vec2& new_point,
                              int orientation, double turn_rad = 0.0);

/// Boundary length (m, in [0, perimeter)) from `arrival` to `departure`
/// travelling in the sense of `orientation`: the cable stored on the
/// section (Alg. 2 line 2).
double sectionWrappedArc(const Section& section, const Vec2& arrival, const Vec2& departure,
                         int orientation);

/// Points (m, section coordinates) of the cable wrapped from `arrival` to
/// `departure` in the sense of `orientation`, for drawing: `arrival`, then
/// the polygon vertices passed in between, or circle points at most
/// `max_step_rad` (rad, > 0) apart, then `departure`; at least these two.
/// Throws std::invalid_argument unless max_step_rad > 0.
std::vector<Vec2> sectionArcPoints(const Section& section, const Vec2& arrival,
                                   const Vec2& departure, int orientation, double max_step_rad);

}  // namespace reeve
