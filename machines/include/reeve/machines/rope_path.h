// The current centre line of one open cable as world points: its straight
// spans and the arcs it wraps on rolling links, each point with the
// outward direction of the section it lies on (zero at the cable's ends).
// Used by `reeve segment` to lay a chain of rigid segments along a cable.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "reeve/cable/cable.h"

namespace reeve {

struct RopePathPoint {
  Vec3 p = Vec3::Zero();  ///< m, world
  /// Unit, world, in the cable plane: away from the section the point lies
  /// on (a wrap's points and its tangent points); zero at the cable's ends.
  Vec3 outward = Vec3::Zero();
};

/// Points along open cable `c` from its first link to its last: each
/// enabled joint's start and end points, and between them on every rolling
/// interior link the wrap (sectionArcPoints, at most `max_step_rad` apart).
/// Consecutive points are joined by a straight span or lie on one wrap.
/// Throws std::invalid_argument for what a chain of segments cannot stand
/// for: a closed cable, a disabled joint (inactive link), pinholes, end
/// links that are not attachments, or slack spans.
std::vector<RopePathPoint> ropeCentreline(const CableSystem& cables, int c, double max_step_rad);

/// Length (m) of the polyline through the points.
double polylineLength(const std::vector<RopePathPoint>& path);

}  // namespace reeve
