// Prismatic (slider) joint: the relative orientation of the two bodies is
// locked and a point of a moves only along an axis fixed in b, within an
// optional slide limit and under an optional drive (linear motor).
// SCA 2020 sec. 3.3.1-3.3.2.
#pragma once

#include <limits>
#include <vector>

#include "reeve/engine/body.h"
#include "reeve/engine/joint_common.h"

namespace reeve {

/// A linear motor on a prismatic joint's slide (a relative to b along the
/// axis). Velocity: slides at `target` m/s; Position: slides to and holds
/// `target` m. Either way with at most `max_force` N (<= 0 or infinity:
/// unlimited, a rigid drive).
///
/// A Position drive with `stiffness` > 0 is a linear spring instead: the
/// force on a along the axis is -stiffness (s - target) - damping ds/dt,
/// still within max_force; one compliant XPBD row, implicit, as a hinge's
/// spring (HingeDrive).
///
/// A Velocity drive with `damping` > 0 is a damper toward its target
/// speed, force damping (target - ds/dt) within max_force, as a hinge's.
///
/// `integration`, as a hinge's (HingeDrive): Implicit (the default:
/// implicit Euler) or Trapezoidal, the force -stiffness (e_+ + 2 e_0 +
/// e_-) / 4 over a substep, e = s - target (the trapezoidal rule: an
/// undamped spring keeps its energy at any stiffness and substep).
struct PrismaticDrive {
  enum class Mode { None, Velocity, Position };
  enum class Integration { Implicit, Trapezoidal };
  Mode mode = Mode::None;
  double target = 0.0;     // m/s (Velocity) or m (Position)
  double max_force = 0.0;  // N; <= 0 or infinity: unlimited
  double stiffness = 0.0;  // N/m, finite; 0: rigid (Position only)
  double damping = 0.0;    // N s/m, finite; a Position drive's only with stiffness > 0
  Integration integration = Integration::Implicit;  // of a spring (stiffness > 0)
  // s, > 0: the drive acts until then and is removed, as a hinge's
  // (HingeDrive::until); infinity: always.
  double until = std::numeric_limits<double>::infinity();
  // Non-empty: `target` follows this schedule, as a hinge drive's
  // (HingeDrive::schedule).
  std::vector<DriveKeyframe> schedule = {};

  /// A spring integrated by the trapezoidal rule.
  bool isTrapezoidalSpring() const {
    return mode == Mode::Position && stiffness > 0.0 && integration == Integration::Trapezoidal;
  }
};

/// A prismatic joint between `body` (a) and `other` (b; kWorldBody: the
/// fixed world frame), given in world space at the moment it is added. Its
/// slide is the displacement (m) of a's anchor point relative to b's along
/// `axis`, 0 when added; the axis turns with b.
struct PrismaticDef {
  BodyId body = 0;
  BodyId other = kWorldBody;
  Vec3 anchor = Vec3::Zero();  // m, world: a point on the rail, fixed in both bodies
  Vec3 axis = Vec3::UnitX();   // world, normalized on use: the rail direction
  double compliance = 0.0;     // m/N across the rail, rad/(N m) for the orientation
  JointLimit limit;            // m; rigid
  PrismaticDrive drive;
};

/// Solver form of a prismatic joint.
struct PrismaticJoint {
  BodyId a = 0, b = kWorldBody;
  Vec3 anchor_a = Vec3::Zero(), anchor_b = Vec3::Zero();  // m, local
  Vec3 axis_b = Vec3::UnitX();                             // local to b
  Quat rel = Quat::Identity();  // q_b^-1 q_a at creation, kept
  double compliance = 0.0;
  JointLimit limit;
  PrismaticDrive drive;
  // Accumulated over this substep's sweeps: the limit and drive rows on the
  // slide; the impulse of all positional rows on body a at its anchor (kg
  // m) and the angular impulse of the orientation rows on a (kg m^2).
  JointCoordinate slide;
  Vec3 impulse_linear = Vec3::Zero();
  Vec3 impulse_angular = Vec3::Zero();
  // A trapezoidal spring's slide at the start of the previous substep (m;
  // NaN before the first).
  double spring_previous = std::numeric_limits<double>::quiet_NaN();
};

/// Converts `def` to body-local form from the current poses of a and b.
PrismaticJoint makePrismaticJoint(const PrismaticDef& def, const BodyState& a,
                                  const BodyState& b);

/// Starts a substep of `h` s, after integration: clears the lambdas and
/// impulses and sets up the drive from the poses at the start of the
/// substep (x_prev, q_prev). A capped position drive brakes in time for
/// `braking_inverse_mass` (1 / kg: World::brakingInverseMass).
void preparePrismaticJoint(PrismaticJoint& joint, const BodyState& a, const BodyState& b,
                           double h, double braking_inverse_mass);

/// One Gauss-Seidel visit over a substep of `h` s: the orientation and
/// cross-rail rows (alpha~ = compliance / h^2) as one block, solved together
/// with each active drive and limit row on the slide in turn (clamped;
/// rigid, but a spring's drive row, as a hinge's).
void solvePrismaticJoint(PrismaticJoint& joint, BodyState& a, BodyState& b, double h);

/// Slide (m) of a relative to b along the axis from poses x_a, q_a, x_b,
/// q_b: (p_a - p_b) . u, p the anchors and u the axis, world.
double prismaticSlide(const PrismaticJoint& joint, const Vec3& x_a, const Quat& q_a,
                      const Vec3& x_b, const Quat& q_b);

/// Force and torque the joint exerted on body a over the last substep of
/// `h` s (JointWrench).
JointWrench prismaticWrench(const PrismaticJoint& joint, double h);

}  // namespace reeve
