// The run job shared by `reeve run` and the Python module's reeve.run():
// step a loaded scene frame by frame and write its outputs, each whole or
// not at all.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "reeve/render/camera.h"
#include "reeve/scene/energy.h"
#include "reeve/scene/scene.h"

namespace reeve {

/// An output exists and overwriting was not asked for (`reeve run` exit 3).
struct WouldOverwrite : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Two outputs on one file, or an output on the scene file being run:
/// refused even with force (`reeve run` exit 64).
struct OutputClash : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What a run writes (none: it only steps). `scene_file` is the file the
/// scene came from, if any, which no output may replace.
struct RunOutputs {
  std::filesystem::path png_dir, video, csv, events;
  /// A replay in one HTML file (html_replay.h: HtmlReplay); none if empty.
  std::filesystem::path html;
  int width = 1280, height = 720;  ///< pixels, of the PNG frames and the video (even for a video)
  bool force = false;              ///< replace outputs that exist
  std::filesystem::path scene_file;
  /// Energy created (EnergyWatch) stops the run with an error, as a
  /// non-finite state does; otherwise it is reported in RunResult.
  bool strict = false;
};

/// How a run went.
struct RunResult {
  int frames_done = 0;      ///< whole frames stepped and written
  int signal = 0;           ///< SIGINT or SIGTERM that stopped it, else 0
  /// Simulated time (s) where a signal stopped it inside a frame, which
  /// is then not written; nullopt when it stopped between frames or ran.
  std::optional<double> part_frame_s;
  double physics_s = 0.0;   ///< wall time spent in World::step (s)
  /// The frames whose energy ledger showed energy created (EnergyWatch),
  /// the first kMaxEnergyFindings of them, and how many there were.
  std::vector<EnergyCreated> energy_created;
  int energy_created_frames = 0;
  /// Spans that ran out of cable (CableEvent::Kind::SpanRunsOut), said
  /// as spanRunsOutMessage says them in the frame they happened, the first
  /// kMaxEnergyFindings of them, and how many there were.
  std::vector<std::string> span_run_out;
  int spans_run_out = 0;
  /// Bodies that overlapped as the scene placed them, pushed apart before
  /// the first step (World::placedOverlaps).
  std::vector<World::PlacedOverlap> placed_overlaps;
};

/// Findings of energy created a RunResult keeps (it counts them all).
inline constexpr int kMaxEnergyFindings = 100;

/// Checks every output before a run, so that nothing is half-written when a
/// later one turns out to be refused: no two on one file nor on the scene
/// file, none that exists unless `force`, a video name ending in .mp4 with
/// an even width and height, a PNG folder that is a folder. Throws
/// OutputClash, WouldOverwrite or std::runtime_error.
void checkRunOutputs(const RunOutputs& outputs, int frames);

/// Why stepping must stop after the last step, as `reeve run` says it: a
/// non-finite state (World::firstNonFinite) or a broken cable bookkeeping
/// (CableSystem::firstBreach), with what to try; nothing while neither.
std::optional<std::string> stopReason(const Scene& scene);

/// "cable 'rope' ran out of cable between 'pulley' and 'slider' at t = T s:
/// ...", as `reeve run` warns (issue 28, item 9).
std::string spanRunsOutMessage(const CableEvent& event, const Scene& scene);

/// The camera a run draws through: the scene's, or one framing every body
/// and cable (frameScene) for images of aspect width / height.
Camera sceneCamera(const Scene& scene, double aspect);

/// Steps `scene` by `frames` frames of 1 / frame_rate_hz, writing after
/// each the CSV row (CsvWriter; a row for the state before the first
/// frame too), the cable events, the PNG frame (frame_00000.png, ...) and
/// the video frame (MP4, H.264, through the ffmpeg program), the replay's
/// frame (HTML, the state before the first frame too). Every output
/// is checked before the first step (checkRunOutputs) and appears only whole, at the end (on
/// SIGINT or SIGTERM too, holding the whole frames done: a signal ends the
/// frame under way after the solver iteration in progress). Throws WouldOverwrite,
/// OutputClash, std::runtime_error for a bad output name, a failed write,
/// a non-finite state or a broken cable bookkeeping (World::firstNonFinite,
/// CableSystem::firstBreach), or with `strict` energy created
/// (EnergyWatch) or a span run out of cable (spanRunsOutMessage), leaving
/// no output behind. Without `strict` both are counted in the result.
RunResult runScene(Scene& scene, int frames, const RunOutputs& outputs);

}  // namespace reeve
