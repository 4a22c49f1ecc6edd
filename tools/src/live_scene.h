// The scene `reeve view` runs (issue 31): stepped a frame at a time, under
// the page's commands (JSON, checked here), and told to the page as
// messages: the scene's fixed part and status as JSON, each frame in
// binary. No threads and no HTTP here (view_server.h owns those).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "reeve/scene/scene.h"

namespace reeve {

/// Messages to the page (viewer/live.js reads them): a little-endian u32
/// byte count of what follows, then a type byte and its payload.
/// kFrameMessage's payload, little-endian, in order:
///   u32 generation, u32 frame, f64 t (s), u32 iterations the frame ran,
///   f64 physics (ms of wall time the frame's step took);
///   u32 B, then per body f64 x, y, z (m), qx, qy, qz, qw, vx, vy, vz (m/s);
///   u32 H, then per hinge f64 angle (rad), drive torque (N m);
///   u32 C, then per cable: u32 J, per joint f64 tension (N), rest length
///   (m), f32 x, y, z of its start and of its end point (m; NaN while the
///   joint is disabled); u32 P pieces of its drawn path (cablePaths), per
///   piece u32 N and 3 N f32 (m); u32 S coils of stored cable on its end
///   spools (spoolCoil), each u32 N and 3 N f32 (m);
///   u32 M link markers (linkMarkers), each u32 kind (MarkerKind: 0
///   rolling, 1 attachment, 2 pinhole, 3 hybrid rolling, 4 hybrid tied)
///   and f32 x, y, z (m).
/// kJsonMessage's payload is UTF-8 JSON with a "type": "scene" (sceneHead
/// and generation, file, warnings), "status", "event", "error".
inline constexpr unsigned char kFrameMessage = 1;
inline constexpr unsigned char kJsonMessage = 2;

/// A frame rate of the wall clock against simulated time the page may ask
/// for (`set` rtf).
inline constexpr double kMinRealTimeFactor = 0.01, kMaxRealTimeFactor = 100.0;
/// Longest command accepted (bytes).
inline constexpr std::size_t kMaxCommandBytes = 4096;

/// The scene, its settings as the viewer overrides them, and play state.
class LiveScene {
 public:
  /// Overrides applied to every scene loaded (the command line's, then the
  /// page's): substeps, iterations, solver.
  struct Overrides {
    std::optional<int> substeps, iterations;
    std::optional<SolverKind> solver;
    std::optional<int> threads;  ///< World::setThreads; none: the cores (as reeve run)
  };

  /// Loads `file` (empty: the built-in simple.json). Throws SceneError.
  LiveScene(std::filesystem::path file, Overrides overrides);
  /// Loads the scene in `text`, `source` naming it in errors (a Python
  /// Scene's "<dict>"). Throws SceneError.
  LiveScene(std::string text, std::string source, Overrides overrides);

  /// Runs a command from the page: {"cmd": "play" | "pause" | "reset" |
  /// "step" [, "frames": 1..1000] | "set" with any of "substeps"
  /// (1..100000), "iterations" (1..100000), "solver" ("direct",
  /// "gauss-seidel"), "rtf" (kMinRealTimeFactor..kMaxRealTimeFactor) |
  /// "drive", "hinge": index, "target": rad or rad/s (a hinge with a
  /// drive) | "winch", "cable": index, "speed": m/s (a cable with a winch)
  /// | "drag", "body": index, "point": body-local [x, y, z] (m), "target":
  /// world [x, y, z] (m) | "release"}. Returns nullopt when done, else why
  /// not ("/substeps: expected an integer 1..100000, got -1"), having
  /// changed nothing.
  std::optional<std::string> command(const std::string& text);

  /// Steps one frame (1 / frame_rate_hz), with the drag's spring on. It
  /// pauses once at the scene's duration (play runs on past it). Once the
  /// state is not finite or the cable bookkeeping broke it pauses,
  /// failure() says why, and only reset steps again.
  void stepFrame();
  /// Loads `text` as the scene (the file changed on disk) and plays it
  /// from t = 0 with the overrides. Throws SceneError, keeping the old.
  void reload(const std::string& text);
  /// reload() of the text of `file` (readSceneFile's checks).
  void reloadFile(const std::filesystem::path& file);

  bool playing() const { return playing_ && !failure_; }
  /// Frames the page asked to step while paused, not yet stepped.
  int stepsWanted() const { return steps_wanted_; }
  double realTimeFactor() const { return rtf_; }
  double frameSeconds() const { return 1.0 / scene_.frame_rate_hz; }
  const std::optional<std::string>& failure() const { return failure_; }
  /// The scene's file, or what names it ("<built-in simple.json>").
  const std::string& source() const { return source_; }
  /// Counts the scenes started (the first is 1; reset and reload start
  /// one): a frame of an older one is stale.
  std::uint32_t sceneGeneration() const { return generation_; }
  const Scene& scene() const { return scene_; }

  /// kJsonMessage "scene": sceneHead, generation, file, warnings.
  std::string sceneMessage() const;
  /// kJsonMessage "status": playing, failure, ended (the duration
  /// reached), rtf, settings, t, frame, duration_s, dragging.
  std::string statusMessage() const;
  /// kFrameMessage of the state now.
  std::string frameMessage() const;
  /// kJsonMessage "event" per cable event since the last call
  /// (CableEvent), and per friction link (0 < mu < infinity) that began or
  /// stopped slipping since then ("slips", "sticks"; seen at frame ends).
  std::vector<std::string> takeEventMessages();

 private:
  void start(Scene scene);  // the scene from t = 0, overrides applied
  void applyDrag();
  void releaseDrag();

  std::string source_;
  std::string text_;  // of the scene running, reloaded by reset
  Overrides overrides_;
  Scene scene_;
  std::uint32_t generation_ = 0;  // scenes started: frames of older ones are stale
  std::uint32_t frame_ = 0;
  int last_iterations_ = 0;
  double physics_ms_ = 0.0;
  bool playing_ = true;
  bool ended_ = false;  // paused at the scene's duration
  int steps_wanted_ = 0;
  double rtf_ = 1.0;
  std::optional<std::string> failure_;
  std::vector<std::vector<char>> slipping_;  // per cable and link, at the last takeEventMessages()
  struct Drag {
    BodyId body;
    Vec3 point;   // body-local, m
    Vec3 target;  // world, m
    Vec3 force, torque;  // the body's own applied load before the drag
  };
  std::optional<Drag> drag_;
};

/// A JSON message (kJsonMessage) of `json`, framed.
std::string jsonMessage(const std::string& json);

}  // namespace reeve
