// libFuzzer harness of the MuJoCo model importer (issue 32): bytes written
// as an .xml file, imported (mjcf.h) and the scene it makes built, as
// `reeve run MODEL.xml` does. A crash, a hang, a sanitizer finding or an
// exception other than SceneError is a bug. tests/fuzz/README.md.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "reeve/scene/mjcf.h"
#include "reeve/scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The importer reads a file (its includes are relative to it): one per
  // process, written again for each input.
  static const std::string path =
      (std::filesystem::temp_directory_path() / ("reeve_fuzz_mjcf_" + std::to_string(getpid()) + ".xml")).string();
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    reeve::loadScene(path);
  } catch (const reeve::SceneError&) {
  }
  return 0;
}
