// Hinge (revolute) joint: two body points coincide and two body axes stay
// aligned; rotation about the axis is free, within an optional angle limit
// and under an optional drive (motor). SCA 2020 sec. 3.3.1-3.3.2 and its
// Appendix (hinge limits).
#pragma once

#include <limits>
#include <vector>

#include "reeve/engine/body.h"
#include "reeve/engine/joint_common.h"

namespace reeve {

/// A motor on a hinge's angle (a relative to b about the axis).
/// Velocity: turns at `target` rad/s; Angle: turns to and holds `target`
/// rad, braking in time for the inertia about the hinge. An angle target
/// is counted through whole turns (HingeJoint::angle_total): 8 rad is a
/// drum turned on past a whole turn, not -4.57 rad.
/// Either way with at most `max_torque` N m (<= 0 or infinity: unlimited,
/// a rigid drive), so a loaded or inert hinge spins up at torque / inertia
/// rather than snapping to its target (formulas above solveHingeJoint).
///
/// An Angle drive with `stiffness` > 0 is a torsional spring instead: the
/// torque on a is -stiffness (theta - target) - damping dtheta/dt, theta
/// counted through whole turns (a spring wound twice pulls back twice as
/// far), still within max_torque. It is one
/// compliant row (Macklin, Müller, Chentanez, *XPBD*, MIG 2016:
/// alpha = 1 / stiffness, and the damping as its eq. 26 with beta~ =
/// damping h^2), implicit in both, so stable at any stiffness and substep.
///
/// `integration` chooses how a spring is integrated. Implicit (the
/// default): the compliant row above, implicit Euler, stable at any
/// stiffness and substep, but it loses about (w h)^2 of an oscillation's
/// energy per substep h (w its angular frequency: 6 % per period at
/// w h = 0.01). Trapezoidal: the trapezoidal rule (Newmark's average
/// acceleration) on the stiffness: over a substep the torque is
/// -stiffness (e_+ + 2 e_0 + e_-) / 4, e = theta - target at the end of
/// the substep, its start and the start of the previous one: still one
/// compliant row (of stiffness / 4, its target moved by the known part),
/// and an undamped linear spring keeps its energy with no drift (exactly,
/// counting its energy at the mid-substep angle; at the substep's end it
/// ripples by O(w h)); it runs slow by about (w h)^2 / 12. With the direct
/// solver it stays bounded at large w h (6.8 tested); Gauss-Seidel turns
/// bodies by first-order corrections and needs w h below about 1. The
/// damping stays implicit. In machines with unilateral cables it no longer
/// damps the other errors away (DESIGN.md: the bow).
///
/// A Velocity drive with `damping` > 0 is a damper toward its target speed
/// instead of a rigid one: the torque on a is damping (target - dtheta/dt),
/// within max_torque (at target 0, a bearing's viscous friction: MuJoCo's
/// joint damping; else its velocity servo of gain kv). One compliant row,
/// implicit: a disc of inertia I keeps 1 / (1 + damping h / I) of its
/// speed each substep h.
struct HingeDrive {
  enum class Mode { None, Velocity, Angle };
  enum class Integration { Implicit, Trapezoidal };
  Mode mode = Mode::None;
  double target = 0.0;      // rad/s (Velocity) or rad (Angle)
  double max_torque = 0.0;  // N m; <= 0 or infinity: unlimited
  double stiffness = 0.0;   // N m/rad, finite; 0: rigid (Angle only)
  double damping = 0.0;     // N m s/rad, finite; an Angle drive's only with stiffness > 0
  Integration integration = Integration::Implicit;  // of a spring (stiffness > 0)
  // s, > 0: the drive acts in the substeps that start before this time
  // (World::time(), to half a substep) and is then removed (mode None), as
  // a hand letting go; infinity: always.
  double until = std::numeric_limits<double>::infinity();
  // Non-empty: `target` follows this schedule (World sets it each substep:
  // a velocity at the substep's middle, an angle at its end, so a ramp is
  // followed exactly); times strictly increasing, targets finite.
  std::vector<DriveKeyframe> schedule = {};

  /// A spring integrated by the trapezoidal rule.
  bool isTrapezoidalSpring() const {
    return mode == Mode::Angle && stiffness > 0.0 && integration == Integration::Trapezoidal;
  }
};

/// A hinge between `body` (a) and `other` (b; kWorldBody: the fixed world
/// frame), given in world space at the moment it is added. Its angle is
/// that of a relative to b about `axis`, measured from a reference
/// direction perpendicular to the axis fixed in each body at creation: 0
/// when added, in (-pi, pi], positive counter-clockwise about `axis`.
struct HingeDef {
  HingeDef() = default;
  /// The original five-field form, `{body, other, anchor, axis,
  /// compliance}`, optionally followed by a limit and a drive.
  HingeDef(BodyId body_, BodyId other_, const Vec3& anchor_, const Vec3& axis_,
           double compliance_ = 0.0, const JointLimit& limit_ = {}, const HingeDrive& drive_ = {})
      : body(body_), other(other_), anchor(anchor_), axis(axis_), compliance(compliance_),
        limit(limit_), drive(drive_) {}

  BodyId body = 0;
  BodyId other = kWorldBody;
  Vec3 anchor = Vec3::Zero();    // m, world: the axle point
  Vec3 axis = Vec3::UnitZ();     // world, normalized on use
  double compliance = 0.0;       // m/N for the point, rad/(N m) for the axis
  JointLimit limit;              // rad, within [-pi, pi]; rigid
  HingeDrive drive;
};

/// Solver form of a hinge: anchors, axes and reference directions
/// body-local, and what the rows did this substep.
struct HingeJoint {
  BodyId a = 0, b = kWorldBody;
  JointFrame frame;  // anchors, axes (the twist axis of a ball joint), references
  double compliance = 0.0;
  JointLimit limit;
  HingeDrive drive;
  // Accumulated over this substep's sweeps: the limit and drive rows on the
  // angle; the impulse of the point rows on body a at the anchor (kg m),
  // and the angular impulse of the axis, limit and drive rows on a (kg m^2).
  JointCoordinate angle;
  // The hinge angle now (rad), counted through whole turns: 0 when made,
  // 2 pi after a turn (trackHingeAngle). Drives aim at it; limits use the
  // angle in (-pi, pi].
  double angle_total = 0.0;
  Vec3 impulse_point = Vec3::Zero();
  Vec3 impulse_axis = Vec3::Zero();
  // A trapezoidal spring's angle at the start of the previous substep
  // (rad; NaN before the first).
  double spring_previous = std::numeric_limits<double>::quiet_NaN();
};

/// Converts `def` to body-local form from the current poses of a and b.
HingeJoint makeHingeJoint(const HingeDef& def, const BodyState& a, const BodyState& b);

/// Starts a substep of `h` s, after integration: clears the lambdas and
/// impulses and sets up the drive from the poses at the start of the
/// substep (x_prev, q_prev; see JointCoordinate and joint_rows.h). A
/// capped angle drive brakes in time for `braking_inverse_inertia`
/// (1 / (kg m^2) about its axis: World::brakingInverseInertia).
void prepareHingeJoint(HingeJoint& joint, const BodyState& a, const BodyState& b, double h,
                       double braking_inverse_inertia);

/// Whether the hinge has no row to solve: a rotor's (body.h) without a
/// drive or limit, whose axle is the rotor's inverse inertia. Its
/// Gauss-Seidel visits do nothing, and the sweep leaves them out.
inline bool hingeSolvesNothing(const HingeJoint& joint, const BodyState& a, const BodyState& b) {
  return (a.isRotor() || b.isRotor()) && joint.drive.mode == HingeDrive::Mode::None && !joint.limit.enabled;
}

/// One Gauss-Seidel visit over a substep of `h` s: the point and axis rows
/// (alpha~ = compliance / h^2) as one block, solved together with each
/// active drive and limit row on the angle in turn (clamped; rigid, but a
/// spring's drive row, whose compliance is 1 / ((stiffness + damping / h)
/// h^2)).
void solveHingeJoint(HingeJoint& joint, BodyState& a, BodyState& b, double h);

/// Angle (rad, in (-pi, pi]) of a relative to b about the axis, 0 when the
/// hinge was made; from orientations q_a, q_b (world).
double hingeAngle(const HingeJoint& joint, const Quat& q_a, const Quat& q_b);

/// Brings `joint.angle_total` to the end of a substep of `h` s, after the
/// velocities are read out: the whole turns from the relative angular
/// velocity (h omega is the substep's turn, however many turns), the rest
/// from the poses (an undamped rotor's turn is h omega exactly, and takes
/// no pose). Right while the speed changes by less than pi / h in a
/// substep.
void trackHingeAngle(HingeJoint& joint, const BodyState& a, const BodyState& b, double h);

/// The hinge angle (rad) counted through whole turns from the current
/// poses: `joint.angle_total` moved to the nearest angle the poses give
/// (a pose set between steps moves it by less than half a turn).
double hingeAngleTotal(const HingeJoint& joint, const Quat& q_a, const Quat& q_b);

/// Force and torque the hinge exerted on body a over the last substep of
/// `h` s (JointWrench).
JointWrench hingeWrench(const HingeJoint& joint, double h);

}  // namespace reeve
