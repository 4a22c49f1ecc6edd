// Contacts: a non-penetration row, static friction as a positional row on
// the tangential motion, and the velocity pass with dynamic friction and
// restitution (Müller, Macklin, Chentanez, Jeschke, Kim, "Detailed Rigid
// Body Simulation with Extended Position Based Dynamics", SCA 2020, sec.
// 3.5 and Alg. 2 lines 20-24).
//
// Sign convention (correction.h): the normal n is the gradient of the
// separation with respect to body b; it points from a into b and pushes b
// away from a. The ground is body a = kWorldBody.
#pragma once

#include "reeve/engine/body.h"

namespace reeve {

/// One contact point, made fresh each substep by the narrow phase
/// (collide.h) after integration, so its lambdas are those of one substep.
struct Contact {
  BodyId a = kWorldBody, b = 0;
  Vec3 local_a = Vec3::Zero();  // m, body-local point of a's surface (world point for the ground)
  Vec3 local_b = Vec3::Zero();  // m, body-local point of b's surface
  Vec3 normal = Vec3::UnitY();  // world, unit, from a into b
  double static_friction = 0.0;   // mu_s, combined (contact_material.h)
  double dynamic_friction = 0.0;  // mu_d
  double restitution = 0.0;       // e
  /// n . (v_b - v_a) at the contact point (m/s) when the contact was found,
  /// after integration and before the position solve: SCA 2020's v~_n.
  double normal_speed_before = 0.0;
  double lambda_n = 0.0;  // kg m, >= 0: accumulated normal correction this substep
  double lambda_t = 0.0;  // kg m, >= 0: accumulated static friction correction
};

/// The contact points one narrow-phase call found between two bodies,
/// `count` consecutive entries from `first` of the contact list; they share
/// a normal, a material and one static friction bound.
struct ContactManifold {
  int first = 0, count = 0;
  /// Sum of the static friction corrections (kg m, world, normal to n) of
  /// all points this substep: the manifold's friction, whose size static
  /// friction may not push past mu_s x sum of lambda_n.
  Vec3 friction_impulse = Vec3::Zero();
};

/// Most sweeps over a manifold's normal rows, and over its friction rows,
/// in one visit; a visit stops sweeping early once no row moves more than
/// 1e-12 m.
inline constexpr int kManifoldSweeps = 8;

/// One Gauss-Seidel visit of a manifold's positional rows (SCA 2020, sec.
/// 3.5, eq. 26-27): up to kManifoldSweeps sweeps over the normal rows of
/// its points, then as many over their static friction rows. (One sweep
/// per visit leaves a box tilted toward the corner solved last, and it
/// walks: 1.4 mm and 2.4 mrad in 10 s at 10 substeps and 2 iterations.)
///   normal:   C = (p_b - p_a) . n  (m); solved only while C < 0, with zero
///             compliance; lambda_n accumulates >= 0.
///   friction: dp = (p_b - p_b_prev) - (p_a - p_a_prev), dp_t its part
///             normal to n, C = |dp_t|, gradient dp_t / |dp_t|; applied only
///             while |friction_impulse + dlambda_t dp_t/|dp_t|| <= mu_s x
///             (sum of its points' lambda_n), otherwise left to the
///             velocity pass.
/// p_prev are a point's body-local arms at the poses before this substep's
/// integration (x_prev, q_prev). The bound is on the manifold, not
/// kept per point as in the paper: Gauss-Seidel lets the first point of a
/// box's face hold the whole box, which a per-point budget (a quarter of
/// the weight at each corner) would refuse, so a box on an incline slid
/// below the friction angle. It bounds the net tangential impulse, so
/// corrections that only turn the body about n (and cancel in the sum) do
/// not use it up. All points of a manifold share one material.
void solveContactPositions(ContactManifold& m, Contact* contacts, BodyState& a, BodyState& b);

/// The velocity pass of one manifold (SCA 2020, eq. 29-34), after the
/// velocities were read from the positions. With v = (v_b + w_b x r_b) -
/// (v_a + w_a x r_a), v_n = n . v, v_t = v - n v_n and w_n, w_t the
/// generalized inverse masses (correction.h) along n and v_t:
///   restitution, per point: impulse n (-v_n + max(-e v~_n, 0)) / w_n,
///     with e = 0 when |v~_n| <= `rest_speed` (SCA 2020 use 2 |g| h, so
///     that resting contacts do not jitter);
///   dynamic friction, once at the centre of pressure (points weighted by
///     lambda_n): impulse -v_t/|v_t| min(mu_d lambda_n / h, |v_t| / w_t),
///     lambda_n of the whole manifold (mu_d |f_n| h, f_n = lambda_n / h^2).
/// The paper bounds the velocity change by h mu_d |f_n| instead of the
/// impulse, and per point; at box corners, where w_t > 1/m, that braked
/// with less than mu_d |f_n| (a box on an incline slid 6-15 % too fast),
/// and corner by corner it yawed a sliding box. Points whose normal row
/// never acted this substep (lambda_n = 0) are skipped.
void solveContactVelocities(const ContactManifold& m, const Contact* contacts, BodyState& a,
                            BodyState& b, double h, double rest_speed);

/// Normal force (N) of a contact over its substep h (s): lambda_n / h^2, on b along n.
inline double contactNormalForce(const Contact& c, double h) { return c.lambda_n / (h * h); }

}  // namespace reeve
