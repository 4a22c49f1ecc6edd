#include "reeve/engine/distance_constraint.h"

#include <algorithm>

#include "reeve/engine/correction.h"
#include "line_up.h"

namespace reeve {

void solveDistanceConstraint(DistanceConstraint& c, BodyState& a, BodyState& b,
                             double alpha_tilde, double h) {
  // C = |p_b - p_a| - d,  n = dC/dp_b = (p_b - p_a) / |p_b - p_a|.
  if (!c.enabled) return;
  const Vec3 r_a = a.q * c.local_a;
  const Vec3 r_b = b.q * c.local_b;
  const Vec3 d = (b.x + r_b) - (a.x + r_a);
  const double len = d.norm();
  if (len < 1e-12) return;
  const double C = len - c.rest_length;
  if (c.unilateral && C <= 0.0 && c.lambda == 0.0) return;  // slack and never pulled
  const Vec3 n = d / len;
  const DampedRow row = dampedRow(C, alpha_tilde, alpha_tilde * h * c.damping, len - c.start_length);
  double dl = positionalDeltaLambda(a, b, r_a, r_b, n, row.C, row.alpha_tilde, c.lambda);
  // Each end turns at most to its line-up (line_up.h, as a cable span's).
  double s_a = 1.0, s_b = 1.0;
  const bool turns_a = a.takesImpulses() && a.moves(), turns_b = b.takesImpulses() && b.moves();
  if ((turns_a || turns_b) && dl != 0.0) {
    const double target = -row.C - row.alpha_tilde * c.lambda;
    double w_all = target / dl;  // w + alpha~
    const Vec3 t_a = -r_a.cross(n), t_b = r_b.cross(n);  // dC / d(turn) of each end
    const Vec3 per_a = turns_a ? a.applyInvInertia(t_a) : Vec3::Zero();  // its turn per unit lambda
    const Vec3 per_b = turns_b ? b.applyInvInertia(t_b) : Vec3::Zero();
    if (turns_a) capVisitTurn(r_a, n, per_a, t_a.dot(per_a), target, w_all, dl, s_a);
    if (turns_b) capVisitTurn(r_b, -n, per_b, t_b.dot(per_b), target, w_all, dl, s_b);
    if (turns_a && s_b < 1.0) capVisitTurn(r_a, n, per_a, t_a.dot(per_a), target, w_all, dl, s_a);
  }
  if (c.unilateral) dl = std::min(c.lambda + dl, 0.0) - c.lambda;
  c.lambda += dl;
  applyPositionalImpulse(a, b, r_a, r_b, dl * n, s_a, s_b);
}

double currentLength(const DistanceConstraint& c, const BodyState& a, const BodyState& b) {
  return (b.toWorld(c.local_b) - a.toWorld(c.local_a)).norm();
}

double startLength(const DistanceConstraint& c, const BodyState& a, const BodyState& b) {
  return (b.toWorldAtSubstepStart(c.local_b) - a.toWorldAtSubstepStart(c.local_a)).norm();
}

}  // namespace reeve
