#include "view.h"

#include <cmath>
#include <numbers>

namespace reeve {

Eigen::Matrix4d viewMatrix(const Camera& camera) {
  const Vec3 forward = (camera.target - camera.eye).normalized();
  const Vec3 right = forward.cross(camera.up).normalized();
  const Vec3 up = right.cross(forward);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = right.transpose();
  m.block<1, 3>(1, 0) = up.transpose();
  m.block<1, 3>(2, 0) = -forward.transpose();
  m.block<3, 1>(0, 3) = -m.block<3, 3>(0, 0) * camera.eye;
  return m;
}

Eigen::Matrix4d projectionMatrix(const Camera& camera, double aspect, double near, double far) {
  const double f = 1.0 / std::tan(camera.fov_y_deg * std::numbers::pi / 360.0);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (far + near) / (near - far);
  m(2, 3) = 2.0 * far * near / (near - far);
  m(3, 2) = -1.0;
  return m;
}

}  // namespace reeve
