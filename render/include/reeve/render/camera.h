// Pinhole camera for the off-screen renderer, and automatic framing of a
// scene.
#pragma once

#include "reeve/cable/cable.h"

namespace reeve {

/// A perspective camera. `eye` and `target` in m, world; `up` is the world
/// direction that appears upward in the image (need not be orthogonal to the
/// view direction, must not be parallel to it); `fov_y_deg` is the full
/// vertical field of view in degrees.
struct Camera {
  Vec3 eye = Vec3(0.0, 0.0, 5.0);
  Vec3 target = Vec3::Zero();
  Vec3 up = Vec3::UnitY();
  double fov_y_deg = 40.0;
};

/// A camera that frames every body (its whole shape) and every cable tangent
/// point of the scene, with a margin, for images of width/height `aspect`.
/// It looks along -z (the 2D scenes' cable plane is x-y) from slightly above
/// (elevation 15 degrees), y up. An empty scene gives the default Camera.
/// Throws std::invalid_argument unless aspect > 0.
Camera frameScene(const World& world, const CableSystem& cables, double aspect);

}  // namespace reeve
