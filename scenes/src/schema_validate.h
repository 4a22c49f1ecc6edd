// JSON Schema validation of a scene document (scenes/scene.schema.json).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace reeve::scene_detail {

/// Validates `document` against the embedded scene schema (valijson,
/// draft-07). Throws SceneError for the first violation in document order,
/// phrased from the schema: unknown and missing keys, wrong types, numbers
/// out of bounds, values not allowed, wrong array sizes.
void validateSceneSchema(const nlohmann::json& document, const std::string& source);

/// Whether `value` satisfies the self-contained JSON Schema `schema`
/// (valijson, draft-07). The one other place valijson is compiled in, so
/// that its templates are instantiated in this file alone.
bool satisfiesSchema(const nlohmann::json& schema, const nlohmann::json& value);

}  // namespace reeve::scene_detail
