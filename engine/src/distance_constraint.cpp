#include "reeve/engine/distance_constraint.h"

#include <algorithm>

#include "reeve/engine/correction.h"

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
  if (c.unilateral) dl = std::min(c.lambda + dl, 0.0) - c.lambda;
  c.lambda += dl;
  applyPositionalImpulse(a, b, r_a, r_b, dl * n);
}

double currentLength(const DistanceConstraint& c, const BodyState& a, const BodyState& b) {
  return (b.toWorld(c.local_b) - a.toWorld(c.local_a)).norm();
}

double startLength(const DistanceConstraint& c, const BodyState& a, const BodyState& b) {
  return (b.toWorldAtSubstepStart(c.local_b) - a.toWorldAtSubstepStart(c.local_a)).norm();
}

}  // namespace reeve
