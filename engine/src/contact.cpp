#include "reeve/engine/contact.h"

#include <algorithm>
#include <cmath>

#include "reeve/engine/contact_material.h"
#include "reeve/engine/correction.h"

namespace reeve {

bool isValid(const ContactMaterial& m) {
  return std::isfinite(m.static_friction) && m.static_friction >= 0.0 &&
         std::isfinite(m.dynamic_friction) && m.dynamic_friction >= 0.0 &&
         m.restitution >= 0.0 && m.restitution <= 1.0;
}

void solveContactPositions(ContactManifold& m, Contact* contacts, BodyState& a, BodyState& b) {
  constexpr double kSettled = 1e-12;  // m: a sweep moving no row more than this ends the visit
  const int end = m.first + m.count;
  for (int sweep = 0; sweep < kManifoldSweeps; ++sweep) {
    double largest = 0.0;
    for (int i = m.first; i < end; ++i) {
      // Normal row: C = (p_b - p_a) . n, dC/dp_b = n; unilateral (C < 0 only).
      Contact& c = contacts[i];
      const Vec3 r_a = a.q * c.local_a, r_b = b.q * c.local_b;
      const double C = ((b.x + r_b) - (a.x + r_a)).dot(c.normal);
      if (C >= 0.0) continue;
      const double dl = positionalDeltaLambda(a, b, r_a, r_b, c.normal, C, 0.0, c.lambda_n);
      if (!(dl > 0.0)) continue;
      c.lambda_n += dl;
      applyPositionalImpulse(a, b, r_a, r_b, dl * c.normal);
      largest = std::max(largest, -C);
    }
    if (largest <= kSettled) break;
  }
  double lambda_n = 0.0;  // of the whole manifold
  for (int i = m.first; i < end; ++i) lambda_n += contacts[i].lambda_n;
  if (lambda_n <= 0.0) return;
  // Static friction holds for the manifold as a whole or not at all: if the
  // sweeps need more than mu_s lambda_n, the poses are put back as they were.
  const Vec3 xa = a.x, xb = b.x, friction_before = m.friction_impulse;
  const Quat qa = a.q, qb = b.q;
  const double mu_s = contacts[m.first].static_friction;
  for (int sweep = 0; sweep < kManifoldSweeps; ++sweep) {
    double largest = 0.0;
    for (int i = m.first; i < end; ++i) {
      // Static friction row: C = |dp_t|, gradient dp_t / |dp_t| wrt b.
      Contact& c = contacts[i];
      if (c.lambda_n <= 0.0) continue;
      const Vec3 r_a = a.q * c.local_a, r_b = b.q * c.local_b;
      const Vec3 dp = ((b.x + r_b) - (b.x_prev + b.q_prev * c.local_b)) -
                      ((a.x + r_a) - (a.x_prev + a.q_prev * c.local_a));
      const Vec3 dp_t = dp - c.normal * c.normal.dot(dp);
      const double len = dp_t.norm();
      if (len <= kSettled) continue;
      const Vec3 t = dp_t / len;
      const Vec3 P = positionalDeltaLambda(a, b, r_a, r_b, t, len, 0.0, 0.0) * t;
      m.friction_impulse += P;
      c.lambda_t += P.norm();
      applyPositionalImpulse(a, b, r_a, r_b, P);
      largest = std::max(largest, len);
    }
    if (largest <= kSettled) break;
  }
  if (m.friction_impulse.norm() > mu_s * lambda_n) {  // sliding
    a.x = xa;
    a.q = qa;
    b.x = xb;
    b.q = qb;
    m.friction_impulse = friction_before;
    for (int i = m.first; i < end; ++i) contacts[i].lambda_t = 0.0;
  }
}

namespace {

/// Velocity change of a point impulse p (kg m/s) on b at r_b and -p on a at r_a.
void applyVelocityImpulse(BodyState& a, BodyState& b, const Vec3& r_a, const Vec3& r_b,
                          const Vec3& p) {
  b.v += p * b.inv_mass;
  b.omega += b.applyInvInertia(r_b.cross(p));
  a.v -= p * a.inv_mass;
  a.omega -= a.applyInvInertia(r_a.cross(p));
}

double inverseMassAlong(const BodyState& a, const BodyState& b, const Vec3& r_a, const Vec3& r_b,
                        const Vec3& dir) {
  return generalizedInverseMass(a, r_a, dir) + generalizedInverseMass(b, r_b, dir);
}

}  // namespace

void solveContactVelocities(const ContactManifold& m, const Contact* contacts, BodyState& a,
                            BodyState& b, double h, double rest_speed) {
  const int end = m.first + m.count;
  double lambda_n = 0.0;
  Vec3 local_a = Vec3::Zero(), local_b = Vec3::Zero();  // centre of pressure, body-local
  for (int i = m.first; i < end; ++i) {
    // Restitution (eq. 34), per point; e = 0 for slow contacts.
    const Contact& c = contacts[i];
    if (c.lambda_n <= 0.0) continue;
    lambda_n += c.lambda_n;
    local_a += c.lambda_n * c.local_a;
    local_b += c.lambda_n * c.local_b;
    const Vec3 r_a = a.q * c.local_a, r_b = b.q * c.local_b;
    const Vec3& n = c.normal;
    const Vec3 v = (b.v + b.omega.cross(r_b)) - (a.v + a.omega.cross(r_a));
    const double e = std::abs(c.normal_speed_before) <= rest_speed ? 0.0 : c.restitution;
    const double dvn = -n.dot(v) + std::max(-e * c.normal_speed_before, 0.0);
    if (const double w = inverseMassAlong(a, b, r_a, r_b, n); w > 0.0 && dvn != 0.0)
      applyVelocityImpulse(a, b, r_a, r_b, n * (dvn / w));
  }
  if (lambda_n <= 0.0) return;
  // Dynamic friction (eq. 30) at the centre of pressure, bounded in
  // impulse: mu_d |f_n| h = mu_d lambda_n / h.
  const Contact& c = contacts[m.first];
  const Vec3 r_a = a.q * (local_a / lambda_n), r_b = b.q * (local_b / lambda_n);
  const Vec3 v = (b.v + b.omega.cross(r_b)) - (a.v + a.omega.cross(r_a));
  const Vec3 vt = v - c.normal * c.normal.dot(v);
  const double vt_len = vt.norm();
  if (vt_len < 1e-15) return;
  const Vec3 t = vt / vt_len;
  const double w = inverseMassAlong(a, b, r_a, r_b, t);
  if (!(w > 0.0)) return;
  applyVelocityImpulse(a, b, r_a, r_b, -t * std::min(c.dynamic_friction * lambda_n / h, vt_len / w));
}

}  // namespace reeve
