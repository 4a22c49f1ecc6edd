// `reeve generate hilbert`: write the paper's Hilbert-curve machine
// (Fig. 18, Fig. 1 right) as a scene file (reeve/machines/machines.h).
#pragma once

#include <filesystem>

namespace reeve {

struct GenerateHilbertOptions {
  int level = 2;
  double slack_m = 0.0;
  std::filesystem::path output;  ///< empty: hilbert<level>[_loose].json in the current folder
  bool force = false;
};

/// Returns the exit code (commands.h): 0 written, kExitWouldOverwrite when
/// the output exists without `force`, kExitFailure for I/O.
int generateHilbertCommand(const GenerateHilbertOptions& options);

}  // namespace reeve
