// The machines `reeve bench trade` measures against closed forms: each
// builds its scene, watches it frame by frame and gives its relative
// errors at the end. The closed forms are the same derivations the
// physics tests check (tests/test_*.cpp), restated here.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "reeve/scene/scene.h"

namespace reeve::bench {

/// Named relative errors (dimensionless) of one run.
struct Errors {
  std::vector<std::pair<std::string, double>> parts;
  /// The largest part, and its name.
  std::pair<std::string, double> worst() const;
};

/// A machine with a closed form. One object serves many runs: start()
/// resets what observe() gathers.
class ClosedFormCase {
 public:
  virtual ~ClosedFormCase() = default;
  /// e.g. "atwood_1_2", and what is compared, for the report.
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;
  /// Frames of 1/60 s to run.
  virtual int frames() const = 0;
  /// A fresh scene at the case's settings (the caller sets the budget).
  virtual Scene make() const = 0;
  /// Called on the fresh scene before its first step.
  virtual void start(const Scene& scene) = 0;
  /// Called after every frame.
  virtual void observe(const Scene& /*scene*/, int /*frame*/) {}
  /// The errors after the last frame.
  virtual Errors errors(const Scene& scene) const = 0;
};

/// Every case, in report order, loading scene files from `scenes_dir`.
std::vector<std::unique_ptr<ClosedFormCase>> tradeCases(const std::filesystem::path& scenes_dir);

/// The Atwood cases as segmented ropes of `segments` rigid cylinders
/// (`reeve segment`, the paper's baseline of sec. 5), against the closed
/// form of a heavy uniform chain. Same names as their cable cases.
std::vector<std::unique_ptr<ClosedFormCase>> ropeCases(const std::filesystem::path& scenes_dir, int segments);

}  // namespace reeve::bench
