// Points that outline a scene, for framing it and placing the ground grid.
#pragma once

#include <vector>

#include "reeve/cable/cable.h"

namespace reeve {

/// Half extents (m) of the world-axis-aligned box around `shape` turned by
/// `q` (local -> world).
Vec3 worldHalfExtents(const Shape& shape, const Quat& q);

/// World points (m): the 8 corners of every body's axis-aligned bounding
/// box and every cable tangent point.
std::vector<Vec3> scenePoints(const World& world, const CableSystem& cables);

}  // namespace reeve
