#include "reeve/engine/hinge_joint.h"

#include <cmath>

#include "joint_row_sets.h"

namespace reeve {
namespace {

joint_rows::DriveKind kindOf(HingeDrive::Mode mode) {
  switch (mode) {
    case HingeDrive::Mode::Velocity: return joint_rows::DriveKind::Velocity;
    case HingeDrive::Mode::Angle: return joint_rows::DriveKind::Position;
    case HingeDrive::Mode::None: break;
  }
  return joint_rows::DriveKind::None;
}

// Adds the point and axis rows (solveHingeJoint) at arms r_a, r_b to
// `rows`.
void addBilateralRows(const HingeJoint& j, const BodyState& a, const BodyState& b, const Vec3& r_a, const Vec3& r_b,
                      joint_rows::BilateralRows& rows) {
  const Vec3 u = a.q * j.frame.axis_a;
  const Vec3 t1 = joint_rows::anyPerpendicular(u), t2 = u.cross(t1);
  const Vec3 phi = joint_rows::alignment(b.q * j.frame.axis_b, u);
  rows.addPoint((b.x + r_b) - (a.x + r_a));
  rows.addAngular(t1, t1.dot(phi));
  rows.addAngular(t2, t2.dot(phi));
}

// How far (rad) a has turned relative to b about the world axis `u` since
// the substep began, as their motion tells: the integration's h omega and
// the solve's turns (a hinge angle itself is known up to whole turns).
double turned(const BodyState& a, const BodyState& b, const Vec3& u, double h) {
  return u.dot(h * (a.omega - b.omega) + a.solve_turn - b.solve_turn);
}

}  // namespace

HingeJoint makeHingeJoint(const HingeDef& def, const BodyState& a, const BodyState& b) {
  HingeJoint j;
  j.a = def.body;
  j.b = def.other;
  j.frame = joint_rows::makeJointFrame(def.anchor, def.axis, a, b);
  j.compliance = def.compliance;
  j.limit = def.limit;
  j.drive = def.drive;
  return j;
}

double hingeAngle(const HingeJoint& j, const Quat& q_a, const Quat& q_b) {
  // The angle turning b's reference direction into a's about a's axis.
  return joint_rows::signedAngle(q_b * j.frame.ref_b, q_a * j.frame.ref_a, q_a * j.frame.axis_a);
}

void prepareHingeJoint(HingeJoint& j, const BodyState& a, const BodyState& b, double h,
                       double braking_inverse_inertia) {
  j.impulse_point.setZero();
  j.impulse_axis.setZero();
  joint_rows::DriveSpec drive{kindOf(j.drive.mode), j.drive.target, j.drive.max_torque, j.drive.stiffness,
                              j.drive.damping};
  if (drive.kind == joint_rows::DriveKind::None) {
    joint_rows::prepareCoordinate(j.angle, drive, 0.0, 0.0, h);
    return;
  }
  // The angle at the substep's start, through whole turns: a target of
  // 8 rad is 8 rad, not 8 - 2 pi.
  const double start = hingeAngleTotal(j, a.q_prev, b.q_prev);
  if (j.drive.isTrapezoidalSpring()) {
    // The trapezoidal rule: torque -k (e_+ + 2 e_0 + e_-) / 4 over the
    // substep, a row of stiffness k / 4 whose error is moved by the known
    // 2 e_0 + e_- (joint_rows::DriveSpec::error_offset). Before the first
    // substep, e_- from the bodies' relative spin.
    const double e0 = start - j.drive.target;
    const double e_minus = std::isnan(j.spring_previous) ? e0 - h * (a.q * j.frame.axis_a).dot(a.omega - b.omega)
                                                         : j.spring_previous - j.drive.target;
    j.spring_previous = start;
    drive.stiffness *= 0.25;
    drive.error_offset = 2.0 * e0 + e_minus;
  }
  joint_rows::prepareCoordinate(j.angle, drive, start, braking_inverse_inertia, h);
}

void solveHingeJoint(HingeJoint& j, BodyState& a, BodyState& b, double h) {
  // Rows (joint_rows.h: positional C_p = p_b - p_a, angular = rotation of a
  // relative to b), u = q_a axis_a, T = [t1 t2] normal to u:
  //   point (3, compliant):  C_p = p_b - p_a;
  //   axes (2, compliant):   C = T^T phi, phi = alignment(u_b, u_a), the
  //                          rotation turning b's axis into a's;
  //   angle (at most one at a time, rigid, clamped), theta = hingeAngle (a
  //   relative to b about u), direction u: lambda > 0 turns a about +u and
  //   pushes theta up (torque lambda u / h^2 on a), in order:
  //     drive, velocity: C = [theta - theta_0] - w* h, theta_0 the angle at
  //       the start of the substep (from q_prev), [.] wrapped to (-pi, pi]:
  //       afterwards a turned w* h relative to b over the substep, so the
  //       velocity read out, [theta - theta_0] / h, is w*;
  //     drive, angle: w* h replaced by the step toward the target that
  //       max_torque can still stop (joint_rows::prepareCoordinate);
  //     drive, spring (angle drive with stiffness k, damping c): w* h
  //       replaced by [target - theta_0] k / (k + c / h), compliant with
  //       alpha~ = 1 / ((k + c / h) h^2): XPBD's damped row (MIG 2016, eq.
  //       26) divided by 1 + gamma; met, the torque lambda / h^2 is
  //       -k (theta - target) - c (theta - theta_0) / h;
  //       |lambda_drive| <= max_torque h^2 for every drive, so the drive
  //       adds at most max_torque h of angular momentum per substep: a
  //       wheel spins up at max_torque / I;
  //     lower limit: C = theta - lower, lambda >= 0; upper: C = theta -
  //       upper, lambda <= 0; each only while violated or already pushing.
  // Each angle row is solved with the point and axis rows as one block
  // (joint_rows::solveRows), so it turns the bodies about the hinge, not
  // about their centres; with no angle row active, the block alone.
  // A rotor (body.h) turns about its axle alone: its point and axis rows
  // hold by construction, and only an angle row is solved.
  if (hingeSolvesNothing(j, a, b)) return;
  const bool rotor = a.isRotor() || b.isRotor();
  const bool driven = j.drive.mode != HingeDrive::Mode::None;
  const double alpha_tilde = j.compliance / (h * h);
  const auto block = [&](const joint_rows::ClampedRow* clamped) {
    const Vec3 r_a = a.q * j.frame.anchor_a, r_b = b.q * j.frame.anchor_b;
    joint_rows::BilateralRows rows;
    if (!rotor) addBilateralRows(j, a, b, r_a, r_b, rows);
    joint_rows::solveRows(a, b, r_a, r_b, rows, alpha_tilde, clamped, j.impulse_point, j.impulse_axis);
  };
  bool solved = false;
  if (driven || j.limit.enabled) {
    const auto value = [&] { return hingeAngle(j, a.q, b.q); };
    const auto turn = [&] { return turned(a, b, a.q * j.frame.axis_a, h); };
    const auto row = [&](double C, double alpha, double lo, double hi, double& lambda) {
      joint_rows::ClampedRow clamped;
      clamped.dir.tail<3>() = a.q * j.frame.axis_a;
      clamped.C = C;
      clamped.alpha = alpha;
      clamped.lo = lo;
      clamped.hi = hi;
      clamped.lambda = &lambda;
      block(&clamped);
    };
    solved = joint_rows::solveCoordinateRows(j.angle, j.limit, driven, true, value, turn, row);
  }
  if (!solved) block(nullptr);
}

void joint_rows::hingeRowSet(HingeJoint& j, const BodyState& a, const BodyState& b, double h, JointRowSet& out) {
  const Vec3 r_a = a.q * j.frame.anchor_a, r_b = b.q * j.frame.anchor_b;
  const bool rotor = a.isRotor() || b.isRotor();
  out.start(r_a, r_b);
  if (!rotor) addBilateralRows(j, a, b, r_a, r_b, out.bilateral);
  Vec6 dir = Vec6::Zero();
  dir.tail<3>() = a.q * j.frame.axis_a;
  addCoordinateRows(j.angle, j.limit, j.drive.mode != HingeDrive::Mode::None, true, hingeAngle(j, a.q, b.q),
                    turned(a, b, dir.tail<3>(), h), dir, out);
}

double hingeAngleTotal(const HingeJoint& j, const Quat& q_a, const Quat& q_b) {
  return j.angle_total + wrapAngle(hingeAngle(j, q_a, q_b) - j.angle_total);
}

void trackHingeAngle(HingeJoint& j, const BodyState& a, const BodyState& b, double h) {
  const Scalars3 axis = rotated(a.q, j.frame.axis_a);  // in scalars: math.h
  const Vec3 spin = a.omega - b.omega;
  const double estimate = j.angle_total + h * (axis.x * spin.x() + axis.y * spin.y() + axis.z * spin.z());
  // An undamped rotor turned by exactly h omega about its axle: integrate()
  // turns it by h omega_0, the solve by what updateVelocities added to
  // omega_0. The poses would correct the estimate by rounding alone (2 ulp
  // of the angle on every shipped scene), for an atan2 a wheel and substep.
  const BodyState& rotor = a.isRotor() ? a : b;
  if (rotor.isRotor() && rotor.angular_damping == 0.0) {
    j.angle_total = estimate;
    return;
  }
  j.angle_total = estimate + wrapAngle(hingeAngle(j, a.q, b.q) - estimate);
}

JointWrench hingeWrench(const HingeJoint& j, double h) {
  if (!(h > 0.0)) return {};
  return {j.impulse_point / (h * h), j.impulse_axis / (h * h)};
}

}  // namespace reeve
