// Finding the subschemas that apply at a place in a document, to phrase
// schema errors from the schema itself (allowed keys, types, bounds).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace reeve::scene_detail {

/// A place in a document: the value there (nullptr if absent) and the
/// object subschemas of the scene schema that apply to it.
struct SchemaSite {
  const nlohmann::json* value = nullptr;
  std::vector<const nlohmann::ordered_json*> schemas;
};

/// Walks `document` and `schema` (the root, for "#/..." references) down
/// the JSON pointer `tokens`: at each step "properties" of an object,
/// "items" of an array, and, transitively, "$ref" targets, "allOf" members
/// and the "then" or "else" branch that the value selects with "if".
SchemaSite schemaSite(const nlohmann::ordered_json& schema, const nlohmann::json& document,
                      const std::vector<std::string>& tokens);

}  // namespace reeve::scene_detail
