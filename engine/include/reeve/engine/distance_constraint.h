// Distance constraint between two body-local points, optionally unilateral
// (a cable span: it pulls, never pushes). Cable joints (cable/) are these,
// with anchors and rest length moved between substeps.
#pragma once

#include "reeve/engine/body.h"

namespace reeve {

/// A distance constraint between body-local points of `a` and `b`.
/// `rest_length` in m; `compliance` in m/N (0: inextensible).
/// Unilateral: enforces |p_b - p_a| <= rest_length only.
struct DistanceConstraint {
  BodyId a = 0, b = 0;
  Vec3 local_a = Vec3::Zero(), local_b = Vec3::Zero();  // m, body-local
  double rest_length = 0.0;                             // m
  double compliance = 0.0;                              // m/N
  bool unilateral = true;
  bool enabled = true;  // a disabled constraint is skipped and exerts nothing
  double lambda = 0.0;  // accumulated this substep, kg m; <= 0 when pulling
};

/// One Gauss-Seidel visit. C = |p_b - p_a| - rest_length, n = (p_b - p_a)/|.|.
/// Unilateral rows keep the accumulated lambda <= 0 (projected Gauss-Seidel),
/// so a slack span exerts nothing and an overshoot is released, not pushed.
void solveDistanceConstraint(DistanceConstraint& c, BodyState& a, BodyState& b,
                             double alpha_tilde);

/// Current distance |p_b - p_a| (m) between the two anchors.
double currentLength(const DistanceConstraint& c, const BodyState& a, const BodyState& b);

}  // namespace reeve
