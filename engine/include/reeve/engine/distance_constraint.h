// Distance constraint between two body-local points, optionally unilateral
// (a cable span: it pulls, never pushes). Cable joints (cable/) are these,
// with anchors and rest length moved between substeps.
#pragma once

#include "reeve/engine/body.h"

namespace reeve {

/// A distance constraint between body-local points of `a` and `b`.
/// `rest_length` in m; `compliance` in m/N (0: inextensible); `damping`
/// (N s/m, only with compliance > 0) a dashpot beside the spring, a force
/// -damping dC/dt (XPBD eq. 25-26, correction.h: dampedRow).
/// Unilateral: enforces |p_b - p_a| <= rest_length only.
struct DistanceConstraint {
  BodyId a = 0, b = 0;
  Vec3 local_a = Vec3::Zero(), local_b = Vec3::Zero();  // m, body-local
  double rest_length = 0.0;                             // m
  double compliance = 0.0;                              // m/N
  double damping = 0.0;                                 // N s/m
  bool unilateral = true;
  bool enabled = true;  // a disabled constraint is skipped and exerts nothing
  double lambda = 0.0;  // accumulated this substep, kg m; <= 0 when pulling
  /// |p_b - p_a| at this substep's start poses and present anchors (m), set
  /// by the World before each solve: the damping's dC is the length since.
  double start_length = 0.0;
};

/// One Gauss-Seidel visit in a substep of `h` s. C = |p_b - p_a| -
/// rest_length, n = (p_b - p_a)/|.|. Unilateral rows keep the accumulated
/// lambda <= 0 (projected Gauss-Seidel), so a slack span exerts nothing and
/// an overshoot is released, not pushed; damping acts only on a row taut or
/// pulling, as the spring does.
void solveDistanceConstraint(DistanceConstraint& c, BodyState& a, BodyState& b,
                             double alpha_tilde, double h);

/// Current distance |p_b - p_a| (m) between the two anchors.
double currentLength(const DistanceConstraint& c, const BodyState& a, const BodyState& b);

/// The distance between the anchors at the substep's start poses (m).
double startLength(const DistanceConstraint& c, const BodyState& a, const BodyState& b);

}  // namespace reeve
