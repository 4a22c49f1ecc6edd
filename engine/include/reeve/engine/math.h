// Small maths vocabulary shared by every Reeve module. Double precision
// throughout (DESIGN.md, XPBD core).
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace reeve {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// Rotates `q` by the small world-space rotation vector `dphi` (rad) and
/// renormalizes: q <- q + 1/2 [dphi, 0] q (Müller et al. 2020, eq. 8).
inline void rotateBy(Quat& q, const Vec3& dphi) {
  const Quat dq(0.0, dphi.x(), dphi.y(), dphi.z());
  q.coeffs() += 0.5 * (dq * q).coeffs();
  q.normalize();
}

/// Rotates `q` exactly by the world-space rotation vector `phi` (rad), with
/// the exponential map. Used where angles are not small, e.g. a fast wheel
/// over a substep: the first-order rotateBy() loses O(|phi|^3) per call,
/// which shows up as a spurious drag on spinning bodies.
inline void rotateExactly(Quat& q, const Vec3& phi) {
  const double angle = phi.norm();
  if (angle == 0.0) return;
  q = (Quat(Eigen::AngleAxisd(angle, phi / angle)) * q).normalized();
}

/// Rotation vector (rad) of the unit quaternion dq, the inverse of the
/// exponential map, taking the shorter way round.
inline Vec3 rotationVector(Quat dq) {
  if (dq.w() < 0.0) dq.coeffs() = -dq.coeffs();
  const double s = dq.vec().norm();
  if (s == 0.0) return Vec3::Zero();
  return 2.0 * std::atan2(s, dq.w()) / s * dq.vec();
}

}  // namespace reeve
