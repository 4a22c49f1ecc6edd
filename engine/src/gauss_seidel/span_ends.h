// A span's rolling ends on rotors, found once per Gauss-Seidel solve
// rather than at each of its visits (issue 30).
#pragma once

#include <vector>

#include "reeve/engine/path_constraint.h"

namespace reeve {

/// The two ends of a span (a two-point path between two bodies) as one
/// Gauss-Seidel solve sees them. A rolling end on a rotor whose circle
/// lies about the rotor's axle (PathPoint::roll_axis along
/// BodyState::rotor_axis, roll_centre on it, both to rounding) is
/// `steady`: the rotor turns about that axle alone, which stays put in the
/// world, and the end's lever is turned back by the solve's turn
/// (solvePoint), so its world axle, lever and arm stay what they were at
/// the solve's start, and a visit reads only its turn since then, from
/// the rotor's orientation. Every visit otherwise builds both rotation
/// matrices and turns both levers back (sin, cos, Rodrigues): a third of
/// a visit of a span between two wheels.
struct SpanEnds {
  SolvePoint end[2];
  Quat start_q[2];             // a steady end's rotor's orientation at the solve's start
  double start_turn[2] = {};   // and its solve turn about the axle then (rad)
  bool steady[2] = {false, false};
  // Both ends steady: the span's line. Neither rotor's centre moves in the
  // solve and each end's arm and lever stay, so the span's direction u,
  // its chord, each end's moment t_k (dC/d(rotation)) and response
  // I_k^-1 (weight t_k), and the row's w stay what they were at the
  // solve's start; a visit reads only the turns, which wind cable:
  //   C = chord + turn_0 per_radian_0 + turn_1 per_radian_1 - L.
  // Hilbert3 under Gauss-Seidel: every span (DESIGN, "Fortieth session").
  bool fixed_line = false;
  Vec3 u = Vec3::Zero();        // unit span, end 0 to end 1
  double chord = 0.0;           // m
  double per_radian[2] = {};    // m/rad (SolvePoint::spanMomentPerRadian)
  Vec3 moment[2] = {Vec3::Zero(), Vec3::Zero()};    // m
  Vec3 response[2] = {Vec3::Zero(), Vec3::Zero()};  // rad per unit lambda
  double w = 0.0;               // 1/kg
};

/// `ends[k]` for `paths[k]` (indices into `all`), at the bodies' present
/// poses and solve turns; nothing steady for a path that is not a span.
/// `ends` is resized, its storage kept.
void prepareSpanEnds(const std::vector<int>& paths, const std::vector<PathConstraint>& all,
                     const BodyTable& bodies, std::vector<SpanEnds>& ends);

/// solvePathConstraint, with a span's ends from prepareSpanEnds at the
/// start of the same solve (only rotations about a rotor's axle in
/// between, each counted in its solve_turn).
void solvePathConstraint(PathConstraint& path, const BodyTable& bodies, double alpha_tilde, double h,
                         const SpanEnds& ends);

}  // namespace reeve
