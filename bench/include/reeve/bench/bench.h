// The sub-commands of `reeve bench` (README "Performance and accuracy").
// Each prints the environment and a table to stdout, writes the CSV and
// PNG that `Output` asks for and returns a process exit code (0, or 1
// when an output could not be written); none passes or fails on a time.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "reeve/bench/report.h"

namespace reeve::bench {

/// `reeve bench table1`: the paper's Table 1 machines at the paper's
/// settings and at each scene's own, with both solvers.
struct Table1Options {
  Output output;
  std::filesystem::path scenes_dir;  ///< holds simple.json, servin.json, ...
  std::vector<std::string> only;     ///< machine names to run; empty: all
  std::vector<std::string> solvers = {"direct", "gauss-seidel"};
  int repeats = 5;
  std::optional<int> frames;  ///< default: each scene's duration
};
int table1(const Table1Options& options);

/// `reeve bench trade`: error against closed forms versus ms/frame over
/// a grid of substeps x iterations, per solver, with the segmented rope
/// on the Atwood machines.
struct TradeOptions {
  Output output;
  std::filesystem::path scenes_dir;
  std::vector<std::string> only;  ///< case names; empty: all
  std::vector<int> substeps = {1, 2, 5, 10, 20, 50};
  std::vector<int> iterations = {1, 2, 5, 10, 20};
  std::vector<std::string> solvers = {"direct", "gauss-seidel"};
  std::vector<int> rope_segments = {20, 100};  ///< empty: no rope series
  int repeats = 3;
};
int trade(const TradeOptions& options);

/// `reeve bench extremes`: a stability map over masses, compliance,
/// frame rate, substeps, iterations, jerks, loads and a light bead
/// between two cables.
struct ExtremesOptions {
  Output output;
  std::vector<std::string> machines = {"atwood", "simple", "bead"};
  std::vector<std::string> conditions;  ///< names to run; empty: all
  std::vector<double> rates_hz = {30, 60, 240, 2000};
  std::vector<int> substeps = {1, 10, 100};
  std::vector<int> iterations = {1, 2, 10, 100};
  std::vector<std::string> solvers = {"direct", "gauss-seidel"};
  std::string cell;  ///< run only this cell (its key, as printed)
};
int extremes(const ExtremesOptions& options);

/// `reeve bench scaling`: ms/frame, peak memory, iterations and statics
/// error of each solver on machines at rest (machines.h, "The series of
/// reeve bench scaling") as their count K grows, each cell in a child
/// process; the fitted exponent of ms/frame against K per series, solver
/// and budget. A baseline for the solvers' cost, never a pass or fail.
struct ScalingOptions {
  Output output;
  std::vector<std::string> series;  ///< series names; empty: all
  std::vector<std::string> solvers = {"direct", "gauss-seidel"};
  std::vector<std::string> budgets = {"1x10", "10x2"};  ///< SUBSTEPSxITERATIONS per frame
  std::vector<int> k = {4, 16, 64, 256, 1024, 4096};
  int frames = 10;                   ///< timed frames of 1/60 s per cell
  double max_ms_per_frame = 2000.0;  ///< skip a K predicted dearer than this (ms)
  double cell_timeout_s = 60.0;      ///< kill a cell running longer (s, wall clock)
};
int scaling(const ScalingOptions& options);

/// Whether `reeve bench peers` was built (Debian's libmujoco-dev found).
bool peersAvailable();

/// `reeve bench peers`: the Atwood machine and zig-zags of K pulleys as
/// MuJoCo spatial tendons next to Reeve, in the same run.
struct PeersOptions {
  Output output;
  /// Timed runs per row: a run is 60 frames, 1 ms at K = 32, and the cost
  /// ratio of medians of 5 moved between 0.96 and 1.09 from one invocation
  /// to the next, of 25 between 1.02 and 1.04.
  int repeats = 25;
};
int peers(const PeersOptions& options);

}  // namespace reeve::bench
