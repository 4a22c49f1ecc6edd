// The cells of `reeve bench extremes`: a machine under one condition
// (masses, compliance, a jerk, a load) at one frame rate, substep count,
// iteration count and solver, run and measured.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "reeve/scene/scene.h"

namespace reeve::bench {

/// What a cell's machine is made of. Masses are relative to the light
/// side (1 kg): the heavy side is `load_ratio` times it, each wheel
/// `wheel_ratio` times it; with `load_N` > 0 the light side weighs that
/// (N) instead and wheels stay 1 kg. A jerk (slack_m > 0) runs without
/// gravity: the heavy box starts at `speed_m_per_s` down with `slack_m` of
/// slack on its side. The bead is a body `bead_ratio` times the 1 kg load
/// it carries on a second rigid cable from a first one to a ceiling
/// anchor `offset_m` to the side of the vertical through it: it starts
/// bent, the load falls until the two cables line up and swings.
struct Condition {
  std::string machine;  ///< "atwood", "simple" or "bead"
  std::string name;     ///< e.g. "wheel_ratio=1e-6"
  double load_ratio = 2.0, wheel_ratio = 1.0, compliance_m_per_N = 0.0;
  double load_N = 0.0, slack_m = 0.0, speed_m_per_s = 0.0;
  double bead_ratio = 1.0, offset_m = 0.0;
};

/// The conditions of `machine` ("atwood": 18, "simple": 14, "bead": 6);
/// throws std::invalid_argument for another machine.
std::vector<Condition> conditions(const std::string& machine);

/// Solver settings of a cell.
struct CellBudget {
  double rate_hz = 60.0;
  int substeps = 1, iterations = 1;
  SolverKind solver = SolverKind::Direct;
};

/// What a run of a cell showed, measured after every frame. Errors are
/// relative; NaN where no closed form applies.
struct CellResult {
  bool finished = false;  ///< ran every frame without an exception
  bool finite = false;    ///< no non-finite body state
  double peak_stretch = 0.0;   ///< largest span strain (length - rest) / rest, any cable
  double stretch_limit = 0.0;  ///< 1 % + twice the static strain compliance predicts
  double energy_growth = 0.0;  ///< (max E - E(0)) / (max kinetic + sum m g x 1 cm)
  double tension_error = std::numeric_limits<double>::quiet_NaN();  ///< last frame, worst span
  double speed_error = std::numeric_limits<double>::quiet_NaN();    ///< jerks: either box, after the snap
  double axle_offset = 0.0;    ///< m, largest hinge anchor gap
  std::string bookkeeping;     ///< CableSystem::firstBreach()'s message; "" when kept
  std::string cause;           ///< why unstable; "" when stable
  bool stable() const { return cause.empty(); }
};

/// Runs `c` at `b` for 1 s (Atwood, the bead), 0.5 s (Simple) or, for a jerk, until
/// 0.2 s after the slack is taken up. Stable: finished, finite, the cable
/// bookkeeping's invariants kept after every substep, peak stretch at most
/// the limit, energy growth at most 1 %.
CellResult runCell(const Condition& c, const CellBudget& b);

/// "machine/condition/RATEHz/SUBxIT/solver": how `--cell` names a cell.
std::string cellKey(const Condition& c, const CellBudget& b);

/// `x` as the grids write it: "1e-6", "0.01", "2000".
std::string shortNumber(double x);

}  // namespace reeve::bench
