// Generated machines as scene files (`reeve generate`), apart from
// machines.h so that only what writes them pays for nlohmann/json.hpp.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "reeve/machines/machines.h"

namespace reeve::machines {

/// The machine as a scene file (scenes/README.md), as `reeve generate
/// hilbert` writes it. Throws std::invalid_argument for a level outside
/// [1, 4] or a negative slack, mass, radius or pitch.
nlohmann::ordered_json hilbertSceneJson(const HilbertSpec& spec);
/// The text of a generated scene file: indented by 2, but any array or
/// object that fits in 200 characters on one line, so a body, a hinge or a
/// link reads as one line. Ends with a newline.
std::string sceneFileText(const nlohmann::ordered_json& doc);

}  // namespace reeve::machines
