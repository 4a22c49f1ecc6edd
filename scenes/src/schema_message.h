// Turning one valijson error into "PATH: expected ..., got ..." words.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace reeve::scene_detail {

/// A schema violation in SceneError terms.
struct SchemaProblem {
  std::string pointer;   ///< JSON pointer of the offending value
  std::string expected;  ///< e.g. `a number > 0`
  std::string found;     ///< e.g. `-0.5`
};

/// Phrases the valijson error `description` reported at the place `tokens`
/// of `document`, reading the allowed keys, types, bounds and values from
/// the subschemas of `schema` that apply there. Unknown kinds of error keep
/// valijson's description in `expected`.
SchemaProblem phraseSchemaError(const nlohmann::ordered_json& schema,
                                const nlohmann::json& document,
                                const std::vector<std::string>& tokens,
                                const std::string& description);

}  // namespace reeve::scene_detail
