// Vertices of a chain of straight segments laid along a rope centre line
// (rope_path.h), lifted off the sections it wraps as far as the chain's
// rods need.
#pragma once

#include <functional>
#include <vector>

#include "reeve/machines/rope_path.h"

namespace reeve {

/// N + 1 vertices (m, world) of `segments` (>= 1) straight segments along
/// the centre line `path` lifted by `lift` (m): each point moved by lift x
/// RopePathPoint::outward, so a wrap on a circle of radius r becomes its
/// arc at r + lift and a span runs straight between its lifted ends.
/// Vertex i sits at arc length i L / N of that polyline (L its length), so
/// the segments are of one length but on a wrap, where a chord of angle a
/// is shorter than its arc by about a^2 / 24 of it; the first and last
/// vertices are the path's ends. Throws std::invalid_argument for fewer
/// than one segment or two points.
std::vector<Vec3> chainVertices(const std::vector<RopePathPoint>& path, int segments, double lift);

/// The vertices of chainVertices() at the least lift (m, >= 0, to 1e-12 of
/// the path's length) at which `clear(vertices)` holds: a chain whose rods
/// of radius rho start clear of the wheels they wrap, each chord at least
/// rho from each section (the chords' sag on a wrap included). `clear` must
/// hold for every lift above one at which it holds. Throws
/// std::invalid_argument as chainVertices(), or when no lift up to the
/// path's length clears.
std::vector<Vec3> clearChainVertices(const std::vector<RopePathPoint>& path, int segments,
                                     const std::function<bool(const std::vector<Vec3>&)>& clear);

/// Total length (m) of the segments between consecutive vertices.
double chainLength(const std::vector<Vec3>& vertices);

}  // namespace reeve
