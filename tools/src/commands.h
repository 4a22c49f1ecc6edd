// The subcommands of `reeve` and their exit codes.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace reeve {

inline constexpr int kExitFailure = 1;       ///< I/O, rendering, video or a non-finite state
inline constexpr int kExitBadScene = 2;      ///< the scene file is invalid
inline constexpr int kExitWouldOverwrite = 3;  ///< an output exists and --force was not given
inline constexpr int kExitUsage = 64;        ///< bad command line, or outputs that clash

struct RunOptions {
  std::string scene;  ///< empty: the built-in default scene
  std::optional<int> frames, substeps, iterations;
  std::optional<int> threads;  ///< World::setThreads; none: the cores (ThreadPool::cores)
  std::string solver;  ///< "direct" or "gauss-seidel" (checked by the parser); empty: the scene's
  std::string projection;  ///< "end" or "start" (checked by the parser); empty: the scene's
  std::filesystem::path png_dir, video, csv, events, html;
  int width = 1280, height = 720;
  bool force = false;
  bool strict = false;  ///< energy created is an error (exit 1), not a warning
};

/// `reeve run`: returns the process exit code (above, or 128 + SIGINT or
/// SIGTERM when one stopped the run after a whole frame); errors go to
/// stderr.
int runCommand(const RunOptions& options);

/// `reeve validate`: 0 and "SCENE: ok" when valid, else kExitBadScene.
int validateCommand(const std::string& scene);

}  // namespace reeve
