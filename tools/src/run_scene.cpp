#include "run_scene.h"

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <system_error>
#include <utility>
#include <vector>

#include "csv_writer.h"
#include "html_replay.h"
#include "event_log.h"
#include "frame_folder.h"
#include "interrupt.h"
#include "output_file.h"
#include "progress.h"
#include "reeve/render/renderer.h"
#include "reeve/render/video.h"

namespace reeve {
namespace {

namespace fs = std::filesystem;

void refuseOverwrite(const fs::path& path, bool force) {
  if (!force && fs::exists(path) && !isStream(path))
    throw WouldOverwrite(path.string() + ": exists; pass --force to overwrite it");
}

void refuseClashes(const RunOutputs& o) {
  std::vector<std::pair<std::string, fs::path>> files;
  if (!o.scene_file.empty()) files.push_back({"the scene", o.scene_file});
  for (const auto& [option, path] : {std::pair{"--csv", o.csv}, {"--events", o.events}, {"--video", o.video}, {"--html", o.html}})
    if (!path.empty()) files.push_back({option, path});
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = i + 1; j < files.size(); ++j) {
      std::error_code ec_i, ec_j, ec;
      const fs::path a = fs::weakly_canonical(files[i].second, ec_i), b = fs::weakly_canonical(files[j].second, ec_j);
      const bool same = (!ec_i && !ec_j && a == b) || fs::equivalent(files[i].second, files[j].second, ec);
      if (same && !isStream(files[j].second))
        throw OutputClash(files[j].first + " " + files[j].second.string() + " is the same file as " +
                          files[i].first + (i == 0 && !o.scene_file.empty() ? "" : " " + files[i].second.string()) +
                          "; give each output its own file (--force does not change this)");
    }
}

std::string bodyName(const World& world, BodyId id) {
  return id == kWorldBody ? std::string("the world") : "'" + world.bodyDef(id).name + "'";
}

// "body 'load' velocity", "tension between 'wheel' and 'load'".
std::string describe(const NonFiniteState& bad, const World& world) {
  if (bad.quantity == NonFiniteState::Quantity::Tension)
    return "the tension between " + bodyName(world, bad.body) + " and " + bodyName(world, bad.other);
  return "body " + bodyName(world, bad.body) + " " + quantityName(bad.quantity);
}

// Why a run stops at a broken cable bookkeeping, with what to try.
std::string breachMessage(const CableBreach& breach, const World& world) {
  char when[32], turn[32];
  std::snprintf(when, sizeof when, "%.9g", breach.time_s);
  std::snprintf(turn, sizeof turn, "%.3g", breach.fastest_turn);
  if (breach.held_stretched)
    return std::string("a rigid cable was stretched at t = ") + when + " s: " + breach.what +
           ". Constraints move neither static nor kinematic bodies (a wheel among them holds the cable without "
           "slipping), so nothing pulls the run in. Give such a wheel \"mu\" (0: a frictionless pulley the "
           "cable slides over) or a hinge so that it turns, give the cable a compliance, or let one of the "
           "bodies move. Nothing of that frame was written";
  std::string message = std::string("the cable bookkeeping broke at t = ") + when + " s: " + breach.what;
  if (breach.spool_ran_out)
    return message + ". Its rolling end ran out of cable: it holds only the stored_m it was given. Give it "
                     "more, or make it a \"hybrid\" link, which ties the cable where it runs out";
  if (breach.farthest >= 0 && breach.farthest_move > breach.farthest_radius) {
    char move[32], radius[32];
    std::snprintf(move, sizeof move, "%.3g", breach.farthest_move);
    std::snprintf(radius, sizeof radius, "%.3g", breach.farthest_radius);
    return message + "; body " + bodyName(world, breach.farthest) + " moved " + move +
           " m in that substep, more than its own size (" + radius +
           " m): the cable's tangents cannot follow a wheel that jumps that far. Nothing of that frame was "
           "written. Try more substeps, or check the loads (gravity, applied forces) for one far too large";
  }
  if (breach.fastest >= 0)
    message += "; body " + bodyName(world, breach.fastest) + " turned " + turn + " rad in that substep";
  return message +
         ". The solve diverged, or turned a wheel further than the cable on it allows (a load hauled into its "
         "wheel). Nothing of that frame was written. Check that the rest lengths fit the bodies' poses (a span "
         "that starts stretched is pulled in by the first solve at any substep count); if a fast motion "
         "stretched it, try more substeps";
}

// What a run that blew up under Gauss-Seidel may try besides: its sweeps
// pass a correction one row further each and do not converge on stiff
// springs and joints (bow.json at the paper's 10 x 10 throws a cam 2e7 m
// at 0.255 s) or on light bodies between heavy ones, which the direct
// solver takes in one solve (README, "Substeps and iterations").
std::string solverHint(const World& world) {
  if (world.settings().solver != SolverKind::GaussSeidel) return "";
  return ". This run used Gauss-Seidel, whose sweeps may not converge on stiff springs and joints or on light "
         "bodies between heavy ones: the direct solver (--solver direct, or \"method\": \"direct\" in the "
         "scene's solver) solves them together";
}

void createParent(const fs::path& file) {
  if (file.has_parent_path()) fs::create_directories(file.parent_path());
}

}  // namespace

void checkRunOutputs(const RunOutputs& o, int frames) {
  refuseClashes(o);
  if (!o.csv.empty()) refuseOverwrite(o.csv, o.force);
  if (!o.events.empty()) refuseOverwrite(o.events, o.force);
  if (!o.html.empty()) refuseOverwrite(o.html, o.force);
  if (!o.video.empty()) {
    if (o.video.extension() != ".mp4")
      throw std::runtime_error(o.video.string() + ": expected a file name ending in .mp4");
    if (o.width % 2 != 0 || o.height % 2 != 0)
      throw std::runtime_error("--video needs an even --width and --height (H.264 yuv420p), got " +
                               std::to_string(o.width) + "x" + std::to_string(o.height));
    refuseOverwrite(o.video, o.force);
  }
  if (!o.png_dir.empty()) {
    if (fs::exists(o.png_dir) && !fs::is_directory(o.png_dir))
      throw std::runtime_error(o.png_dir.string() + ": exists and is not a folder");
    for (int f = 0; f < frames; ++f) refuseOverwrite(o.png_dir / frameName(f), o.force);
  }
}

std::string spanRunsOutMessage(const CableEvent& e, const Scene& scene) {
  const Cable& cable = scene.cables->cables()[e.cable];
  const Link& a = cable.links[e.link];
  const Link& b = cable.links[cable.joints[e.link].to];
  const World& world = *scene.world;
  char when[32];
  std::snprintf(when, sizeof when, "%.6g", e.time_s);
  const std::string where = "cable '" + cable.name + "' ran out between " + bodyName(world, a.body) + " (link " +
                            std::to_string(e.link) + ") and " + bodyName(world, b.body) + " at t = " + when + " s: ";
  if (a.type == LinkType::Pinhole || b.type == LinkType::Pinhole)
    return where + "a tie point reached the pinhole in " + bodyName(world, (a.type == LinkType::Pinhole ? a : b).body) +
           " and jammed there: a ball joint holds it to the hole from now on (a knot against it). Stop what hauls it "
           "before, or give the span more cable";
  return where + bodyName(world, (a.rolls() ? a : b).body) +
         " wound more cable than the span held (a tie point reached its rim). " +
         (cable.joints[e.link].jammed
              ? "The tie point jammed there: a ball joint holds it to the wheel from now on (a hook block hauled "
                "into its sheave), and the drive stalls against it or turns the two together"
              : "The tie point is not at the rim (an unconverged solve): the wheel slips on the cable") +
         ". Stop the drive before, or give the span more cable";
}

std::optional<std::string> stopReason(const Scene& scene) {
  if (const auto& bad = scene.world->firstNonFinite())
    return nonFiniteMessage(bad->time_s, describe(*bad, *scene.world)) + solverHint(*scene.world);
  if (const auto& breach = scene.cables->firstBreach())
    return breachMessage(*breach, *scene.world) + solverHint(*scene.world);
  return std::nullopt;
}

Camera sceneCamera(const Scene& scene, double aspect) {
  if (!scene.camera) return frameScene(*scene.world, *scene.cables, aspect);
  return Camera{scene.camera->eye, scene.camera->target, scene.camera->up, scene.camera->fov_y_deg};
}

RunResult runScene(Scene& scene, int frames, const RunOutputs& o) {
  checkRunOutputs(o, frames);
  EnergyWatch energy(scene);
  std::unique_ptr<CsvWriter> csv;
  if (!o.csv.empty()) {
    createParent(o.csv);
    csv = std::make_unique<CsvWriter>(o.csv, o.force, *scene.cables, energy);
  }
  std::unique_ptr<HtmlReplay> html;
  if (!o.html.empty()) {
    createParent(o.html);
    html = std::make_unique<HtmlReplay>(o.html, o.force, scene);
  }
  std::unique_ptr<EventLog> events;
  if (!o.events.empty()) {
    createParent(o.events);
    events = std::make_unique<EventLog>(o.events, o.force);
  }
  const bool draw = !o.png_dir.empty() || !o.video.empty();
  std::unique_ptr<Renderer> renderer;
  // ffmpeg writes a temporary file beside the video (an absolute name, so
  // "file:x.mp4" is a file, not a protocol), moved into place at the end;
  // removed if the run fails (after ffmpeg has been waited for).
  struct RemoveUnlessMoved {
    fs::path path;
    ~RemoveUnlessMoved() {
      std::error_code ec;
      if (!path.empty()) fs::remove(path, ec);
    }
  } video_file;
  std::unique_ptr<VideoWriter> video;
  Camera camera;
  if (draw) {
    renderer = std::make_unique<Renderer>(o.width, o.height);
    camera = sceneCamera(scene, static_cast<double>(o.width) / o.height);
  }
  std::unique_ptr<FrameFolder> pngs;
  if (!o.png_dir.empty()) pngs = std::make_unique<FrameFolder>(o.png_dir, o.force);
  if (!o.video.empty()) {
    createParent(o.video);
    video_file.path = temporarySibling(o.video);
    video = std::make_unique<VideoWriter>(video_file.path, o.width, o.height, scene.frame_rate_hz, o.video);
  }

  const double dt = 1.0 / scene.frame_rate_hz;
  RunResult result;
  const InterruptGuard interrupt;
  ProgressBar progress(frames);
  // A signal ends the frame under way within a solver iteration (its
  // part-frame is not written); the bar moves inside long frames.
  struct Detach {
    World& world;
    ~Detach() {
      world.setInterruptFlag(nullptr);
      world.setSubstepProgress({});
    }
  } detach{*scene.world};
  scene.world->setInterruptFlag(InterruptGuard::flag());
  scene.world->setSubstepProgress([&](int done, int substeps) { progress.updateWithin(done, substeps); });
  if (csv) csv->writeRow();  // t = 0: the scene as loaded
  if (html) html->record();
  for (int f = 0; f < frames && !interrupt.received(); ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    scene.world->step(dt);
    result.physics_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (const auto why = stopReason(scene)) throw std::runtime_error(*why);
    if (f == 0) result.placed_overlaps = scene.world->placedOverlaps();
    if (scene.world->stepInterrupted()) {
      result.part_frame_s = scene.world->time();
      break;
    }
    if (const auto created = energy.check(scene)) {
      if (o.strict)
        throw std::runtime_error(energyCreatedMessage(*created) +
                                 "; nothing of that frame was written (--strict). Try more substeps");
      if (result.energy_created_frames++ < kMaxEnergyFindings) result.energy_created.push_back(*created);
    }
    if (csv) csv->writeRow();
    if (html) html->record();
    const std::vector<CableEvent> happened = scene.cables->takeEvents();
    for (const CableEvent& e : happened) {
      if (e.kind != CableEvent::Kind::SpanRunsOut) continue;
      if (o.strict) throw std::runtime_error(spanRunsOutMessage(e, scene) + " (--strict)");
      if (result.spans_run_out++ < kMaxEnergyFindings) result.span_run_out.push_back(spanRunsOutMessage(e, scene));
    }
    if (events) events->write(*scene.cables, happened);
    if (html) html->recordEvents(happened);
    if (draw) {
      const Image image = renderer->render(*scene.world, *scene.cables, camera);
      if (pngs) pngs->write(f, image);
      if (video) video->add(image);
    }
    progress.update(f + 1);
    result.frames_done = f + 1;
  }
  // Every output complete before any is moved into place (on an interrupt
  // too: they hold the frames done, each whole).
  if (video) video->finish();
  if (csv) csv->close();
  if (events) events->close();
  if (html) html->close();
  if (video) {
    moveIntoPlace(video_file.path, o.video, o.force);
    video_file.path.clear();
  }
  if (csv) csv->commit();
  if (events) events->commit();
  if (html) html->commit();
  if (pngs) pngs->commit();
  result.signal = interrupt.received();
  return result;
}

}  // namespace reeve
