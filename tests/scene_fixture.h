// Loading and stepping the shipped scenes in tests.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "reeve/cable/cable.h"
#include "reeve/scene/scene.h"
#include "solver_budgets.h"

namespace reeve::test {

/// The shipped scene files (scenes/*.json but the schema), sorted by name.
inline std::vector<std::filesystem::path> shippedSceneFiles() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(REEVE_SCENES_DIR))
    if (entry.path().extension() == ".json" && entry.path().filename() != "scene.schema.json")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

/// Loads scenes/NAME.json from the source tree.
inline Scene scene(const std::string& name) { return loadScene(std::string(REEVE_SCENES_DIR) + "/" + name + ".json"); }

/// scenes/NAME.json with its solver budget replaced: `substeps` per frame,
/// `iterations` per substep.
inline Scene scene(const std::string& name, int substeps, int iterations) {
  Scene s = scene(name);
  s.world->settings().substeps = substeps;
  s.world->settings().iterations = iterations;
  return s;
}

/// The id of the body named `name` (the scene must have it).
inline BodyId body(const Scene& s, const std::string& name) { return *s.world->findBody(name); }

/// The index of the cable named `name` (a test failure, and 0, if none).
inline int cable(const Scene& s, const std::string& name) {
  const auto& all = s.cables->cables();
  for (int c = 0; c < static_cast<int>(all.size()); ++c)
    if (all[c].name == name) return c;
  ADD_FAILURE() << "no cable " << name;
  return 0;
}

/// A scene's "solver" member at budget `b` (60 frames a second), for
/// scenes written as JSON in a test.
inline std::string solverJson(const Budget& b) {
  return R"("solver": {"frame_rate_hz": 60, "substeps": )" + std::to_string(b.substeps) + R"(, "iterations": )" +
         std::to_string(b.iterations) + R"(, "method": ")" + solverMethodName(b.solver) + R"("})";
}

/// One frame of the scene.
inline void frame(Scene& s) { s.world->step(1.0 / s.frame_rate_hz); }

}  // namespace reeve::test
