// What a scene may hold before it is built (scene.h, kMaxSceneJoints ...).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace reeve::scene_detail {

/// Throws SceneError at the entry that passes kMaxSceneJoints (hinges and
/// joints together) or kMaxSceneLinks (links of all cables together).
/// Runs before the schema, so that its cost never meets such a document;
/// a value of the wrong type is left for the schema to name.
void refuseOversizedScene(const nlohmann::json& document, const std::string& source);

}  // namespace reeve::scene_detail
