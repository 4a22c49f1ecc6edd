// Spherical (ball-and-socket) joint: two body points coincide; rotation is
// free, within an optional swing limit (the angle between the bodies'
// twist axes) and an optional twist limit (rotation about them).
// SCA 2020 sec. 3.3.1-3.3.2 and its Appendix (swing and twist limits).
#pragma once

#include <numbers>

#include "reeve/engine/body.h"
#include "reeve/engine/joint_common.h"

namespace reeve {

/// A spherical joint between `body` (a) and `other` (b; kWorldBody: the
/// fixed world frame), given in world space at the moment it is added.
/// `axis` is the twist axis of both bodies at creation (used by the limits
/// only): the swing is the angle between a's and b's copies of it, and the
/// twist the rotation of a relative to b about their mean, measured from a
/// reference direction normal to the axis fixed in each body at creation
/// (0 when added, in (-pi, pi], positive counter-clockwise about the axis).
/// A twist limit needs a swing limit of at most kMaxSwingWithTwist.
struct SphericalDef {
  BodyId body = 0;
  BodyId other = kWorldBody;
  Vec3 anchor = Vec3::Zero();  // m, world: the ball's centre
  Vec3 axis = Vec3::UnitZ();   // world, normalized on use
  double compliance = 0.0;     // m/N for the point
  SwingLimit swing_limit;      // rad, in [0, pi]; rigid
  JointLimit twist_limit;      // rad, within [-pi, pi]; rigid
};

/// The largest swing limit (rad, 90 deg) a twist limit may go with. The
/// twist about the mean of the two axes is undefined at a swing of pi and
/// ill-conditioned well before it: a bar on a ball joint with a twist
/// limit alone, swung over its axis, gained 1e5 J; with swing limits past
/// pi/2, tumbling into both, it gained energy in 5 to 11 % of the spins
/// tried (1.6 to 2.5 rad; 1e5 J at 2.5), and in none up to pi/2.
inline constexpr double kMaxSwingWithTwist = std::numbers::pi / 2.0;

/// Solver form of a spherical joint.
struct SphericalJoint {
  BodyId a = 0, b = kWorldBody;
  JointFrame frame;  // anchors, axes (the twist axis of a ball joint), references
  double compliance = 0.0;
  SwingLimit swing_limit;
  JointLimit twist_limit;
  // Accumulated over this substep's sweeps: lambda of the swing limit
  // (kg m^2, <= 0), the twist limit rows, the point block's impulse on body
  // a at the anchor (kg m; its lambda is -impulse_linear) and the angular
  // impulse of the limits on a (kg m^2).
  double lambda_swing = 0.0;
  JointCoordinate twist;
  Vec3 impulse_linear = Vec3::Zero();
  Vec3 impulse_angular = Vec3::Zero();
};

/// Converts `def` to body-local form from the current poses of a and b.
SphericalJoint makeSphericalJoint(const SphericalDef& def, const BodyState& a,
                                  const BodyState& b);

/// Starts a substep: clears the lambdas and impulses.
void prepareSphericalJoint(SphericalJoint& joint);

/// One Gauss-Seidel visit over a substep of `h` s: the point rows (alpha~ =
/// compliance / h^2) as one block, solved together with each active swing
/// and twist limit row in turn (rigid, clamped).
void solveSphericalJoint(SphericalJoint& joint, BodyState& a, BodyState& b, double h);

/// Swing (rad, in [0, pi]): the angle between the two twist axes.
double swingAngle(const SphericalJoint& joint, const Quat& q_a, const Quat& q_b);

/// Twist (rad, in (-pi, pi]) of a relative to b about the mean of the two
/// twist axes (SCA 2020, Appendix).
double twistAngle(const SphericalJoint& joint, const Quat& q_a, const Quat& q_b);

/// Force and torque the joint exerted on body a over the last substep of
/// `h` s (JointWrench).
JointWrench sphericalWrench(const SphericalJoint& joint, double h);

}  // namespace reeve
