// The scalar-row kernels every XPBD constraint is built from (Müller,
// Macklin, Chentanez, Jeschke, Kim, "Detailed Rigid Body Simulation with
// Extended Position Based Dynamics", SCA 2020, sec. 3.3).
//
// Sign convention for both kernels: C is the constraint value and n its unit
// gradient with respect to body b (dC/dx_b = n, dC/dx_a = -n for positions;
// the same for rotations). A correction P = dlambda * n is applied to b and
// -P to a. With C > 0 and zero compliance, dlambda < 0 and C is driven to 0.
// The force on b is lambda * n / h^2 (N), the torque lambda * n / h^2 (N m).
#pragma once

#include "reeve/engine/body.h"

namespace reeve {

/// w = 1/m + (r x n)^T I^-1 (r x n): inverse mass of `body` seen along unit
/// `n` at world-space arm `r` (m) from its centre (SCA 2020, eq. 2).
double generalizedInverseMass(const BodyState& body, const Vec3& r, const Vec3& n);

/// dlambda = (-C - alpha~ lambda) / (w_a + w_b + alpha~) for a positional
/// row (SCA 2020, eq. 4), alpha~ = compliance / h^2. `C` in m, arms in m.
double positionalDeltaLambda(const BodyState& a, const BodyState& b, const Vec3& r_a,
                             const Vec3& r_b, const Vec3& n, double C,
                             double alpha_tilde, double lambda);

/// A compliant row with XPBD damping (Macklin, Müller, Chentanez, "XPBD",
/// MIG 2016, eq. 25-26) folded into an undamped one: with gamma = alpha~
/// beta~ / h = alpha~ h beta (beta the damping coefficient, N s/m),
///   dlambda = (-C - alpha~ lambda - gamma dC) / ((1 + gamma) w + alpha~)
/// is the undamped row's update with C' = (C + gamma dC) / (1 + gamma) and
/// alpha~' = alpha~ / (1 + gamma); dC (m) is the change of the row's value
/// since the substep began, grad C . (x - x_prev). The row then meets
/// C / alpha + beta dC / h = tension: a spring and a dashpot side by side.
struct DampedRow {
  double C = 0.0;            ///< C', m
  double alpha_tilde = 0.0;  ///< alpha~', 1/kg
};
inline DampedRow dampedRow(double C, double alpha_tilde, double gamma, double dC) {
  return {(C + gamma * dC) / (1.0 + gamma), alpha_tilde / (1.0 + gamma)};
}

/// Moves b by the positional impulse P (kg m) applied at arm r_b, and a by
/// -P at r_a: x += P/m, q += 1/2 [I^-1 (r x P), 0] q (SCA 2020, eq. 6-9);
/// adds P, r x P and the turn to the bodies' impulse, angular_impulse and
/// solve_turn (body.h). `scale_a`, `scale_b` (<= 1) scale each body's turn
/// alone, where a visit stiffens it (DESIGN, "A light crank").
void applyPositionalImpulse(BodyState& a, BodyState& b, const Vec3& r_a, const Vec3& r_b,
                            const Vec3& P, double scale_a = 1.0, double scale_b = 1.0);

/// dlambda for an angular row: w = n^T I^-1 n per body (SCA 2020, eq.
/// 11-12). `C` in rad.
double angularDeltaLambda(const BodyState& a, const BodyState& b, const Vec3& n, double C,
                          double alpha_tilde, double lambda);

/// Rotates b by I_b^-1 P and a by -I_a^-1 P (SCA 2020, eq. 13-14); adds
/// +-P and the turns to their angular_impulse and solve_turn.
void applyAngularImpulse(BodyState& a, BodyState& b, const Vec3& P);

/// The 3x3 generalized inverse mass of a point constraint, SCA 2020 eq. 2
/// for all directions at once: an impulse P (kg m) on b at world arm r_b
/// and -P on a at r_a changes p_b - p_a by K P (m), with
/// K = (1/m_a + 1/m_b) 1 - [r_a]x I_a^-1 [r_a]x - [r_b]x I_b^-1 [r_b]x
/// (1/kg), symmetric positive semi-definite; n^T K n is the scalar w of
/// generalizedInverseMass along n.
Eigen::Matrix3d pointInverseMass(const BodyState& a, const BodyState& b, const Vec3& r_a,
                                 const Vec3& r_b);

/// I^-1 of `body` in world axes, R diag(1/I) R^T (1/(kg m^2)); 0 when static.
Eigen::Matrix3d inverseInertiaWorld(const BodyState& body);

/// The 3x3 angular counterpart, K = I_a^-1 + I_b^-1 (world, 1/(kg m^2)): an
/// angular impulse P on b and -P on a changes b's rotation relative to a
/// by K P (rad).
Eigen::Matrix3d angularInverseMass(const BodyState& a, const BodyState& b);

}  // namespace reeve
