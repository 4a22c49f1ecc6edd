// `reeve generate hilbert`: write the paper's Hilbert-curve machine
// (Fig. 18, Fig. 1 right) as a scene file (reeve/machines/machines.h).
#pragma once

#include <filesystem>
#include <string>

namespace reeve {

struct GenerateHilbertOptions {
  int level = 2;
  double slack_m = 0.0;
  /// "brake": the last wheel is a drum braked with 10 N m (the paper's);
  /// "load": a 10 kg load hangs 3 m below it; empty: the level's default
  /// (braked, as in the paper).
  std::string end;
  double wheel_kg = 0.0;  ///< > 0: every wheel's mass (kg); 0: the default 1 kg
  std::filesystem::path output;  ///< empty: hilbert<level>[_loose].json in the current folder
  bool force = false;
};

/// Returns the exit code (commands.h): 0 written, kExitWouldOverwrite when
/// the output exists without `force`, kExitFailure for I/O.
int generateHilbertCommand(const GenerateHilbertOptions& options);

}  // namespace reeve
