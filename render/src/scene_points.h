// Points that outline a scene, for framing it and placing the ground grid.
#pragma once

#include <vector>

#include "reeve/cable/cable.h"

namespace reeve {

/// Half extents (m) of the world-axis-aligned box around `shape` turned by
/// `q` (local -> world).
Vec3 worldHalfExtents(const Shape& shape, const Quat& q);

/// World points (m): the 8 corners of every body's axis-aligned bounding
/// box, every point of every drawn cable path (enabled spans, hanging
/// loose spans, wraps; see cablePath), the outline of every section a
/// rolling or hybrid link wraps and spool coils at their widest.
std::vector<Vec3> scenePoints(const World& world, const CableSystem& cables);

}  // namespace reeve
