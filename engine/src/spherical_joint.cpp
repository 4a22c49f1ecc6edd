#include "reeve/engine/spherical_joint.h"

#include <cmath>

#include "joint_row_sets.h"

namespace reeve {
namespace {

// Mean of the two world twist axes, the axis the twist is measured about
// (SCA 2020, Appendix); a's axis when they are opposite.
Vec3 twistAxis(const Vec3& u_a, const Vec3& u_b) {
  const Vec3 sum = u_a + u_b;
  const double norm = sum.norm();
  return norm > 1e-9 ? Vec3(sum / norm) : u_a;
}

}  // namespace

SphericalJoint makeSphericalJoint(const SphericalDef& def, const BodyState& a,
                                  const BodyState& b) {
  SphericalJoint j;
  j.a = def.body;
  j.b = def.other;
  j.frame = joint_rows::makeJointFrame(def.anchor, def.axis, a, b);
  j.compliance = def.compliance;
  j.swing_limit = def.swing_limit;
  j.twist_limit = def.twist_limit;
  return j;
}

double swingAngle(const SphericalJoint& j, const Quat& q_a, const Quat& q_b) {
  const Vec3 u_a = q_a * j.frame.axis_a, u_b = q_b * j.frame.axis_b;
  return std::atan2(u_a.cross(u_b).norm(), u_a.dot(u_b));
}

double twistAngle(const SphericalJoint& j, const Quat& q_a, const Quat& q_b) {
  const Vec3 n = twistAxis(q_a * j.frame.axis_a, q_b * j.frame.axis_b);
  return joint_rows::signedAngle(q_b * j.frame.ref_b, q_a * j.frame.ref_a, n);
}

void prepareSphericalJoint(SphericalJoint& j) {
  j.lambda_swing = 0.0;
  j.twist.lambda_lower = j.twist.lambda_upper = j.twist.lambda_drive = 0.0;
  j.impulse_linear.setZero();
  j.impulse_angular.setZero();
}

void solveSphericalJoint(SphericalJoint& j, BodyState& a, BodyState& b, double h) {
  // Rows (joint_rows.h: positional C_p = p_b - p_a, angular = rotation of a
  // relative to b):
  //   point (3, compliant): C_p = p_b - p_a;
  //   swing limit (rigid, clamped): C = swing - max <= 0, swing = the angle
  //     between u_a = q_a axis_a and u_b = q_b axis_b; turning a about
  //     m = u_b x u_a / |.| opens it, so the direction is m and lambda <= 0;
  //   twist limits (rigid, clamped) about n = (u_a + u_b) / |.|, theta =
  //     twistAngle (a relative to b), direction n: lower: C = theta - lower,
  //     lambda >= 0; upper: C = theta - upper, lambda <= 0;
  //   each limit only while violated or already pushing, each solved with
  //   the point rows as one block (joint_rows::solveRows), so it turns the
  //   bodies about the ball, not about their centres.
  const double alpha_tilde = j.compliance / (h * h);
  const auto block = [&](const joint_rows::ClampedRow* clamped) {
    const Vec3 r_a = a.q * j.frame.anchor_a, r_b = b.q * j.frame.anchor_b;
    joint_rows::BilateralRows rows;
    rows.addPoint((b.x + r_b) - (a.x + r_a));
    joint_rows::solveRows(a, b, r_a, r_b, rows, alpha_tilde, clamped, j.impulse_linear,
                          j.impulse_angular);
  };
  const auto angular = [&](const Vec3& n, double C, double lo, double hi, double& lambda) {
    joint_rows::ClampedRow clamped;
    clamped.dir.tail<3>() = n;
    clamped.C = C;
    clamped.lo = lo;
    clamped.hi = hi;
    clamped.lambda = &lambda;
    block(&clamped);
  };
  bool solved = false;
  if (j.swing_limit.enabled) {
    const Vec3 u_a = a.q * j.frame.axis_a, u_b = b.q * j.frame.axis_b;
    const Vec3 m = u_b.cross(u_a);
    const double C = swingAngle(j, a.q, b.q) - j.swing_limit.max;
    if ((C > 0.0 || j.lambda_swing < 0.0) && m.norm() > 1e-12) {
      angular(m.normalized(), C, -joint_rows::kInf, 0.0, j.lambda_swing);
      solved = true;
    }
  }
  if (j.twist_limit.enabled) {
    const auto value = [&] { return twistAngle(j, a.q, b.q); };
    const auto row = [&](double C, double /*alpha: 0, no drive*/, double lo, double hi, double& lambda) {
      angular(twistAxis(a.q * j.frame.axis_a, b.q * j.frame.axis_b), C, lo, hi, lambda);
    };
    solved |= joint_rows::solveCoordinateRows(j.twist, j.twist_limit, false, true, value, [] { return 0.0; }, row);
  }
  if (!solved) block(nullptr);
}

void joint_rows::sphericalRowSet(SphericalJoint& j, const BodyState& a, const BodyState& b, JointRowSet& out) {
  const Vec3 r_a = a.q * j.frame.anchor_a, r_b = b.q * j.frame.anchor_b;
  out.start(r_a, r_b);
  out.bilateral.addPoint((b.x + r_b) - (a.x + r_a));
  const Vec3 u_a = a.q * j.frame.axis_a, u_b = b.q * j.frame.axis_b;
  if (j.swing_limit.enabled) {
    // As in solveSphericalJoint; with the axes aligned the row has no
    // direction and stays inactive.
    const Vec3 m = u_b.cross(u_a);
    const double C = swingAngle(j, a.q, b.q) - j.swing_limit.max;
    Vec6 dir = Vec6::Zero();
    if (m.norm() > 1e-12) dir.tail<3>() = m.normalized();
    out.addClamped(dir, C, 0.0, -kInf, 0.0, &j.lambda_swing, (C > 0.0 || j.lambda_swing < 0.0) && m.norm() > 1e-12);
  }
  Vec6 dir = Vec6::Zero();
  dir.tail<3>() = twistAxis(u_a, u_b);
  addCoordinateRows(j.twist, j.twist_limit, false, true, twistAngle(j, a.q, b.q), 0.0, dir, out);
}

JointWrench sphericalWrench(const SphericalJoint& j, double h) {
  if (!(h > 0.0)) return {};
  return {j.impulse_linear / (h * h), j.impulse_angular / (h * h)};
}

}  // namespace reeve
