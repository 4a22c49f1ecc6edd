// Fixed (weld) joint: two body points coincide and the relative orientation
// is locked, so the two bodies move as one. SCA 2020 sec. 3.3.1-3.3.2.
#pragma once

#include "reeve/engine/body.h"
#include "reeve/engine/joint_common.h"

namespace reeve {

/// A fixed joint between `body` (a) and `other` (b; kWorldBody: the fixed
/// world frame), keeping the poses they have when it is added. `anchor` is
/// where the joint's force acts (JointWrench).
struct FixedDef {
  BodyId body = 0;
  BodyId other = kWorldBody;
  Vec3 anchor = Vec3::Zero();  // m, world
  double compliance = 0.0;     // m/N for the point, rad/(N m) for the orientation
};

/// Solver form of a fixed joint.
struct FixedJoint {
  BodyId a = 0, b = kWorldBody;
  Vec3 anchor_a = Vec3::Zero(), anchor_b = Vec3::Zero();  // m, local
  Quat rel = Quat::Identity();  // q_b^-1 q_a at creation, kept
  double compliance = 0.0;
  // Accumulated over this substep's sweeps: the point block's impulse on
  // body a at the anchor (kg m, -lambda) and the orientation block's
  // angular impulse on a (kg m^2, lambda).
  Vec3 impulse_linear = Vec3::Zero();
  Vec3 impulse_angular = Vec3::Zero();
};

/// Converts `def` to body-local form from the current poses of a and b.
FixedJoint makeFixedJoint(const FixedDef& def, const BodyState& a, const BodyState& b);

/// Starts a substep: clears the lambdas and impulses.
void prepareFixedJoint(FixedJoint& joint);

/// One Gauss-Seidel visit over a substep of `h` s: the point and
/// orientation rows as one 6x6 block, alpha~ = compliance / h^2.
void solveFixedJoint(FixedJoint& joint, BodyState& a, BodyState& b, double h);

/// Force and torque the joint exerted on body a over the last substep of
/// `h` s (JointWrench).
JointWrench fixedWrench(const FixedJoint& joint, double h);

}  // namespace reeve
