// Vertices of a chain of straight segments laid along a rope centre line
// (rope_path.h) with the centre line's length.
#pragma once

#include <vector>

#include "reeve/machines/rope_path.h"

namespace reeve {

/// N + 1 vertices (m, world) of `segments` (>= 1) straight segments along
/// `path`: vertex i sits at arc length i L / N of the polyline (L its
/// length), moved outward (RopePathPoint::outward, interpolated) by one
/// common lift chosen so that the segments' total length is `target_length`
/// (m) to 1e-12 relative: chords cut the wraps short, and the lift puts that
/// length back. The first and last vertices are the path's ends. Throws
/// std::invalid_argument if the target is shorter than the chords with no
/// lift, or cannot be reached with a lift below the path length.
std::vector<Vec3> chainVertices(const std::vector<RopePathPoint>& path, int segments,
                                double target_length);

/// Total length (m) of the segments between consecutive vertices.
double chainLength(const std::vector<Vec3>& vertices);

}  // namespace reeve
