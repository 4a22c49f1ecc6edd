#include "schema_walk.h"

#include "schema_validate.h"

namespace reeve::scene_detail {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

// Whether `value` satisfies the self-contained subschema `condition` (an
// "if" of the scene schema).
bool satisfies(const ordered_json& condition, const json& value) {
  return satisfiesSchema(json::parse(condition.dump()), value);
}

void collect(const ordered_json& node, const json* value, const ordered_json& root,
             std::vector<const ordered_json*>& out) {
  if (!node.is_object()) return;  // boolean schema: says nothing to phrase
  out.push_back(&node);
  if (const auto ref = node.find("$ref"); ref != node.end() && ref->is_string()) {
    const std::string target = ref->get<std::string>();
    if (target.rfind('#', 0) == 0) {
      const ordered_json::json_pointer pointer(target.substr(1));
      if (root.contains(pointer)) collect(root.at(pointer), value, root, out);
    }
  }
  if (const auto all = node.find("allOf"); all != node.end() && all->is_array())
    for (const ordered_json& member : *all) collect(member, value, root, out);
  if (const auto condition = node.find("if"); condition != node.end() && value) {
    const char* branch = satisfies(*condition, *value) ? "then" : "else";
    if (const auto chosen = node.find(branch); chosen != node.end())
      collect(*chosen, value, root, out);
  }
}

}  // namespace

SchemaSite schemaSite(const ordered_json& schema, const json& document,
                      const std::vector<std::string>& tokens) {
  SchemaSite site{&document, {}};
  collect(schema, site.value, schema, site.schemas);
  for (const std::string& token : tokens) {
    const json* parent = site.value;
    const json* child = nullptr;
    if (parent && parent->is_object() && parent->contains(token)) {
      child = &parent->at(token);
    } else if (parent && parent->is_array() && !token.empty() && token.size() < 16 &&
               token.find_first_not_of("0123456789") == std::string::npos &&
               std::stoull(token) < parent->size()) {
      child = &parent->at(std::stoull(token));
    }
    std::vector<const ordered_json*> schemas;
    for (const ordered_json* s : site.schemas) {
      const bool in_array = parent && parent->is_array();
      const auto sub = in_array ? s->find("items") : s->find("properties");
      if (sub == s->end()) continue;
      if (in_array) {
        collect(*sub, child, schema, schemas);
      } else if (const auto property = sub->find(token); property != sub->end()) {
        collect(*property, child, schema, schemas);
      }
    }
    site = {child, std::move(schemas)};
  }
  return site;
}

}  // namespace reeve::scene_detail
