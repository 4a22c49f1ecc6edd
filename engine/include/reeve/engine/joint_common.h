// What the joint types (hinge, prismatic, spherical, fixed) share: limits
// and drives on a joint coordinate, and the force and torque a joint
// exerts. Müller et al., "Detailed Rigid Body Simulation with Extended
// Position Based Dynamics", SCA 2020, sec. 3.3.
//
// Every joint joins body a (its def's `body`) to body b (its def's `other`,
// kWorldBody for the fixed world frame). Its coordinates (hinge angle,
// twist angle, slide) are those of a relative to b, 0 when the joint is
// added; lambda > 0 on a coordinate row pushes the coordinate up.
#pragma once

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "reeve/engine/keyframes.h"
#include "reeve/engine/math.h"

namespace reeve {

/// A range [lower, upper] of a joint coordinate, in the coordinate's unit:
/// rad for hinge and twist angles (within [-pi, pi]), m for slides.
/// Enforced only while `enabled`, as unilateral rows: a bound acts only
/// when it is violated and only pushes back (SCA 2020 sec. 3.3.2, joint
/// limits; Appendix, hinge and twist limits). lower <= upper.
struct JointLimit {
  bool enabled = false;
  double lower = 0.0;
  double upper = 0.0;
};

/// A bound on the swing of a spherical joint: the angle (rad, in [0, pi])
/// between the twist axes of the two bodies (SCA 2020, Appendix, swing
/// limit). Enforced only while `enabled`.
struct SwingLimit {
  bool enabled = false;
  double max = 0.0;
};

/// What a joint exerted on its body a over the last substep, from the sum
/// of its rows' lambda n / h^2 (SCA 2020 sec. 3.3: f = lambda n / h^2):
/// `force` (N, world) acting at the joint's anchor on a, and a pure
/// `torque` (N m, world) from its angular rows. Body b got the opposite.
struct JointWrench {
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
};

/// True when a drive's maximum force (N) or torque (N m) means
/// "unlimited": <= 0 or infinite.
inline bool isUnlimited(double max_effort) {
  return !(max_effort > 0.0) || std::isinf(max_effort);
}

/// One point of a drive's schedule: from `time` (s, simulated) the drive
/// aims at `target` (its unit: rad/s or rad, m/s or m).
struct DriveKeyframe {
  double time = 0.0;
  double target = 0.0;
};

/// A drive's target at time `t` (s) under `schedule` (times strictly
/// increasing, at least one point): linear between keyframes, the first's
/// target before it and the last's after it (a ramp, then a hold).
double scheduledTarget(const std::vector<DriveKeyframe>& schedule, double t);

/// Per-substep solver state of a joint coordinate with limit and drive rows
/// (a hinge's angle, a prismatic joint's slide, a spherical joint's twist).
/// lambdas are accumulated over the sweeps of one substep, in kg m^2 for
/// angles and kg m for slides, > 0 when pushing the coordinate up.
struct JointCoordinate {
  double lambda_lower = 0.0;  // lower limit, >= 0
  double lambda_upper = 0.0;  // upper limit, <= 0
  double lambda_drive = 0.0;  // drive, |.| <= max_drive_lambda
  double start = 0.0;         // coordinate at the start of the substep (rad or m)
  double drive_step = 0.0;    // change the drive asks for over the substep (rad or m)
  double max_drive_lambda = std::numeric_limits<double>::infinity();  // max effort x h^2
  // Compliance alpha~ of the drive row, rad/(kg m^2) for angles, 1/kg for
  // slides: 0 for a rigid drive, 1 / ((k + c / h) h^2) for a spring of
  // stiffness k and damping c (joint_rows::prepareCoordinate).
  double drive_compliance = 0.0;
};

/// A joint's frame on its two bodies, fixed at creation: body-local anchors
/// (m), the joint axis and a reference direction normal to it in each body,
/// so relative angles about the axis start at 0.
struct JointFrame {
  Vec3 anchor_a = Vec3::Zero(), anchor_b = Vec3::Zero();
  Vec3 axis_a = Vec3::UnitZ(), axis_b = Vec3::UnitZ();
  Vec3 ref_a = Vec3::UnitX(), ref_b = Vec3::UnitX();
};

}  // namespace reeve
