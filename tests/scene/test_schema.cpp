// scene.schema.json: every scene file satisfies it (checked with valijson
// directly, not through the library), its objects are closed, and its
// documented defaults are the ones the loader applies.
#include <nlohmann/json.hpp>
#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validator.hpp>

#include "scene_test_util.h"

namespace reeve::test {
namespace {

using nlohmann::json;

json schemaFile() { return json::parse(readFile(kScenesDir / "scene.schema.json")); }

TEST(SceneSchema, EverySceneFileValidates) {
  const json schema_json = schemaFile();
  valijson::Schema schema;
  valijson::SchemaParser(valijson::SchemaParser::kDraft7)
      .populateSchema(valijson::adapters::NlohmannJsonAdapter(schema_json), schema);
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kScenesDir)) {
    const std::filesystem::path& p = entry.path();
    if (p.extension() != ".json" || p.filename() == "scene.schema.json") continue;
    const json scene = json::parse(readFile(p));
    valijson::ValidationResults results;
    EXPECT_TRUE(valijson::Validator().validate(
        schema, valijson::adapters::NlohmannJsonAdapter(scene), &results))
        << p << ": " << (results.numErrors() ? results.begin()->description : "");
    ++count;
  }
  EXPECT_GE(count, 3);
  // And the schema rejects something: a negative radius.
  json bad = json::parse(readFile(kScenesDir / "simple.json"));
  bad["bodies"][0]["shape"]["radius_m"] = -0.5;
  EXPECT_FALSE(valijson::Validator().validate(schema, valijson::adapters::NlohmannJsonAdapter(bad),
                                              nullptr));
}

void expectClosed(const json& node, const std::string& where) {
  if (node.is_object()) {
    if (node.value("type", json()) == "object") {
      EXPECT_EQ(node.value("additionalProperties", json()), false) << where;
      for (const json& key : node.value("required", json::array()))
        EXPECT_TRUE(node.at("properties").contains(key.get<std::string>())) << where << " " << key;
    }
    for (const auto& [key, child] : node.items()) expectClosed(child, where + "/" + key);
  } else if (node.is_array()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      expectClosed(node[i], where + "/" + std::to_string(i));
  }
}

// Editors complete and check keys from the schema a scene names: each
// shipped scene names the file beside it, and the schema has an absolute id.
TEST(SceneSchema, HasAnIdAndEveryShippedSceneNamesIt) {
  const std::string id = schemaFile().at("$id").get<std::string>();
  EXPECT_EQ(id.rfind("https://", 0), 0u) << id;
  EXPECT_EQ(id.substr(id.rfind('/') + 1), "scene.schema.json");
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kScenesDir)) {
    const std::filesystem::path& p = entry.path();
    if (p.extension() != ".json" || p.filename() == "scene.schema.json") continue;
    const nlohmann::ordered_json scene = nlohmann::ordered_json::parse(readFile(p));
    ASSERT_FALSE(scene.empty()) << p;
    EXPECT_EQ(scene.begin().key(), "$schema") << p << ": editors read it first";
    EXPECT_EQ(scene.value("$schema", ""), "scene.schema.json") << p;
    EXPECT_TRUE(std::filesystem::is_regular_file(p.parent_path() / scene.value("$schema", ""))) << p;
    ++count;
  }
  EXPECT_GE(count, 17);
}

TEST(SceneSchema, EveryObjectIsClosedAndListsItsRequiredKeys) {
  const json schema = schemaFile();
  EXPECT_EQ(schema.at("$schema"), "http://json-schema.org/draft-07/schema#");
  expectClosed(schema, "");
}

TEST(SceneSchema, DefaultsAreWhatTheLoaderApplies) {
  const json schema = schemaFile();
  const json& defs = schema.at("definitions");
  const json& solver = defs.at("solver").at("properties");
  const Scene s = parseScene(R"({
    "name": "defaults", "solver": {},
    "bodies": [
      {"name": "post", "shape": {"type": "box", "half_extents_m": [1, 1, 1]},
       "static": true, "position_m": [0, 0, 0]},
      {"name": "ball", "shape": {"type": "sphere", "radius_m": 0.5},
       "mass_kg": 1, "position_m": [0, -2, 0]}],
    "hinges": [{"body": "ball", "anchor_m": [0, 0, 0], "axis": [1, 0, 0]}],
    "cables": [{"name": "c", "links": [
      {"body": "post", "type": "attachment", "point_m": [0, -1, 0]},
      {"body": "ball", "type": "attachment", "point_m": [0, 0.5, 0]}]}],
    "camera": {"eye_m": [0, 0, 5], "target_m": [0, 0, 0]}})",
                             "defaults.json");
  EXPECT_DOUBLE_EQ(s.frame_rate_hz, solver.at("frame_rate_hz").at("default").get<double>());
  EXPECT_EQ(s.world->settings().substeps, solver.at("substeps").at("default").get<int>());
  EXPECT_EQ(s.world->settings().iterations, solver.at("iterations").at("default").get<int>());
  EXPECT_EQ(solverMethodName(s.world->settings().solver), solver.at("method").at("default").get<std::string>());
  const auto gravity = solver.at("gravity_m_per_s2").at("default").get<std::vector<double>>();
  EXPECT_EQ(s.world->settings().gravity, Vec3(gravity[0], gravity[1], gravity[2]));
  EXPECT_DOUBLE_EQ(s.duration_s,
                   schema.at("properties").at("duration_s").at("default").get<double>());
  EXPECT_EQ(s.description,
            schema.at("properties").at("description").at("default").get<std::string>());

  const json& body = defs.at("body").at("properties");
  EXPECT_EQ(body.at("static").at("default"), false);
  EXPECT_GT(s.world->body(1).inv_mass, 0.0);
  EXPECT_EQ(s.world->body(0).inv_mass, 0.0);
  EXPECT_EQ(s.world->body(1).v, Vec3::Zero());
  EXPECT_EQ(s.world->body(1).q.coeffs(), Quat::Identity().coeffs());

  const json& hinge = defs.at("hinge").at("properties");
  EXPECT_EQ(hinge.at("other").at("default"), "world");
  ASSERT_EQ(s.world->hinges().size(), 1u);
  EXPECT_EQ(s.world->hinges()[0].b, kWorldBody);
  EXPECT_EQ(s.world->hinges()[0].compliance, hinge.at("compliance").at("default").get<double>());

  EXPECT_EQ(s.world->body(1).linear_damping,
            body.at("linear_damping_per_s").at("default").get<double>());
  EXPECT_EQ(s.world->body(1).angular_damping,
            body.at("angular_damping_per_s").at("default").get<double>());

  const json& cable = defs.at("cable").at("properties");
  EXPECT_EQ(s.world->path(s.cables->cables()[0].joints[0].path).compliance,
            cable.at("compliance_m_per_N").at("default").get<double>());
  EXPECT_EQ(s.world->path(s.cables->cables()[0].joints[0].path).damping,
            cable.at("damping_N_s_per_m").at("default").get<double>());
  EXPECT_EQ(s.cables->cables()[0].closed, cable.at("closed").at("default").get<bool>());
  EXPECT_NEAR(s.cables->restLength(0, 0), 0.5, 1e-12);  // taut: from y = -1 to y = -1.5

  const json& camera = defs.at("camera").at("properties");
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_DOUBLE_EQ(s.camera->fov_y_deg, camera.at("fov_y_deg").at("default").get<double>());
  const auto up = camera.at("up").at("default").get<std::vector<double>>();
  EXPECT_EQ(s.camera->up, Vec3(up[0], up[1], up[2]));
}

TEST(SceneSchema, LinkDefaultsAreWhatTheLoaderApplies) {
  const json rolling = schemaFile().at("definitions").at("rolling_link").at("properties");
  const Scene s = parseScene(kBase, "base.json");
  const Link& wheel = s.cables->cables()[0].links[1];
  ASSERT_EQ(wheel.type, LinkType::Rolling);
  EXPECT_EQ(wheel.plane_offset, rolling.at("plane_offset_m").at("default").get<double>());
  EXPECT_EQ(wheel.active, rolling.at("active").at("default").get<bool>());
  EXPECT_FALSE(rolling.at("stored_m").contains("default"));  // depends on the link: see README
}

TEST(SceneSchema, BaseTestSceneBuilds) {
  const Scene s = parseScene(kBase, "base.json");
  EXPECT_EQ(s.world->bodyCount(), 3);
  EXPECT_NEAR(s.world->bodyMass(0), 1000.0 * std::acos(-1.0) * 0.25 * 0.2, 1e-9);
  EXPECT_EQ(s.cables->cables()[0].joints.size(), 2u);
  EXPECT_FALSE(s.camera.has_value());
}

}  // namespace
}  // namespace reeve::test
