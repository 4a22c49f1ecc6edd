#include "reeve/engine/prismatic_joint.h"

#include <cmath>

#include "joint_row_sets.h"

namespace reeve {
namespace {

joint_rows::DriveKind kindOf(PrismaticDrive::Mode mode) {
  switch (mode) {
    case PrismaticDrive::Mode::Velocity: return joint_rows::DriveKind::Velocity;
    case PrismaticDrive::Mode::Position: return joint_rows::DriveKind::Position;
    case PrismaticDrive::Mode::None: break;
  }
  return joint_rows::DriveKind::None;
}

// The arm on the rail b at which its rows act: to the point of b under a's
// anchor, where the rail holds the slider, not to b's own anchor. The rows
// C = t . (p_b - p_a) and s = (p_a - p_b) . u turn with b, so their
// gradient on b's rotation is (p_a - x_b) x t (Box2D's d + r_A). At b's
// anchor a slider s metres along applied its reaction s metres off, a
// torque that worked on the rail: a bead on a swinging rod gained energy
// as it slid out, and blew up (1e8 J) within half a second.
Vec3 railArm(const BodyState& a, const BodyState& b, const Vec3& r_a) { return a.x + r_a - b.x; }

// Adds the rail and orientation rows (solvePrismaticJoint) at arms r_a,
// r_b to `rows`.
void addBilateralRows(const PrismaticJoint& j, const BodyState& a, const BodyState& b, const Vec3& r_a,
                      const Vec3& r_b, joint_rows::BilateralRows& rows) {
  const Vec3 u = b.q * j.axis_b;
  const Vec3 t1 = joint_rows::anyPerpendicular(u), t2 = u.cross(t1);
  const Vec3 separation = (b.x + r_b) - (a.x + r_a);
  const Vec3 phi = rotationVector(a.q * (b.q * j.rel).conjugate());
  rows.addPositional(t1, t1.dot(separation));
  rows.addPositional(t2, t2.dot(separation));
  for (int i = 0; i < 3; ++i) rows.addAngular(Vec3::Unit(i), phi[i]);
}

}  // namespace

PrismaticJoint makePrismaticJoint(const PrismaticDef& def, const BodyState& a,
                                  const BodyState& b) {
  PrismaticJoint j;
  j.a = def.body;
  j.b = def.other;
  j.anchor_a = a.toLocal(def.anchor);
  j.anchor_b = b.toLocal(def.anchor);
  j.axis_b = b.q.conjugate() * def.axis.normalized();
  j.rel = (b.q.conjugate() * a.q).normalized();
  j.compliance = def.compliance;
  j.limit = def.limit;
  j.drive = def.drive;
  return j;
}

double prismaticSlide(const PrismaticJoint& j, const Vec3& x_a, const Quat& q_a, const Vec3& x_b,
                      const Quat& q_b) {
  const Vec3 d = (x_a + q_a * j.anchor_a) - (x_b + q_b * j.anchor_b);
  return d.dot(q_b * j.axis_b);
}

void preparePrismaticJoint(PrismaticJoint& j, const BodyState& a, const BodyState& b, double h,
                           double braking_inverse_mass) {
  j.impulse_linear.setZero();
  j.impulse_angular.setZero();
  joint_rows::DriveSpec drive{kindOf(j.drive.mode), j.drive.target, j.drive.max_force, j.drive.stiffness,
                              j.drive.damping};
  if (drive.kind == joint_rows::DriveKind::None) {
    joint_rows::prepareCoordinate(j.slide, drive, 0.0, 0.0, h);
    return;
  }
  const double start = prismaticSlide(j, a.x_prev, a.q_prev, b.x_prev, b.q_prev);
  if (j.drive.isTrapezoidalSpring()) {
    // The trapezoidal rule, as a hinge's (prepareHingeJoint). Before the
    // first substep e_- = e_0 - h ds/dt, ds/dt of the anchors' separation
    // d along the axis u (which turns with b): (v_pa - v_pb) . u + d . (w_b x u).
    const double e0 = start - j.drive.target;
    double e_minus = j.spring_previous - j.drive.target;
    if (std::isnan(j.spring_previous)) {
      const Vec3 u = b.q_prev * j.axis_b;
      const Vec3 r_a = a.q_prev * j.anchor_a, r_b = b.q_prev * j.anchor_b;
      const Vec3 d = (a.x_prev + r_a) - (b.x_prev + r_b);
      const double rate = ((a.v + a.omega.cross(r_a)) - (b.v + b.omega.cross(r_b))).dot(u) + d.dot(b.omega.cross(u));
      e_minus = e0 - h * rate;
    }
    j.spring_previous = start;
    drive.stiffness *= 0.25;
    drive.error_offset = 2.0 * e0 + e_minus;
  }
  joint_rows::prepareCoordinate(j.slide, drive, start, braking_inverse_mass, h);
}

void solvePrismaticJoint(PrismaticJoint& j, BodyState& a, BodyState& b, double h) {
  // Rows (joint_rows.h: positional C_p = p_b - p_a, angular = rotation of a
  // relative to b), u = q_b axis_b, T = [t1 t2] normal to u:
  //   across the rail (2, compliant): C = T^T (p_b - p_a);
  //   orientation (3, compliant): C = phi, the rotation vector of the
  //     error rotation q_a (q_b rel)^-1;
  //   slide (at most one at a time, rigid, clamped), s = (p_a - p_b) . u
  //   (prismaticSlide), positional direction -u: lambda > 0 pushes a along
  //   +u (force lambda u / h^2 on a), in order:
  //     drive, velocity: C = (s - s_0) - v* h, s_0 the slide at the start
  //       of the substep (from x_prev, q_prev): afterwards a moved v* h
  //       relative to b over the substep, a velocity of v*;
  //     drive, position: v* h replaced by the step toward the target that
  //       max_force can still stop (joint_rows::prepareCoordinate);
  //     drive, spring (position drive with stiffness k, damping c): v* h
  //       replaced by (target - s_0) k / (k + c / h), compliant with
  //       alpha~ = 1 / ((k + c / h) h^2) (as a hinge's spring): met, the
  //       force lambda / h^2 is -k (s - target) - c (s - s_0) / h;
  //       |lambda_drive| <= max_force h^2 for every drive;
  //     lower limit: C = s - lower, lambda >= 0; upper: C = s - upper,
  //       lambda <= 0; each only while violated or already pushing.
  // Each slide row is solved with the five locked rows as one block
  // (joint_rows::solveRows); with no slide row active, the block alone.
  const double alpha_tilde = j.compliance / (h * h);
  const auto block = [&](const joint_rows::ClampedRow* clamped) {
    const Vec3 r_a = a.q * j.anchor_a, r_b = b.q * j.anchor_b;
    joint_rows::BilateralRows rows;
    addBilateralRows(j, a, b, r_a, r_b, rows);
    joint_rows::solveRows(a, b, r_a, railArm(a, b, r_a), rows, alpha_tilde, clamped, j.impulse_linear,
                          j.impulse_angular);
  };
  const bool driven = j.drive.mode != PrismaticDrive::Mode::None;
  bool solved = false;
  if (driven || j.limit.enabled) {
    const auto value = [&] { return prismaticSlide(j, a.x, a.q, b.x, b.q); };
    const auto row = [&](double C, double alpha, double lo, double hi, double& lambda) {
      joint_rows::ClampedRow clamped;
      clamped.dir.head<3>() = -(b.q * j.axis_b);
      clamped.C = C;
      clamped.alpha = alpha;
      clamped.lo = lo;
      clamped.hi = hi;
      clamped.lambda = &lambda;
      block(&clamped);
    };
    solved = joint_rows::solveCoordinateRows(j.slide, j.limit, driven, false, value, [] { return 0.0; }, row);
  }
  if (!solved) block(nullptr);
}

void joint_rows::prismaticRowSet(PrismaticJoint& j, const BodyState& a, const BodyState& b, JointRowSet& out) {
  const Vec3 r_a = a.q * j.anchor_a, r_b = b.q * j.anchor_b;
  out.start(r_a, railArm(a, b, r_a));
  addBilateralRows(j, a, b, r_a, r_b, out.bilateral);
  Vec6 dir = Vec6::Zero();
  dir.head<3>() = -(b.q * j.axis_b);
  addCoordinateRows(j.slide, j.limit, j.drive.mode != PrismaticDrive::Mode::None, false,
                    prismaticSlide(j, a.x, a.q, b.x, b.q), 0.0, dir, out);
}

JointWrench prismaticWrench(const PrismaticJoint& j, double h) {
  if (!(h > 0.0)) return {};
  return {j.impulse_linear / (h * h), j.impulse_angular / (h * h)};
}

}  // namespace reeve
