// Common tangents and surface distances on circular cross-sections, in the
// 2D coordinates of a cable plane (paper sec. 3.1 and Appendix A).
#pragma once

#include <optional>

#include "reeve/engine/math.h"

namespace reeve {

/// A circle the cable wraps (radius > 0) or a point it is fixed to
/// (radius 0), in cable-plane coordinates (m). `orientation` is +1 when the
/// cable travels counter-clockwise around the circle (about the plane
/// normal) as one walks along it, -1 clockwise; ignored for points.
struct CableCircle {
  Vec2 center = Vec2::Zero();
  double radius = 0.0;
  int orientation = 1;
};

/// Tangent points of a straight span leaving `from` and arriving at `to`.
struct TangentPoints {
  Vec2 on_from;
  Vec2 on_to;
};

/// The one common tangent of `from` and `to` consistent with their
/// orientations and order (paper Fig. 3; Alg. 3 for point-circle, Alg. 4
/// for circle-circle, all four choices). With signed radii s = -o r and span
/// direction t = (cos b, sin b), the points are c + s perp(t) and
/// b = atan2(d) - asin((s_from - s_to) / |d|), d = to.center - from.center.
/// Returns nullopt when no such tangent exists (|s_from - s_to| >= |d|: the
/// shapes overlap in the sense the span needs).
std::optional<TangentPoints> commonTangent(const CableCircle& from, const CableCircle& to);

/// surfaceDist(a, a') of paper Alg. 1: arc length (m) on a circle of
/// `radius` centred at the origin from `new_point` to `old_point`, positive
/// when that arc runs in the sense of `orientation`. The shorter arc is
/// taken, so the points must be less than half a turn apart (one substep).
double surfaceDistance(const Vec2& old_point, const Vec2& new_point, double radius,
                       int orientation);

/// Arc length (m) from `arrival` to `departure` travelling in the sense of
/// `orientation`, in [0, 2 pi r): the cable wrapped on a circle of `radius`
/// centred at the origin (paper Alg. 2 line 2).
double wrappedArc(const Vec2& arrival, const Vec2& departure, double radius, int orientation);

}  // namespace reeve
