// Small maths vocabulary shared by every Reeve module. Double precision
// throughout (DESIGN.md, XPBD core).
#pragma once

#include <cmath>
#include <numbers>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace reeve {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// The shortest rotation taking the direction of `from` to that of `to`
/// (neither zero): Eigen's Quaternion::FromTwoVectors, compiled once in
/// math.cpp (its antiparallel case is an SVD, seconds of compile time in
/// every file that instantiates it).
Quat rotationBetween(const Vec3& from, const Vec3& to);

/// A vector as three scalars, for kernels that go on in scalars (rotated).
struct Scalars3 {
  double x, y, z;
};

/// q v q^-1 for a unit q as Eigen's `q * v` takes it (uv = 2 q.vec x v,
/// then v + w uv + q.vec x uv: the same operations in the same order, the
/// same bits), as scalars. Eigen's stores its cross products a coefficient
/// at a time and adds them a pair at a time, a store-forwarding stall per
/// rotation: a quarter of trackHingeAngle's time and a fifth of
/// DirectSolver::prepare's on Hilbert3, whose frame at 1 x 10 this takes
/// from 153 to 142-146 us (with integrate's rotors; DESIGN, "Fifty-first
/// session"). Made a Vec3 and read by Eigen at once (BodyState::toLocal)
/// it gained nothing.
[[gnu::always_inline]] inline Scalars3 rotated(const Quat& q, const Vec3& v) {
  const double qx = q.x(), qy = q.y(), qz = q.z(), qw = q.w();
  double ux = qy * v.z() - qz * v.y(), uy = qz * v.x() - qx * v.z(), uz = qx * v.y() - qy * v.x();
  ux += ux;
  uy += uy;
  uz += uz;
  return {v.x() + qw * ux + (qy * uz - qz * uy), v.y() + qw * uy + (qz * ux - qx * uz),
          v.z() + qw * uz + (qx * uy - qy * ux)};
}

/// Rotates `q` by the small world-space rotation vector `dphi` (rad) and
/// renormalizes: q <- q + 1/2 [dphi, 0] q (Müller et al. 2020, eq. 8).
/// One division, not normalize()'s four: every solver kernel ends here.
inline void rotateBy(Quat& q, const Vec3& dphi) {
  const Quat dq(0.0, dphi.x(), dphi.y(), dphi.z());
  q.coeffs() += 0.5 * (dq * q).coeffs();
  q.coeffs() *= 1.0 / q.coeffs().norm();
}

/// Rotates `q` exactly by the world-space rotation vector `phi` (rad), with
/// the exponential map. Used where angles are not small, e.g. a fast wheel
/// over a substep: the first-order rotateBy() loses O(|phi|^3) per call,
/// which shows up as a spurious drag on spinning bodies.
inline void rotateExactly(Quat& q, const Vec3& phi) {
  const double angle2 = phi.squaredNorm();
  if (angle2 == 0.0) return;
  // sin(a/2) / a and cos(a/2); below a = 0.1 their Taylor series to the
  // a^8 term, exact in double precision (the next terms are under 1e-18),
  // and several times cheaper than sin and cos: solvers turn every body
  // by small angles many times per frame. In a^2, with the coefficients'
  // reciprocals: no square root or division before the normalization (a
  // call 18.6 -> 10.6 ns, DESIGN "Twenty-third session").
  double s, c;
  if (angle2 < 0.01) {
    const double x2 = 0.25 * angle2;  // (a/2)^2
    s = 0.5 * (1.0 - x2 * (1.0 / 6.0) *
                         (1.0 - x2 * (1.0 / 20.0) * (1.0 - x2 * (1.0 / 42.0) * (1.0 - x2 * (1.0 / 72.0)))));
    c = 1.0 - x2 * 0.5 * (1.0 - x2 * (1.0 / 12.0) * (1.0 - x2 * (1.0 / 30.0) * (1.0 - x2 * (1.0 / 56.0))));
  } else {
    const double angle = std::sqrt(angle2);
    s = std::sin(0.5 * angle) / angle;
    c = std::cos(0.5 * angle);
  }
  q = (Quat(c, s * phi.x(), s * phi.y(), s * phi.z()) * q).normalized();
}

/// `angle` (rad) wrapped to [-pi, pi]: remainder(angle, 2 pi), which is
/// the angle itself where |angle| <= pi (the quotient rounds to 0, a tie
/// to even), as a substep's turn almost always is: the same bits without
/// the library call.
inline double wrapAngle(double angle) {
  constexpr double kTurn = 2.0 * std::numbers::pi;
  return std::abs(angle) <= 0.5 * kTurn ? angle : std::remainder(angle, kTurn);
}

/// atan(t) / t for x = t^2 <= 1/64: the series 1 - x/3 + x^2/5 - ... to
/// x^9 (the next term is under 4e-20), by Estrin's scheme, seven
/// operations deep where Horner's is eighteen (every body's and tangent
/// point's turn, every substep: a chain the next body waits behind).
inline double atanSeries(double x) {
  const double x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  const double b0 = 1.0 - x * (1.0 / 3.0), b1 = 1.0 / 5.0 - x * (1.0 / 7.0), b2 = 1.0 / 9.0 - x * (1.0 / 11.0),
               b3 = 1.0 / 13.0 - x * (1.0 / 15.0), b4 = 1.0 / 17.0 - x * (1.0 / 19.0);
  return (b0 + x2 * b1) + x4 * (b2 + x2 * b3) + x8 * b4;
}

/// atan2(y, x) (rad). Where |y| <= x / 8 (the angles a body or a tangent
/// point turns in a substep), the series of t = y / x (atanSeries): libm's
/// angle to rounding, at a fifth of its cost.
inline double atan2Small(double y, double x) {
  if (!(x > 0.0 && std::abs(y) <= 0.125 * x)) return std::atan2(y, x);
  const double t = y / x;
  return t * atanSeries(t * t);
}

/// Rotation vector (rad) of the unit quaternion dq, the inverse of the
/// exponential map, taking the shorter way round.
inline Vec3 rotationVector(Quat dq) {
  if (dq.w() < 0.0) dq.coeffs() = -dq.coeffs();
  const double s2 = dq.vec().squaredNorm(), w = dq.w();
  if (s2 == 0.0) return Vec3::Zero();
  if (!(w > 0.0 && s2 <= 0.015625 * w * w)) {  // past atan2Small's series
    const double s = std::sqrt(s2);
    return 2.0 * std::atan2(s, w) / s * dq.vec();
  }
  // 2 atan(t) / s with t = s / w: (2 / w) atan(t) / t, the series in t^2:
  // no square root, one division (11 -> 7.6 ns a call).
  const double inv_w = 1.0 / w;
  return (2.0 * inv_w * atanSeries(s2 * inv_w * inv_w)) * dq.vec();
}

}  // namespace reeve
