// Helpers for the scene tests: a small valid scene to break in one place,
// and the SceneError a text produces.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "reeve/scene/scene.h"

namespace reeve::test {

inline const std::filesystem::path kScenesDir = REEVE_SCENES_DIR;

inline std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A valid scene: a hinged wheel, a box and a sphere hanging from a rope.
inline constexpr const char* kBase = R"({
  "name": "base",
  "solver": {},
  "bodies": [
    {"name": "wheel", "shape": {"type": "cylinder", "radius_m": 0.5, "half_length_m": 0.1},
     "density_kg_per_m3": 1000, "position_m": [0, 0, 0]},
    {"name": "crate", "shape": {"type": "box", "half_extents_m": [0.2, 0.2, 0.2]},
     "mass_kg": 2, "position_m": [-0.5, -2, 0]},
    {"name": "ball", "shape": {"type": "sphere", "radius_m": 0.2},
     "mass_kg": 1, "position_m": [0.5, -2, 0]}
  ],
  "hinges": [{"body": "wheel", "anchor_m": [0, 0, 0], "axis": [0, 0, 1]}],
  "cables": [{"name": "rope", "links": [
    {"body": "crate", "type": "attachment", "point_m": [0, 0.2, 0]},
    {"body": "wheel", "type": "rolling", "orientation": "cw"},
    {"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]}]}]
})";

/// `text` with the one occurrence of `from` replaced by `to`.
inline std::string with(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "not in the scene: " << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "twice in the scene: " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// kBase with the one occurrence of `from` replaced by `to`.
inline std::string baseWith(const std::string& from, const std::string& to) {
  return with(kBase, from, to);
}

/// The SceneError parseScene(text, "test.json") throws; nullopt (and a test
/// failure) if it throws none.
inline std::optional<SceneError> errorOf(const std::string& text) {
  try {
    parseScene(text, "test.json");
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no SceneError for:\n" << text;
  return std::nullopt;
}

/// Checks the error of `text`: its JSON pointer exactly, and that expected()
/// and found() contain the given words.
inline void expectError(const std::string& text, const std::string& pointer,
                        const std::string& expected_words, const std::string& found_words) {
  const std::optional<SceneError> e = errorOf(text);
  if (!e) return;
  EXPECT_EQ(e->file(), "test.json");
  EXPECT_EQ(e->jsonPath(), pointer) << e->what();
  EXPECT_NE(e->expected().find(expected_words), std::string::npos) << e->what();
  EXPECT_NE(e->found().find(found_words), std::string::npos) << e->what();
  const std::string shown_path = pointer.empty() ? "(root)" : pointer;
  EXPECT_EQ(std::string(e->what()),
            "test.json: " + shown_path + ": expected " + e->expected() + ", got " + e->found());
}

}  // namespace reeve::test
