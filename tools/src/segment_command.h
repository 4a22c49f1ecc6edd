// `reeve segment`: write a scene with one cable replaced by a chain of
// rigid segments (segment_scene.h).
#pragma once

#include <filesystem>
#include <string>

#include "reeve/machines/segment_scene.h"

namespace reeve {

struct SegmentCommandOptions {
  std::string scene;
  std::filesystem::path output;  ///< empty: SCENE's stem + "_segments.json" beside it
  SegmentOptions segment;
  bool force = false;
};

/// Returns the exit code (commands.h): 0 written, kExitBadScene for an
/// invalid input scene, kExitUsage for options or a cable that cannot be
/// segmented, kExitWouldOverwrite, kExitFailure for I/O.
int segmentCommand(const SegmentCommandOptions& options);

}  // namespace reeve
