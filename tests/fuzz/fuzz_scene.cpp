// libFuzzer harness (issue 12): bytes to the scene loader; a scene that
// loads is stepped a few frames. A crash, a sanitizer finding, an exception
// other than SceneError, a non-finite output number the World's guard
// missed, or a broken cable bookkeeping that no diverged solve explains is
// a bug. tests/fuzz/README.md says how to run it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <optional>
#include <string>

#include "reeve/scene/scene.h"
#include "reeve/scene/warnings.h"

namespace {

constexpr int kFrames = 3;
constexpr int kMaxSubsteps = 4, kMaxIterations = 4;  // a bounded cost per input
constexpr double kMaxSeconds = 1.0;                 // predicted, per input

[[noreturn]] void fail(const char* what, double value) {
  std::fprintf(stderr, "fuzz_scene: %s is %g although World::firstNonFinite() saw nothing\n", what, value);
  std::abort();
}

// Every number `reeve run --csv` would write for this frame.
void checkOutputs(const reeve::Scene& scene) {
  const reeve::World& world = *scene.world;
  for (reeve::BodyId b = 0; b < world.bodyCount(); ++b) {
    const reeve::BodyState& s = world.body(b);
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(s.x[i])) fail("a position", s.x[i]);
      if (!std::isfinite(s.v[i])) fail("a velocity", s.v[i]);
    }
  }
  const reeve::CableSystem& cables = *scene.cables;
  for (int c = 0; c < static_cast<int>(cables.cables().size()); ++c) {
    const reeve::Cable& cable = cables.cables()[c];
    for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
      if (!std::isfinite(cables.tension(c, j))) fail("a tension", cables.tension(c, j));
      if (!std::isfinite(cables.restLength(c, j))) fail("a rest length", cables.restLength(c, j));
      if (!std::isfinite(cables.length(c, j))) fail("a length", cables.length(c, j));
    }
    for (const reeve::Link& link : cable.links)
      if (!std::isfinite(link.stored)) fail("stored cable", link.stored);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::optional<reeve::Scene> scene;
  try {
    scene.emplace(reeve::parseScene(std::string(reinterpret_cast<const char*>(data), size), "<fuzz>"));
  } catch (const reeve::SceneError&) {
    return 0;  // a clean error: what the loader is for
  }
  reeve::SolverSettings& settings = scene->world->settings();
  settings.substeps = std::min(settings.substeps, kMaxSubsteps);
  settings.iterations = std::min(settings.iterations, kMaxIterations);
  const int frames = std::min(kFrames, scene->frameCount());
  // A scene the cost model prices at more than a second for these frames
  // (a thousand joints on two bodies) is loaded, not stepped: `reeve run`
  // warns of it, and its cost is issue 29's.
  if (predictedSecondsPerSimulatedSecond(*scene) * frames / scene->frame_rate_hz > kMaxSeconds) return 0;
  for (int f = 0; f < frames; ++f) {
    scene->world->step(1.0 / scene->frame_rate_hz);
    if (scene->world->firstNonFinite()) return 0;  // `reeve run` stops here, naming it
    if (const auto& breach = scene->cables->firstBreach()) {
      // `reeve run` stops here too, blaming a spool that ran out, a wheel
      // carried further than its size in the substep, or else a diverged
      // solve; with no wheel turning even half a turn the last blame would
      // be wrong.
      if (!breach->spool_ran_out && std::abs(breach->fastest_turn) < std::numbers::pi &&
          breach->farthest_move <= breach->farthest_radius) {
        std::fprintf(stderr, "fuzz_scene: cable bookkeeping broke with no wheel turning fast: %s\n",
                     breach->what.c_str());
        std::abort();
      }
      return 0;
    }
    checkOutputs(*scene);
  }
  return 0;
}
