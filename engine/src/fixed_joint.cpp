#include "reeve/engine/fixed_joint.h"

#include "joint_row_sets.h"

namespace reeve {
namespace {

// Adds the six rows (solveFixedJoint) at arms r_a, r_b to `rows`.
void addBilateralRows(const FixedJoint& j, const BodyState& a, const BodyState& b, const Vec3& r_a, const Vec3& r_b,
                      joint_rows::BilateralRows& rows) {
  const Vec3 phi = rotationVector(a.q * (b.q * j.rel).conjugate());
  rows.addPoint((b.x + r_b) - (a.x + r_a));
  for (int i = 0; i < 3; ++i) rows.addAngular(Vec3::Unit(i), phi[i]);
}

}  // namespace

FixedJoint makeFixedJoint(const FixedDef& def, const BodyState& a, const BodyState& b) {
  FixedJoint j;
  j.a = def.body;
  j.b = def.other;
  j.anchor_a = a.toLocal(def.anchor);
  j.anchor_b = b.toLocal(def.anchor);
  j.rel = (b.q.conjugate() * a.q).normalized();
  j.compliance = def.compliance;
  return j;
}

void prepareFixedJoint(FixedJoint& j) {
  j.impulse_linear.setZero();
  j.impulse_angular.setZero();
}

void solveFixedJoint(FixedJoint& j, BodyState& a, BodyState& b, double h) {
  // Six compliant rows as one block (joint_rows.h, joint_rows::solveRows):
  //   point (3): C_p = p_b - p_a;
  //   orientation (3): C = phi, the rotation vector of the error rotation
  //     q_a (q_b rel)^-1 (rotating a about +phi grows it, b shrinks it).
  const Vec3 r_a = a.q * j.anchor_a, r_b = b.q * j.anchor_b;
  joint_rows::BilateralRows rows;
  addBilateralRows(j, a, b, r_a, r_b, rows);
  joint_rows::solveRows(a, b, r_a, r_b, rows, j.compliance / (h * h), nullptr, j.impulse_linear, j.impulse_angular);
}

void joint_rows::fixedRowSet(FixedJoint& j, const BodyState& a, const BodyState& b, JointRowSet& out) {
  const Vec3 r_a = a.q * j.anchor_a, r_b = b.q * j.anchor_b;
  out.start(r_a, r_b);
  addBilateralRows(j, a, b, r_a, r_b, out.bilateral);
}

JointWrench fixedWrench(const FixedJoint& j, double h) {
  if (!(h > 0.0)) return {};
  return {j.impulse_linear / (h * h), j.impulse_angular / (h * h)};
}

}  // namespace reeve
