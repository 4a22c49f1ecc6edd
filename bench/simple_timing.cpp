// Times the paper's Simple scene (Fig. 12 left, 4 cable joints) per frame,
// with each solver method, and prints min / median / max over repeated
// runs next to the paper's
// Table 1 (0.012 ms at 1 iteration, 0.036 ms at 10, one step per frame, on
// a 3.5 GHz Core i7). Timings only; nothing here passes or fails.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "reeve/scene/scene.h"

namespace {

struct Row {
  const char* label;
  int substeps, iterations;
  double paper_ms;  // < 0: not in the paper
};

// Median of a copy.
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : REEVE_SCENES_DIR "/simple.json";
  constexpr int kFrames = 600, kRepeats = 21;
  const Row rows[] = {
      {"paper: 1 step, 1 iteration", 1, 1, 0.012},
      {"paper: 1 step, 10 iterations", 1, 10, 0.036},
      {"scene default", 0, 0, -1.0},
      {"20 substeps, 1 iteration", 20, 1, -1.0},
  };
  std::printf("Simple scene (%s), %d frames at 60 Hz, %d repeats\n", path.c_str(), kFrames, kRepeats);
  std::printf("%-32s %-12s %9s %10s %10s %10s %10s\n", "setting", "solver", "sub x it", "min ms", "median ms",
              "max ms", "paper ms");
  for (const Row& row : rows)
  for (const reeve::SolverKind method : {reeve::SolverKind::Direct, reeve::SolverKind::GaussSeidel}) {
    std::vector<double> per_frame_ms;
    int substeps = 0, iterations = 0;
    for (int r = 0; r < kRepeats; ++r) {
      reeve::Scene scene = reeve::loadScene(path);
      scene.world->settings().solver = method;
      if (row.substeps > 0) scene.world->settings().substeps = row.substeps;
      if (row.iterations > 0) scene.world->settings().iterations = row.iterations;
      substeps = scene.world->settings().substeps;
      iterations = scene.world->settings().iterations;
      const double dt = 1.0 / scene.frame_rate_hz;
      const auto t0 = std::chrono::steady_clock::now();
      for (int f = 0; f < kFrames; ++f) scene.world->step(dt);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      per_frame_ms.push_back(1e3 * s / kFrames);
    }
    const auto [lo, hi] = std::minmax_element(per_frame_ms.begin(), per_frame_ms.end());
    char paper[16] = "-";
    if (row.paper_ms > 0) std::snprintf(paper, sizeof paper, "%.3f", row.paper_ms);
    std::printf("%-32s %-12s %4d x %-3d %10.5f %10.5f %10.5f %10s\n", row.label, reeve::solverMethodName(method),
                substeps, iterations, *lo, median(per_frame_ms), *hi, paper);
  }
  return 0;
}
