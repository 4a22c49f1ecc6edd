// Times every shipped scene at its own substeps and iterations with each
// solver method, side by side: ms per frame of physics (min / median / max
// over repeated runs), cable joints and events, so the cost of each cable
// feature and of each method is visible. Timings only; nothing here
// passes or fails.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "reeve/scene/scene.h"

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  const fs::path dir = argc > 1 ? argv[1] : REEVE_SCENES_DIR;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".json" && entry.path().filename() != "scene.schema.json")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  constexpr int kRepeats = 11;
  std::printf("%-14s %-12s %6s %6s %8s %10s %10s %10s %7s\n", "scene", "solver", "joints", "frames", "sub x it",
              "min ms", "median ms", "max ms", "events");
  for (const fs::path& file : files) {
    for (const reeve::SolverKind method : {reeve::SolverKind::Direct, reeve::SolverKind::GaussSeidel}) {
      std::vector<double> ms;
      int joints = 0, frames = 0, events = 0;
      std::string setting;
      for (int r = 0; r < kRepeats; ++r) {
        reeve::Scene scene = reeve::loadScene(file);
        scene.world->settings().solver = method;
        frames = scene.frameCount();
        joints = 0;
        for (const reeve::Cable& c : scene.cables->cables()) joints += static_cast<int>(c.joints.size());
        setting = std::to_string(scene.world->settings().substeps) + " x " +
                  std::to_string(scene.world->settings().iterations);
        events = 0;
        const double dt = 1.0 / scene.frame_rate_hz;
        const auto t0 = std::chrono::steady_clock::now();
        for (int f = 0; f < frames; ++f) {
          scene.world->step(dt);
          events += static_cast<int>(scene.cables->takeEvents().size());
        }
        ms.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / frames);
      }
      std::sort(ms.begin(), ms.end());
      std::printf("%-14s %-12s %6d %6d %8s %10.5f %10.5f %10.5f %7d\n", file.stem().c_str(),
                  reeve::solverMethodName(method), joints, frames, setting.c_str(), ms.front(), ms[ms.size() / 2],
                  ms.back(), events);
    }
  }
  return 0;
}
