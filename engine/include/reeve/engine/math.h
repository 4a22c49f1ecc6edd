// Small maths vocabulary shared by every Reeve module. Double precision
// throughout (DESIGN.md, XPBD core).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace reeve {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

/// Rotates `q` by the small world-space rotation vector `dphi` (rad) and
/// renormalizes: q <- q + 1/2 [dphi, 0] q (Müller et al. 2020, eq. 8).
inline void rotateBy(Quat& q, const Vec3& dphi) {
  const Quat dq(0.0, dphi.x(), dphi.y(), dphi.z());
  q.coeffs() += 0.5 * (dq * q).coeffs();
  q.normalize();
}

}  // namespace reeve
