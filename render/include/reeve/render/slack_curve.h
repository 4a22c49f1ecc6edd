// The drawn shape of a loose cable span. Paper sec. 3.1: "We visualize the
// loose case by drawing a curved cable procedurally but for the simulation
// we can still think of it as a straight line." The curve is a catenary,
// the shape of a hanging cable.
#pragma once

#include <vector>

#include "reeve/engine/math.h"

namespace reeve {

/// Relative excess of rest length over straight length beyond which a span
/// is drawn hanging rather than straight.
inline constexpr double kSlackThreshold = 1e-4;

/// Whether a span of rest length `rest` (m) between points `chord` (m)
/// apart is drawn hanging: rest > chord * (1 + kSlackThreshold).
bool isSlack(double rest, double chord);

/// `segments` + 1 points (m) of a cable of length `length` (m) hanging from
/// `a` to `b` under gravity along `down` (any non-zero vector): a catenary
/// in the vertical plane through the chord (ends at different heights
/// allowed), sampled at equal arc lengths, whose POLYLINE length equals
/// `length` (to rounding, by adjusting the catenary for the chords cut
/// short). The first point is `a` and the last `b`, exactly. When
/// `length` <= |b - a| the points lie evenly spaced on the straight chord.
/// When the chord is (within 1e-9 of `length`) parallel to `down`, the
/// cable hangs folded: straight down to one lowest point and back up.
/// Throws std::invalid_argument unless segments >= 2, length >= 0 and
/// finite, and down is non-zero and finite.
std::vector<Vec3> slackCurve(const Vec3& a, const Vec3& b, double length, const Vec3& down,
                             int segments);

}  // namespace reeve
