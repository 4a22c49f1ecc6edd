#include "schema_message.h"

#include <algorithm>
#include <string_view>

#include "describe.h"
#include "schema_walk.h"

namespace reeve::scene_detail {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;
using Schemas = std::vector<const ordered_json*>;

// valijson (1.0) descriptions this file phrases, by their fixed beginnings.
constexpr std::string_view kMissing = "Missing required property '";
constexpr std::string_view kUnknown =
    "Object contains a property that could not be validated using 'properties' or "
    "'additionalProperties' constraints: '";
constexpr std::string_view kType = "Value type not permitted by 'type' constraint.";
constexpr std::string_view kBound = "Expected number ";
constexpr std::string_view kEnum = "Failed to match against any enum values.";
constexpr std::string_view kConst = "Failed to match expected value set by 'const' constraint.";
constexpr std::string_view kItems = "Array should contain no ";
constexpr std::string_view kShortString = "String should be no fewer than ";

bool startsWith(const std::string& text, std::string_view prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

// The name in "<prefix>NAME'." descriptions.
std::string nameAfter(const std::string& description, std::string_view prefix) {
  const std::size_t end = description.size() >= prefix.size() + 2 ? description.size() - 2 : 0;
  return end > prefix.size() ? description.substr(prefix.size(), end - prefix.size()) : "";
}

const ordered_json* firstWith(const Schemas& schemas, const char* key) {
  for (const ordered_json* s : schemas)
    if (s->contains(key)) return s;
  return nullptr;
}

std::string plural(const std::string& type) { return type == "boolean" ? "booleans" : type + "s"; }

std::string withArticle(const std::string& type) {
  if (type == "null") return "null";
  if (type == "boolean") return "true or false";
  return (type == "integer" || type == "object" || type == "array" ? "an " : "a ") + type;
}

std::string arrayPhrase(const ordered_json& schema) {
  const int min = schema.value("minItems", -1);
  const int max = schema.value("maxItems", -1);
  std::string noun = "items";
  if (const auto items = schema.find("items"); items != schema.end() && items->is_object() &&
                                               items->contains("type") &&
                                               items->at("type").is_string())
    noun = plural(items->at("type").get<std::string>());
  if (min >= 0 && min == max) return "an array of " + std::to_string(min) + " " + noun;
  if (min >= 0 && max >= 0)
    return "an array of " + std::to_string(min) + " to " + std::to_string(max) + " " + noun;
  if (min >= 0) return "an array of at least " + std::to_string(min) + " " + noun;
  if (max >= 0) return "an array of at most " + std::to_string(max) + " " + noun;
  return noun == "items" ? "an array" : "an array of " + noun;
}

// "a number", "an array of 3 numbers", "a string or null", from "type".
std::string typePhrase(const Schemas& schemas) {
  const ordered_json* s = firstWith(schemas, "type");
  if (!s) return "a value";
  const ordered_json& type = s->at("type");
  std::vector<std::string> types;
  if (type.is_string()) types.push_back(type.get<std::string>());
  if (type.is_array())
    for (const ordered_json& t : type)
      if (t.is_string()) types.push_back(t.get<std::string>());
  std::string phrase;
  for (const std::string& t : types)
    phrase += (phrase.empty() ? "" : " or ") + (t == "array" ? arrayPhrase(*s) : withArticle(t));
  return phrase.empty() ? "a value" : phrase;
}

// "> 0 and < 180" from the numeric bounds of the first schema that has any.
std::string boundsPhrase(const Schemas& schemas) {
  static const std::pair<const char*, const char*> kBounds[] = {
      {"minimum", ">="}, {"exclusiveMinimum", ">"}, {"maximum", "<="}, {"exclusiveMaximum", "<"}};
  for (const ordered_json* s : schemas) {
    std::string phrase;
    for (const auto& [key, op] : kBounds)
      if (const auto bound = s->find(key); bound != s->end() && bound->is_number())
        phrase += std::string(phrase.empty() ? "" : " and ") + op + " " + bound->dump();
    if (!phrase.empty()) return phrase;
  }
  return "within its bounds";
}

std::string literalList(const ordered_json& values) {
  std::string list;
  for (const ordered_json& v : values) list += (list.empty() ? "" : ", ") + v.dump();
  return list;
}

// The keys an object may have: those every closed ("additionalProperties":
// false) schema at the site lists, in the first one's order.
std::vector<std::string> allowedKeys(const Schemas& schemas) {
  Schemas closed;
  for (const ordered_json* s : schemas)
    if (const auto extra = s->find("additionalProperties");
        extra != s->end() && *extra == false && s->contains("properties"))
      closed.push_back(s);
  std::vector<std::string> keys;
  if (closed.empty()) return keys;
  for (const auto& item : closed.front()->at("properties").items()) {
    const std::string& key = item.key();  // a structured binding: clang 14 cannot capture one
    if (std::all_of(closed.begin(), closed.end(),
                    [&](const ordered_json* s) { return s->at("properties").contains(key); }))
      keys.push_back(key);
  }
  return keys;
}

// A value whose kind may be wrong: strings and numbers as written, other
// kinds described.
std::string foundValue(const json* value) {
  if (!value) return "nothing";
  return value->is_string() || value->is_number() ? literal(*value) : describe(*value);
}

}  // namespace

SchemaProblem phraseSchemaError(const ordered_json& schema, const json& document,
                                const std::vector<std::string>& tokens,
                                const std::string& description) {
  std::string pointer;
  for (const std::string& token : tokens) pointer = childPointer(pointer, token);
  const SchemaSite site = schemaSite(schema, document, tokens);

  if (startsWith(description, kMissing))
    return {pointer, "required property " + quote(nameAfter(description, kMissing)), "nothing"};
  if (startsWith(description, kUnknown)) {
    const std::string key = nameAfter(description, kUnknown);
    return {childPointer(pointer, key),
            "no property " + quote(key) + " (allowed: " + nameList(allowedKeys(site.schemas), 100) +
                ")",
            quote(key)};
  }
  if (startsWith(description, kType))
    return {pointer, typePhrase(site.schemas), site.value ? describe(*site.value) : "nothing"};
  if (startsWith(description, kBound))
    return {pointer, typePhrase(site.schemas) + " " + boundsPhrase(site.schemas),
            foundValue(site.value)};
  if (startsWith(description, kEnum)) {
    const ordered_json* s = firstWith(site.schemas, "enum");
    return {pointer, s ? "one of " + literalList(s->at("enum")) : "an allowed value",
            foundValue(site.value)};
  }
  if (startsWith(description, kConst)) {
    const ordered_json* s = firstWith(site.schemas, "const");
    return {pointer, s ? s->at("const").dump() : "the one allowed value", foundValue(site.value)};
  }
  if (startsWith(description, kItems)) {
    const ordered_json* s = firstWith(site.schemas, "minItems");
    if (!s) s = firstWith(site.schemas, "maxItems");
    return {pointer, s ? arrayPhrase(*s) : "another number of items",
            site.value ? describe(*site.value) : "nothing"};
  }
  if (startsWith(description, kShortString)) {
    const ordered_json* s = firstWith(site.schemas, "minLength");
    const int min = s ? s->value("minLength", 1) : 1;
    return {pointer,
            min == 1 ? "a non-empty string"
                     : "a string of at least " + std::to_string(min) + " characters",
            foundValue(site.value)};
  }
  return {pointer, "a value allowed by the scene schema (" + description + ")",
          site.value ? describe(*site.value) : "nothing"};
}

}  // namespace reeve::scene_detail
