#include "reeve/engine/hinge_joint.h"

#include <cmath>

#include "reeve/engine/correction.h"

namespace reeve {

HingeJoint makeHingeJoint(const HingeDef& def, const BodyState& a, const BodyState& b) {
  HingeJoint j;
  j.a = def.body;
  j.b = def.other;
  j.anchor_a = a.toLocal(def.anchor);
  j.anchor_b = b.toLocal(def.anchor);
  const Vec3 axis = def.axis.normalized();
  j.axis_a = a.q.conjugate() * axis;
  j.axis_b = b.q.conjugate() * axis;
  j.compliance = def.compliance;
  return j;
}

void solveHingeJoint(HingeJoint& j, BodyState& a, BodyState& b, double alpha_tilde) {
  // Axis row: C = angle(axis_a, axis_b), n = axis_a x axis_b / |.|; turning
  // b about +n opens the angle, so dC/dtheta_b = n.
  {
    const Vec3 u = a.q * j.axis_a;
    const Vec3 v = b.q * j.axis_b;
    const Vec3 cross = u.cross(v);
    const double s = cross.norm();
    if (s > 1e-12) {
      const Vec3 n = cross / s;
      const double C = std::atan2(s, u.dot(v));
      const double dl = angularDeltaLambda(a, b, n, C, alpha_tilde, j.lambda_axis);
      j.lambda_axis += dl;
      j.impulse_axis -= dl * n;
      applyAngularImpulse(a, b, dl * n);
    }
  }
  // Point row: C = |p_b - p_a|, n = (p_b - p_a) / C.
  const Vec3 r_a = a.q * j.anchor_a;
  const Vec3 r_b = b.q * j.anchor_b;
  const Vec3 d = (b.x + r_b) - (a.x + r_a);
  const double C = d.norm();
  if (C > 1e-15) {
    const Vec3 n = d / C;
    const double dl = positionalDeltaLambda(a, b, r_a, r_b, n, C, alpha_tilde, j.lambda_point);
    j.lambda_point += dl;
    j.impulse_point -= dl * n;
    applyPositionalImpulse(a, b, r_a, r_b, dl * n);
  }
}

}  // namespace reeve
