// The drawn shape of a cable: its spans (straight when taut, hanging when
// loose), the arcs it wraps on rolling links, the coils stored on spools,
// and the sections rolling links wrap where the body does not show them.
#pragma once

#include <vector>

#include "reeve/cable/cable.h"

namespace reeve {

/// Segments of the curve drawn for a loose span (see slackCurve).
inline constexpr int kSlackSegments = 48;

/// Turns of stored cable drawn at most on a spool (see spoolCoil).
inline constexpr int kMaxCoilTurns = 20;

/// The enabled joint of cable `c` arriving at link k (its `to` is k), or
/// -1 when none does (the first link of an open cable, an inactive link).
int arrivingJoint(const CableSystem& cables, int c, int k);

/// World points (m) of the cable wrapped on rolling `link` of `body`, from
/// the world point `arrival` to `departure` (its tangent points) in the
/// link's orientation sense, in the body's cable plane (body-local x, y;
/// z = link.plane_offset), along the section: the polygon's hull vertices,
/// or circle points at most `max_step_rad` apart (sectionArcPoints), then
/// `extra_turns` (>= 0) whole turns more, each from the departure point
/// round to itself. Both ends included.
std::vector<Vec3> wrapPath(const Link& link, const BodyState& body, const Vec3& arrival,
                           const Vec3& departure, int extra_turns, double max_step_rad);

/// Whole turns of cable stored on an interior rolling link beyond the
/// geometric wrap from `arrival` to `departure` (world points):
/// round((stored - wrap) / perimeter), negative when the stored cable is
/// short of the wrap by about a turn (the arc is then not drawn).
int extraTurns(const Link& link, const BodyState& body, const Vec3& arrival,
               const Vec3& departure);

/// Polylines of world points (m) along cable `c`, following its enabled
/// joints only (a disabled joint, leaving an inactive link, is not drawn):
/// for each enabled joint j from startPoint(c, j) to endPoint(c, j) a straight span,
/// or, when its rest length exceeds its length (isSlack), a catenary of the
/// rest length sagging along the World's gravity (world -y if gravity is
/// zero); between the arriving joint and joint k, on every active link k
/// that rolls, the wrap of wrapPath() with extraTurns(). An open cable runs
/// from its first link to its last; a closed cable starts with the wrap on
/// its first active link and ends where it began, so the loop closes.
/// An unbroken cable is one polyline; a parted joint (CableJoint::parted)
/// ends one piece at its start point and the next begins after it, and
/// its loose ends hang from its two end points along gravity, tail_a and
/// tail_b long, each a polyline of its own (pieces and ends in cable
/// order, the last piece last). Polylines of fewer than two points are
/// left out. Consecutive wrap points are at most `max_step_rad` apart in
/// angle on circles; points closer than 1e-12 m to the last are dropped.
/// `c` must be a valid cable index and max_step_rad > 0.
std::vector<std::vector<Vec3>> cablePaths(const CableSystem& cables, int c, double max_step_rad);

/// The stored cable of end link k of open cable c drawn as a coil, when
/// that link rolls (rolling, or hybrid not attached) and stores cable > 0:
/// a spiral in the body's cable plane that starts at the link's tangent
/// point on the section and winds away from the span (against the link's
/// orientation on the first link, with it on the last) for
/// min(stored / perimeter, kMaxCoilTurns) turns, round polygon corners as
/// circle arcs, points at most `max_step_rad` apart in angle. Its distance
/// outside the section grows by `pitch` (m) a turn, or less: at most
/// max(inradius, `min_full_band`) / kMaxCoilTurns, so a full coil is no
/// thicker than the section's inradius (the distance from its middle to
/// its nearest edge), or `min_full_band` (m) on a spool too small to show
/// one. The spacing does not depend on the stored cable, so the coil's
/// thickness follows it as it pays out. Empty otherwise.
std::vector<Vec3> spoolCoil(const CableSystem& cables, int c, int k, double pitch,
                            double max_step_rad, double min_full_band = 0.0);

/// The closed outline of the section of rolling or hybrid `link` on
/// `body`, world points (m) in its cable plane, the first point repeated
/// at the end; circle points at most `max_step_rad` apart.
std::vector<Vec3> sectionOutline(const Link& link, const BodyState& body, double max_step_rad);

/// Whether the body's drawn `shape` shows the section `link` wraps: a
/// cylinder or sphere cut by the cable plane in a circle of the section's
/// radius, a box by the rectangle of the section, a hull by its own
/// section polygon in that plane (1e-9 relative). False
/// for links that do not wrap a section (attachments, pinholes).
bool sectionMatchesShape(const Link& link, const Shape& shape);

}  // namespace reeve
