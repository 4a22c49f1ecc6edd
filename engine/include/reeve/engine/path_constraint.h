// A unilateral constraint on the length of a polyline through body-local
// points: sum_i |p_{i+1} - p_i| <= rest_length. A cable running through
// pinholes is one such constraint, so the tension is the same in every
// span, as a frictionless pinhole demands (a two-point path is a plain
// cable span). The generalization of Box2D's pulley joint to any number
// of points and bodies.
#pragma once

#include <vector>

#include "reeve/engine/body.h"

namespace reeve {

/// A point of a path: a body and a body-local position (m).
struct PathPoint {
  BodyId body = 0;
  Vec3 local = Vec3::Zero();
};

/// At least two points; `rest_length` (m), `compliance` (m/N) of the whole
/// path. Disabled paths are skipped and exert nothing.
struct PathConstraint {
  std::vector<PathPoint> points;
  double rest_length = 0.0;
  double compliance = 0.0;
  bool enabled = true;
  double lambda = 0.0;  // accumulated this substep, kg m; <= 0 when pulling
};

/// The World's bodies as the path kernels see them: id -> state, with
/// kWorldBody the fixed world frame.
struct BodyTable {
  BodyState* bodies;
  BodyState* world_frame;
  BodyState& operator()(BodyId id) const { return id == kWorldBody ? *world_frame : bodies[id]; }
};

/// One Gauss-Seidel visit. C = sum_i |p_{i+1} - p_i| - rest_length; the
/// gradient at point i is u_{i-1} - u_i, u_i the unit direction of segment
/// i. A body holding several points gets the sum of their gradients, and
/// its generalized inverse mass is g^T M^-1 g over all of them (SCA 2020
/// eq. 2-4 for a general gradient). lambda is kept <= 0 (pull only).
void solvePathConstraint(PathConstraint& path, const BodyTable& bodies, double alpha_tilde);

}  // namespace reeve
