#include "reeve/render/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "scene_points.h"

namespace reeve {
namespace {

constexpr double kElevationRad = 15.0 * std::numbers::pi / 180.0;
constexpr double kFill = 0.88;  // the scene spans at most this much of the half-image
constexpr int kCentringPasses = 3;

}  // namespace

Camera frameScene(const World& world, const CableSystem& cables, double aspect) {
  if (std::isnan(aspect) || aspect <= 0.0)  // a quiet test: `aspect > 0` on NaN raises "invalid"
    throw std::invalid_argument("frameScene: aspect ratio must be > 0, got " +
                                std::to_string(aspect));
  const std::vector<Vec3> points = scenePoints(world, cables);
  Camera camera;
  if (points.empty()) return camera;

  const Vec3 forward(0.0, -std::sin(kElevationRad), -std::cos(kElevationRad));
  const Vec3 right = forward.cross(camera.up).normalized();
  const Vec3 up = right.cross(forward);
  const double tan_y = std::tan(camera.fov_y_deg * std::numbers::pi / 360.0) * kFill;
  const double tan_x = tan_y * aspect;
  Eigen::AlignedBox3d box;
  for (const Vec3& p : points) box.extend(p);
  const double min_depth = 0.1 * box.diagonal().norm() + 1e-3;  // m, nothing nearer

  // Closest distance from the target that shows every point; then shift
  // the target to centre the points' image extent, and fit again.
  Vec3 target = box.center();
  double distance = 0.0;
  for (int pass = 0;; ++pass) {
    distance = 0.0;
    for (const Vec3& p : points) {
      const Vec3 v = p - target;
      const double ahead = v.dot(forward);
      distance = std::max({distance, std::abs(v.dot(right)) / tan_x - ahead,
                           std::abs(v.dot(up)) / tan_y - ahead, min_depth - ahead});
    }
    if (pass == kCentringPasses) break;
    constexpr double inf = std::numeric_limits<double>::infinity();
    Eigen::Vector2d lo(inf, inf), hi(-inf, -inf);
    for (const Vec3& p : points) {
      const Vec3 v = p - target;
      const Eigen::Vector2d image(v.dot(right), v.dot(up));
      lo = lo.cwiseMin(image / (distance + v.dot(forward)));
      hi = hi.cwiseMax(image / (distance + v.dot(forward)));
    }
    const Eigen::Vector2d mid = 0.5 * (lo + hi) * distance;
    target += mid.x() * right + mid.y() * up;
  }
  camera.target = target;
  camera.eye = target - distance * forward;
  return camera;
}

}  // namespace reeve
