// libFuzzer harness, parse only (issue 27): bytes to the scene loader and
// nothing more, thousands of inputs a second, for the limits and errors
// of parsing, schema and building. A crash, a sanitizer finding or an
// exception other than SceneError is a bug. tests/fuzz/README.md.
#include <cstdint>
#include <string>

#include "reeve/scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    reeve::parseScene(std::string(reinterpret_cast<const char*>(data), size), "<fuzz>");
  } catch (const reeve::SceneError&) {
  }
  return 0;
}
