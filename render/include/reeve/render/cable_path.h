// The drawn shape of a cable: its spans and the arcs it wraps on bodies.
#pragma once

#include <vector>

#include "reeve/cable/cable.h"

namespace reeve {

/// World points (m) along cable `c` from its first link to its last: for
/// each joint j its start and end tangent points (a straight span), and
/// between joints k-1 and k, for a rolling link k, the arc on the body's
/// circle in its local z = 0 plane, from the arrival tangent point to the
/// departure one in the link's orientation sense (+1 counter-clockwise
/// about local +z), through whole extra turns when the stored cable says
/// so. Consecutive arc points are at most `max_step_rad` apart in angle.
/// `c` must be a valid cable index and max_step_rad > 0.
std::vector<Vec3> cablePath(const CableSystem& cables, int c, double max_step_rad);

}  // namespace reeve
