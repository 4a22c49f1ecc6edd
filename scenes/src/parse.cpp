#include "build.h"
#include "scene_limits.h"
#include "magnitudes.h"
#include "parse_json.h"
#include "reeve/scene/scene.h"
#include "schema_validate.h"

namespace reeve {

Scene parseScene(const std::string& json_text, const std::string& source_name) {
  nlohmann::json document = scene_detail::parseJson(json_text, source_name);
  scene_detail::refuseOversizedScene(document, source_name);
  scene_detail::integralNumbersAsIntegers(document);
  scene_detail::validateSceneSchema(document, source_name);
  scene_detail::refuseHugeNumbers(document, source_name);
  return scene_detail::buildScene(document, source_name);
}

}  // namespace reeve
