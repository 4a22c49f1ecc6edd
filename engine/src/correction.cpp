#include "reeve/engine/correction.h"

namespace reeve {
namespace {

// I^-1 v, or 0 for a body nothing moves (static or kinematic: its inverse
// inertia is 0), without its two rotations: the ground under every
// contact.
Vec3 turnOf(const BodyState& body, const Vec3& v) { return body.moves() ? body.applyInvInertia(v) : Vec3::Zero(); }

}  // namespace

double generalizedInverseMass(const BodyState& body, const Vec3& r, const Vec3& n) {
  if (!body.moves()) return body.inv_mass;
  const Vec3 rn = r.cross(n);
  return body.inv_mass + rn.dot(body.applyInvInertia(rn));
}

double positionalDeltaLambda(const BodyState& a, const BodyState& b, const Vec3& r_a,
                             const Vec3& r_b, const Vec3& n, double C,
                             double alpha_tilde, double lambda) {
  const double w = generalizedInverseMass(a, r_a, n) + generalizedInverseMass(b, r_b, n);
  const double denom = w + alpha_tilde;
  return denom > 0.0 ? (-C - alpha_tilde * lambda) / denom : 0.0;
}

void applyPositionalImpulse(BodyState& a, BodyState& b, const Vec3& r_a, const Vec3& r_b,
                            const Vec3& P, double scale_a, double scale_b) {
  const Vec3 turn_b = scale_b * turnOf(b, r_b.cross(P)), turn_a = -scale_a * turnOf(a, r_a.cross(P));
  if (b.takesImpulses()) {
    b.x += P * b.inv_mass;
    rotateBy(b.q, turn_b);
    b.impulse += P;
    b.angular_impulse += r_b.cross(P);
    b.solve_turn += turn_b;
  }
  if (a.takesImpulses()) {
    a.x -= P * a.inv_mass;
    rotateBy(a.q, turn_a);
    a.impulse -= P;
    a.angular_impulse -= r_a.cross(P);
    a.solve_turn += turn_a;
  }
}

double angularDeltaLambda(const BodyState& a, const BodyState& b, const Vec3& n, double C,
                          double alpha_tilde, double lambda) {
  const double w = n.dot(turnOf(a, n)) + n.dot(turnOf(b, n));
  const double denom = w + alpha_tilde;
  return denom > 0.0 ? (-C - alpha_tilde * lambda) / denom : 0.0;
}

void applyAngularImpulse(BodyState& a, BodyState& b, const Vec3& P) {
  const Vec3 turn_b = turnOf(b, P), turn_a = -turnOf(a, P);
  if (b.takesImpulses()) {
    rotateBy(b.q, turn_b);
    b.angular_impulse += P;
    b.solve_turn += turn_b;
  }
  if (a.takesImpulses()) {
    rotateBy(a.q, turn_a);
    a.angular_impulse -= P;
    a.solve_turn += turn_a;
  }
}

Eigen::Matrix3d inverseInertiaWorld(const BodyState& body) {
  const Eigen::Matrix3d R = body.q.toRotationMatrix();
  return R * body.inv_inertia * R.transpose();
}

namespace {

Eigen::Matrix3d cross(const Vec3& r) {
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

}  // namespace

Eigen::Matrix3d pointInverseMass(const BodyState& a, const BodyState& b, const Vec3& r_a,
                                 const Vec3& r_b) {
  const Eigen::Matrix3d ra = cross(r_a), rb = cross(r_b);
  return (a.inv_mass + b.inv_mass) * Eigen::Matrix3d::Identity() -
         ra * inverseInertiaWorld(a) * ra - rb * inverseInertiaWorld(b) * rb;
}

Eigen::Matrix3d angularInverseMass(const BodyState& a, const BodyState& b) {
  return inverseInertiaWorld(a) + inverseInertiaWorld(b);
}

}  // namespace reeve
