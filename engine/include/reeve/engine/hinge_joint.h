// Hinge (revolute) joint: two body points coincide and two body axes stay
// aligned; rotation about the axis is free. SCA 2020 sec. 3.3.1-3.3.2.
#pragma once

#include "reeve/engine/body.h"

namespace reeve {

/// A hinge between `body` and `other` (kWorldBody: the fixed world frame),
/// given in world space at the moment it is added.
struct HingeDef {
  BodyId body = 0;
  BodyId other = kWorldBody;
  Vec3 anchor = Vec3::Zero();    // m, world: the axle point
  Vec3 axis = Vec3::UnitZ();     // world, normalized on use
  double compliance = 0.0;       // m/N for the point, rad/(N m) for the axis
};

/// Solver form of a hinge: anchors and axes body-local.
struct HingeJoint {
  BodyId a = 0, b = kWorldBody;
  Vec3 anchor_a = Vec3::Zero(), anchor_b = Vec3::Zero();  // m, local
  Vec3 axis_a = Vec3::UnitZ(), axis_b = Vec3::UnitZ();    // local
  double compliance = 0.0;
  double lambda_point = 0.0, lambda_axis = 0.0;           // this substep
  Vec3 impulse_point = Vec3::Zero();  // kg m on body a, this substep
  Vec3 impulse_axis = Vec3::Zero();   // kg m^2 on body a, this substep
};

/// Converts `def` to body-local form from the current poses of a and b.
HingeJoint makeHingeJoint(const HingeDef& def, const BodyState& a, const BodyState& b);

/// One Gauss-Seidel visit: align axes (angular row), then join anchors
/// (positional row). `alpha_tilde` = compliance / h^2.
void solveHingeJoint(HingeJoint& joint, BodyState& a, BodyState& b, double alpha_tilde);

}  // namespace reeve
