#include "commands.h"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <string>

#include "frame_folder.h"
#include "reeve/engine/thread_pool.h"
#include "reeve/scene/scene.h"
#include "reeve/scene/warnings.h"
#include "run_scene.h"

namespace reeve {
namespace {

// Warnings go to stderr and do not change the exit status.
void printWarnings(const Scene& scene, const std::string& source) {
  for (const SceneWarning& w : sceneWarnings(scene))
    std::fprintf(stderr, "reeve: warning: %s: %s: %s\n", source.c_str(), w.json_path.c_str(), w.message.c_str());
}

// Energy created (EnergyWatch): the first few frames, and how many in all.
void printEnergyCreated(const RunResult& r) {
  constexpr int kShown = 3;
  for (int i = 0; i < std::min<int>(kShown, static_cast<int>(r.energy_created.size())); ++i)
    std::fprintf(stderr, "reeve: warning: %s\n", energyCreatedMessage(r.energy_created[i]).c_str());
  if (r.energy_created_frames > kShown)
    std::fprintf(stderr, "reeve: warning: energy created in %d frames in all\n", r.energy_created_frames);
  if (r.energy_created_frames > 0)
    std::fprintf(stderr,
                 "reeve: warning: more substeps or iterations may remove it; the CSV's energy.* columns hold the ledger, and "
                 "--strict makes this an error\n");
}

// Spans run out of cable (item 9): the first few, and how many in all.
void printSpansRunOut(const RunResult& r) {
  constexpr int kShown = 3;
  for (int i = 0; i < std::min<int>(kShown, static_cast<int>(r.span_run_out.size())); ++i)
    std::fprintf(stderr, "reeve: warning: %s\n", r.span_run_out[i].c_str());
  if (r.spans_run_out > kShown) std::fprintf(stderr, "reeve: warning: spans ran out %d times in all\n", r.spans_run_out);
}

// Bodies placed overlapping, pushed apart before the first step: the
// deepest few, and how many pairs in all.
void printPlacedOverlaps(const Scene& scene, const RunResult& r) {
  constexpr int kShown = 3;
  const auto name = [&](BodyId id) {
    return id == kWorldBody ? std::string("the ground") : "'" + scene.world->bodyDef(id).name + "'";
  };
  for (int i = 0; i < std::min<int>(kShown, static_cast<int>(r.placed_overlaps.size())); ++i) {
    const World::PlacedOverlap& o = r.placed_overlaps[i];
    std::fprintf(stderr, "reeve: note: %s and %s overlapped by %.3g m as placed; pushed apart before the first step\n",
                 name(o.a).c_str(), name(o.b).c_str(), o.depth_m);
  }
  if (static_cast<int>(r.placed_overlaps.size()) > kShown)
    std::fprintf(stderr, "reeve: note: %zu pairs of bodies overlapped as placed\n", r.placed_overlaps.size());
}

int simulate(const RunOptions& o) {
  Scene scene = o.scene.empty() ? parseScene(std::string(defaultSceneJson()), "<built-in simple.json>")
                                : loadScene(o.scene);
  if (o.substeps) scene.world->settings().substeps = *o.substeps;
  if (o.iterations) scene.world->settings().iterations = *o.iterations;
  scene.world->setThreads(o.threads.value_or(ThreadPool::cores()));
  if (!o.solver.empty()) scene.world->settings().solver = *solverMethodFromName(o.solver);
  if (!o.projection.empty()) scene.world->settings().projection = o.projection == "start" ? Projection::Start : Projection::End;
  if (scene.world->settings().solver == SolverKind::GaussSeidel && scene.world->settings().projection == Projection::Start) {
    std::fprintf(stderr, "reeve: the start projection (%s) is the direct solver's, not gauss-seidel's: pass --projection end "
                 "or --solver direct\n", o.projection.empty() ? "the scene's solver/projection" : "--projection start");
    return kExitUsage;
  }
  const int frames = o.frames.value_or(scene.frameCount());
  const RunOutputs outputs{o.png_dir, o.video, o.csv, o.events, o.html, o.width, o.height, o.force, o.scene, o.strict};
  checkRunOutputs(outputs, frames);  // before the warnings: a refused output is the one message
  printWarnings(scene, o.scene.empty() ? "<built-in simple.json>" : o.scene);
  const RunResult r = runScene(scene, frames, outputs);
  const int done = r.frames_done;
  const double dt = 1.0 / scene.frame_rate_hz;
  if (r.signal) {
    char inside[96] = "";
    if (r.part_frame_s)
      std::snprintf(inside, sizeof inside, " inside frame %d (at t = %.6g s, not written)", done + 1, *r.part_frame_s);
    std::fprintf(stderr, "reeve: %s: stopped after %d of %d frames%s; the outputs hold those %d frames\n",
                 r.signal == SIGINT ? "interrupted (SIGINT)" : "terminated (SIGTERM)", done, frames, inside, done);
  }
  printPlacedOverlaps(scene, r);
  printEnergyCreated(r);
  printSpansRunOut(r);
  std::printf("reeve: simulated %d frames of '%s' (%.3f s, %d substeps x %d iterations, %s%s) in %.3f ms/frame of physics\n",
              done, scene.name.c_str(), done * dt, scene.world->settings().substeps,
              scene.world->settings().iterations, solverMethodName(scene.world->settings().solver),
              scene.world->settings().projection == Projection::Start ? ", start projection" : "",
              1e3 * r.physics_s / std::max(done, 1));
  if (!o.png_dir.empty() && done > 0)
    std::printf("  PNG frames: %s .. %s\n", (o.png_dir / frameName(0)).c_str(), frameName(done - 1).c_str());
  if (!o.video.empty()) std::printf("  video:      %s\n", o.video.c_str());
  if (!o.csv.empty()) std::printf("  CSV:        %s\n", o.csv.c_str());
  if (!o.html.empty()) std::printf("  replay:     %s (open it in a browser)\n", o.html.c_str());
  if (!o.events.empty()) std::printf("  events:     %s\n", o.events.c_str());
  if (o.png_dir.empty() && o.video.empty() && o.csv.empty() && o.events.empty() && o.html.empty())
    std::printf("  (no output requested: add --png DIR, --video FILE.mp4, --csv FILE, --events FILE or --html FILE)\n");
  return r.signal ? 128 + r.signal : 0;  // the shells' convention: 130 for SIGINT, 143 for SIGTERM
}

}  // namespace

int runCommand(const RunOptions& options) {
  try {
    return simulate(options);
  } catch (const SceneError& e) {
    std::cerr << "reeve: " << e.what() << '\n';
    return kExitBadScene;
  } catch (const WouldOverwrite& e) {
    std::cerr << "reeve: " << e.what() << '\n';
    return kExitWouldOverwrite;
  } catch (const OutputClash& e) {
    std::cerr << "reeve: " << e.what() << '\n';
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "reeve: " << e.what() << '\n';
    return kExitFailure;
  }
}

int validateCommand(const std::string& scene) {
  try {
    printWarnings(loadScene(scene), scene);
    std::printf("%s: ok\n", scene.c_str());
    return 0;
  } catch (const SceneError& e) {
    std::cerr << "reeve: " << e.what() << '\n';
    return kExitBadScene;
  } catch (const std::exception& e) {  // a check the loader missed: still an error, never an abort
    std::cerr << "reeve: " << e.what() << '\n';
    return kExitFailure;
  }
}

}  // namespace reeve
