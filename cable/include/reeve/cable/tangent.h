// Common tangents of circular cross-sections and points, in the
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
/// b = atan2(d) - asin((s_from - s_to) / |d|), d = to.center - from.center,
/// evaluated without angles: perp(t) = cos(a) perp(e) + sin(a) e, e = d / |d|,
/// sin(a) = (s_from - s_to) / |d|.
/// Returns nullopt when no such tangent exists (|s_from - s_to| >= |d|: the
/// shapes overlap in the sense the span needs).
std::optional<TangentPoints> commonTangent(const CableCircle& from, const CableCircle& to);

}  // namespace reeve
