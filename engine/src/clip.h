// Sutherland-Hodgman clipping for contact manifolds (collide.cpp).
#pragma once

#include <vector>

#include "reeve/engine/math.h"

namespace reeve {

/// Clips `points` (world, m: a convex polygon in cyclic order, a segment or
/// a single point) to the infinite prism swept by the convex polygon `face`
/// (world, cyclic order, >= 3 vertices) along its unit normal `n`: what
/// remains is the part whose projection along n falls inside the face.
/// `scratch` is a reused buffer.
void clipToPrism(const std::vector<Vec3>& face, const Vec3& n, std::vector<Vec3>& points,
                 std::vector<Vec3>& scratch);

}  // namespace reeve
