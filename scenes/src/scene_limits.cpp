#include "scene_limits.h"

#include "reeve/scene/scene.h"

namespace reeve::scene_detail {
namespace {

// The array under `key` of `object`, if `object` is an object with one.
const nlohmann::json* arrayAt(const nlohmann::json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it != object.end() && it->is_array() ? &*it : nullptr;
}

}  // namespace

void refuseOversizedScene(const nlohmann::json& document, const std::string& source) {
  std::size_t joints = 0;
  for (const char* key : {"hinges", "joints"}) {
    const nlohmann::json* list = arrayAt(document, key);
    if (!list) continue;
    if (joints + list->size() > kMaxSceneJoints)
      throw SceneError(source, "/" + std::string(key) + "/" + std::to_string(kMaxSceneJoints - joints),
                       "at most " + std::to_string(kMaxSceneJoints) + " hinges and joints together",
                       std::to_string(joints + list->size()));
    joints += list->size();
  }
  const nlohmann::json* cables = arrayAt(document, "cables");
  if (!cables) return;
  std::size_t links = 0;
  for (std::size_t c = 0; c < cables->size(); ++c) {
    const nlohmann::json* list = arrayAt((*cables)[c], "links");
    if (!list) continue;
    if (links + list->size() > kMaxSceneLinks)
      throw SceneError(source, "/cables/" + std::to_string(c) + "/links/" + std::to_string(kMaxSceneLinks - links),
                       "at most " + std::to_string(kMaxSceneLinks) + " links in all cables together",
                       "more");
    links += list->size();
  }
}

}  // namespace reeve::scene_detail
