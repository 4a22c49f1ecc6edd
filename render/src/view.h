// OpenGL-convention view and projection matrices of a Camera.
#pragma once

#include "reeve/render/camera.h"

namespace reeve {

/// World -> eye transform: the camera at the origin looking down -z, y up.
Eigen::Matrix4d viewMatrix(const Camera& camera);

/// Eye -> clip perspective transform (gluPerspective) for an image of
/// width/height `aspect`, with depth range [near, far] (m, 0 < near < far).
Eigen::Matrix4d projectionMatrix(const Camera& camera, double aspect, double near, double far);

}  // namespace reeve
