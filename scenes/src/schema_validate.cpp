#include "schema_validate.h"

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validator.hpp>

#include "reeve/scene/scene.h"
#include "schema_message.h"

namespace reeve::scene_detail {
namespace {

// The embedded schema, parsed once: ordered (for messages that list keys in
// schema order) and compiled for valijson.
struct CompiledSchema {
  nlohmann::ordered_json ordered;
  nlohmann::json plain;
  valijson::Schema schema;

  CompiledSchema()
      : ordered(nlohmann::ordered_json::parse(sceneSchemaJson())),
        plain(nlohmann::json::parse(sceneSchemaJson())) {
    valijson::SchemaParser(valijson::SchemaParser::kDraft7)
        .populateSchema(valijson::adapters::NlohmannJsonAdapter(plain), schema);
  }
};

const CompiledSchema& compiledSchema() {
  static const CompiledSchema compiled;
  return compiled;
}

// valijson reports each violation where it happens, then a summary at every
// enclosing constraint ("Failed to validate item #2 in array.", ...); the
// first report that is not such a summary is the first violation.
bool isSummary(const std::string& description) {
  return description.rfind("Failed to validate", 0) == 0;
}

// valijson context {"<root>", "[bodies]", "[2]"} -> tokens {"bodies", "2"}.
std::vector<std::string> tokensOf(const std::vector<std::string>& context) {
  std::vector<std::string> tokens;
  for (std::size_t i = 1; i < context.size(); ++i) {
    const std::string& c = context[i];
    tokens.push_back(
        c.size() >= 2 && c.front() == '[' && c.back() == ']' ? c.substr(1, c.size() - 2) : c);
  }
  return tokens;
}

}  // namespace

void validateSceneSchema(const nlohmann::json& document, const std::string& source) {
  const CompiledSchema& compiled = compiledSchema();
  valijson::ValidationResults results;
  if (valijson::Validator().validate(compiled.schema,
                                     valijson::adapters::NlohmannJsonAdapter(document), &results))
    return;
  const valijson::ValidationResults::Error* first = nullptr;
  for (const auto& error : results)
    if (!isSummary(error.description)) {
      first = &error;
      break;
    }
  if (!first) first = &*results.begin();
  const SchemaProblem problem =
      phraseSchemaError(compiled.ordered, document, tokensOf(first->context), first->description);
  throw SceneError(source, problem.pointer, problem.expected, problem.found);
}

bool satisfiesSchema(const nlohmann::json& schema, const nlohmann::json& value) {
  valijson::Schema compiled;
  valijson::SchemaParser().populateSchema(valijson::adapters::NlohmannJsonAdapter(schema), compiled);
  return valijson::Validator().validate(compiled, valijson::adapters::NlohmannJsonAdapter(value), nullptr);
}

}  // namespace reeve::scene_detail
