// Measurements the robustness tests and benchmarks take of a running
// machine: how far a hinge's two anchors have come apart, how far the
// cable's spans are stretched, the smallest rest length.
#pragma once

#include <algorithm>

#include "reeve/cable/cable.h"

namespace reeve::machines {

/// Distance (m) between a hinge's anchor on its body and on the other body
/// (the axle a wheel should stay on).
inline double axleOffset(const World& world, HingeId id) {
  const HingeJoint& j = world.hinge(id);
  return (world.body(j.a).toWorld(j.frame.anchor_a) - world.body(j.b).toWorld(j.frame.anchor_b)).norm();
}

/// Largest strain (length - rest length) / rest length over the enabled
/// spans of cable `c` that hold cable, as of the poses now (lengthNow,
/// restLengthNow: a wheel the last solve turned has wound its cable); 0
/// when all are slack.
inline double maxStretch(const CableSystem& cables, int c) {
  double worst = 0.0;
  for (int j = 0; j < static_cast<int>(cables.cables()[c].joints.size()); ++j) {
    const double rest = cables.restLengthNow(c, j);
    if (!cables.jointEnabled(c, j) || rest <= 0.0) continue;
    worst = std::max(worst, (cables.lengthNow(c, j) - rest) / rest);
  }
  return worst;
}

/// Smallest rest length (m) of the enabled spans of cable `c`.
inline double minRestLength(const CableSystem& cables, int c) {
  double least = 1e300;
  for (int j = 0; j < static_cast<int>(cables.cables()[c].joints.size()); ++j)
    if (cables.jointEnabled(c, j)) least = std::min(least, cables.restLength(c, j));
  return least;
}

}  // namespace reeve::machines
