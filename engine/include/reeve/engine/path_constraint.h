// A unilateral constraint on the length of a polyline through body-local
// points: sum_i |p_{i+1} - p_i| <= rest_length. A cable running through
// pinholes is one such constraint, so the tension is the same in every
// span, as a frictionless pinhole demands (a two-point path is a plain
// cable span). The generalization of Box2D's pulley joint to any number
// of points and bodies. Segment weights put friction between segments: a
// cable slipping over a wheel or through a hole with friction keeps the
// capstan ratio T_tight / T_slack = exp(mu theta) between the two sides.
#pragma once

#include <limits>
#include <vector>

#include "reeve/engine/body.h"

namespace reeve {

/// A point of a path: a body and a body-local position (m).
struct PathPoint {
  BodyId body = 0;
  Vec3 local = Vec3::Zero();
};

/// At least two points; `rest_length` (m), `compliance` (m/N) and
/// `damping` (N s/m: a force -damping dL/dt on the path's length L, only
/// with compliance > 0; XPBD eq. 25-26, correction.h: dampedRow) of the
/// whole path. Disabled paths are skipped and exert nothing.
///
/// `weights`: empty (every segment pulls with the same tension: a
/// frictionless path) or one value > 0 per segment (points - 1): segment i
/// pulls with tension w_i T, T = -lambda / h^2 being the tension of a
/// weight-1 segment. The length constraint stays unweighted, sum L_i <=
/// rest_length; only the forces are weighted (gradient of the length J_c,
/// force direction J_f = sum w_i grad L_i), so the path is not a
/// conservative constraint when the weights differ: it dissipates, as the
/// friction it stands for does (the direct solver, whose system is
/// symmetric, sweeps weighted paths with solvePathConstraint after each of
/// its iterations). `compliance` is the stretch of the whole path per unit
/// T: sum_i w_i c_i for segment compliances c_i.
struct PathConstraint {
  std::vector<PathPoint> points;
  std::vector<double> weights;
  double rest_length = 0.0;
  double compliance = 0.0;
  double damping = 0.0;
  /// Cable fed into the path this substep at a point that does not slide
  /// (m, as long as it was stretched; a winch paying out, negative reeling
  /// in): a change of its length that is not stretching, which the damping
  /// leaves out.
  double fed = 0.0;
  /// The most the path pulls with (N, tension of a weight-1 segment): a
  /// winch's maximum pull; beyond it the constraint gives, lambda held at
  /// -max_tension h^2. Infinite: no limit.
  double max_tension = std::numeric_limits<double>::infinity();
  bool enabled = true;
  double lambda = 0.0;  // accumulated this substep, kg m; <= 0 when pulling
  /// The length at this substep's start poses and present points plus
  /// `fed` (m), set by the World before each solve: the damping's dC is the
  /// length since.
  double start_length = 0.0;
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
/// i (weighted w_{i-1} u_{i-1} - w_i u_i for the force). A body holding
/// several points gets the sum of their gradients, and the generalized
/// inverse mass is J_c M^-1 J_f^T over all of them (SCA 2020 eq. 2-4 for a
/// general gradient; J_c = J_f without weights). lambda is kept in
/// [-max_tension h^2, 0] (pull only, and at most max_tension) for the
/// substep `h` (s). Damping acts only on a path taut or pulling, as the
/// spring does.
void solvePathConstraint(PathConstraint& path, const BodyTable& bodies, double alpha_tilde, double h);

/// The path's length at the substep's start poses (m).
double pathStartLength(const PathConstraint& path, const BodyTable& bodies);

}  // namespace reeve
