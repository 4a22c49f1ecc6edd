// Sutherland-Hodgman clipping for contact manifolds (collide.cpp).
#pragma once

#include <vector>

#include "reeve/engine/math.h"

namespace reeve {

/// How far outside the face's edges (a fraction of its largest centre to
/// vertex distance) a point still counts as inside. A box on a box of the
/// same depth has coincident edges: yawed by 2 urad, a corner poked out
/// and the cut added points mid-edge every other substep, rocking the box
/// and its friction between two manifolds.
inline constexpr double kClipSlop = 1e-4;

/// Clips `points` (world, m: a convex polygon in cyclic order, a segment or
/// a single point) to the infinite prism swept by the convex polygon `face`
/// (world, cyclic order, >= 3 vertices) along its unit normal `n`: what
/// remains is the part whose projection along n falls inside the face, a
/// point less than the slop outside an edge kept as it is, not cut.
/// `scratch` is a reused buffer.
void clipToPrism(const std::vector<Vec3>& face, const Vec3& n, std::vector<Vec3>& points,
                 std::vector<Vec3>& scratch);

}  // namespace reeve
