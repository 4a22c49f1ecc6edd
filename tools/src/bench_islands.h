// `reeve bench islands`: one scene of K separate Atwood machines, its
// islands solved on 1 and more threads (World::setThreads): ms a frame, the
// speed-up over one thread, and whether every run ended on the same bits
// (issue 30). Prints; never passes or fails.
#pragma once

#include <string>
#include <vector>

#include "reeve/bench/report.h"

namespace reeve {

struct IslandsBenchOptions {
  bench::Output output;
  int machines = 64;            ///< Atwood machines in the scene
  std::vector<int> threads;     ///< default: 1, 2 and the cores (once each)
  std::vector<std::string> solvers = {"direct", "gauss-seidel"};
  int substeps = 10, iterations = 2;
  int frames = 60;              ///< timed frames per run
  int repeats = 5;              ///< timed runs per row; the median is reported
};

/// Runs the benchmark; returns the exit code. Throws bench::OutputError for
/// an output and std::invalid_argument for counts below 1.
int benchIslands(const IslandsBenchOptions& options);

}  // namespace reeve
