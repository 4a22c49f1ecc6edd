// `reeve import mjcf`: write the scene a MuJoCo model makes (mjcf.h).
#pragma once

#include <filesystem>
#include <string>

#include "reeve/scene/mjcf.h"

namespace reeve {

struct ImportCommandOptions {
  std::filesystem::path model;
  std::filesystem::path output;  ///< empty: the scene goes to stdout
  MjcfOptions mjcf;
  bool force = false;
};

/// Returns the exit code (commands.h): 0 written, kExitBadScene for a model
/// that is malformed or cannot be built, kExitWouldOverwrite, kExitFailure
/// for I/O. What the scene does not carry of the model goes to stderr as
/// one warning.
int importCommand(const ImportCommandOptions& options);

}  // namespace reeve
