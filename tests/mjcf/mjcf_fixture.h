// Loading the MJCF test models (models/) and small models written inline.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "reeve/cable/cable.h"
#include "reeve/scene/mjcf.h"
#include "reeve/scene/scene.h"

namespace reeve::test {

inline std::string mjcfModel(const std::string& name) { return std::string(REEVE_MJCF_MODELS) + "/" + name + ".xml"; }

/// The scene importMjcf makes of models/NAME.xml.
inline Scene importedScene(const std::string& name, MjcfWheels wheels = MjcfWheels::Fixed) {
  const std::string path = mjcfModel(name);
  MjcfOptions options;
  options.wheels = wheels;
  MjcfImport model = importMjcf(path, options);
  Scene scene = parseScene(model.scene_json, path);
  scene.not_imported = model.unmapped;
  return scene;
}

/// Writes `xml` to a file of its own in the test's temporary folder and
/// returns its path.
inline std::filesystem::path writeModel(const std::string& name, const std::string& xml) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "reeve_mjcf_tests";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / (name + ".xml");
  std::ofstream(path) << xml;
  return path;
}

inline BodyId bodyNamed(const Scene& s, const std::string& name) {
  const auto id = s.world->findBody(name);
  EXPECT_TRUE(id.has_value()) << name;
  return id.value_or(0);
}

}  // namespace reeve::test
