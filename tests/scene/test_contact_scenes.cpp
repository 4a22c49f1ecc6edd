// Contacts in scene files: the "ground" object and the per-body contact
// keys load as the README and schema say (defaults included), a scene
// without them does no collision work, bad values are errors, and
// scenes/contacts.json behaves as its description claims.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "scene_test_util.h"

namespace reeve::test {
namespace {

TEST(ContactScenes, SceneWithoutGroundOrCollidingBodiesHasNoContacts) {
  const Scene s = parseScene(kBase, "base.json");
  EXPECT_FALSE(s.world->hasContacts());
  EXPECT_FALSE(s.world->ground().has_value());
  for (BodyId b = 0; b < s.world->bodyCount(); ++b) EXPECT_FALSE(s.world->bodyDef(b).collides);
}

TEST(ContactScenes, DefaultsAreTheSchemaDefaults) {
  const Scene s = parseScene(with(kBase, R"("name": "base",)", R"("name": "base", "ground": {},)"),
                             "ground.json");
  const nlohmann::json schema = nlohmann::json::parse(sceneSchemaJson());
  const nlohmann::json& ground = schema.at("definitions").at("ground").at("properties");
  const nlohmann::json& body = schema.at("definitions").at("body").at("properties");
  ASSERT_TRUE(s.world->ground().has_value());
  const GroundPlane& g = *s.world->ground();
  EXPECT_EQ(g.height_m, ground.at("height_m").at("default").get<double>());
  const auto normal = ground.at("normal").at("default").get<std::vector<double>>();
  EXPECT_EQ(g.normal, Vec3(normal[0], normal[1], normal[2]));
  EXPECT_EQ(g.material.static_friction, ground.at("static_friction").at("default").get<double>());
  EXPECT_EQ(g.material.dynamic_friction, ground.at("dynamic_friction").at("default").get<double>());
  EXPECT_EQ(g.material.restitution, ground.at("restitution").at("default").get<double>());
  const BodyDef& crate = s.world->bodyDef(1);
  EXPECT_EQ(crate.material.static_friction, body.at("static_friction").at("default").get<double>());
  EXPECT_EQ(crate.material.dynamic_friction, body.at("dynamic_friction").at("default").get<double>());
  EXPECT_EQ(crate.material.restitution, body.at("restitution").at("default").get<double>());
  EXPECT_EQ(crate.collides, body.at("collides").at("default").get<bool>());
  EXPECT_TRUE(s.world->hasContacts());
}

TEST(ContactScenes, GivenValuesAreLoaded) {
  const Scene s = parseScene(
      with(with(kBase, R"("name": "base",)",
                R"("name": "base", "ground": {"height_m": -3, "normal": [0, 2, 0], "static_friction": 0.9, "dynamic_friction": 0.7, "restitution": 0.25},)"),
           R"("mass_kg": 2,)",
           R"("mass_kg": 2, "static_friction": 0.8, "dynamic_friction": 0.6, "restitution": 0.4, "collides": true,)"),
      "given.json");
  const GroundPlane& g = *s.world->ground();
  EXPECT_EQ(g.height_m, -3.0);
  EXPECT_EQ(g.normal, Vec3::UnitY());
  EXPECT_EQ(g.material.static_friction, 0.9);
  EXPECT_EQ(g.material.dynamic_friction, 0.7);
  EXPECT_EQ(g.material.restitution, 0.25);
  const BodyDef& crate = s.world->bodyDef(1);
  EXPECT_EQ(crate.material.static_friction, 0.8);
  EXPECT_EQ(crate.material.dynamic_friction, 0.6);
  EXPECT_EQ(crate.material.restitution, 0.4);
  EXPECT_TRUE(crate.collides);
}

TEST(ContactScenes, BadValuesAreErrors) {
  const std::string ground = R"("name": "base",)";
  expectError(with(kBase, ground, R"("name": "base", "ground": {"normal": [0, 0, 0]},)"),
              "/ground/normal", "a non-zero normal", "[0,0,0]");
  const std::optional<SceneError> e =
      errorOf(with(kBase, ground, R"("name": "base", "ground": {"restitution": 1.5},)"));
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->jsonPath(), "/ground/restitution");
  const std::optional<SceneError> f =
      errorOf(baseWith(R"("mass_kg": 2,)", R"("mass_kg": 2, "static_friction": -1,)"));
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->jsonPath(), "/bodies/1/static_friction");
  const std::optional<SceneError> g =
      errorOf(with(kBase, ground, R"("name": "base", "ground": {"friction": 1},)"));
  ASSERT_TRUE(g.has_value());
}

TEST(ContactScenes, ContactsSceneBehavesAsDescribed) {
  Scene s = loadScene(kScenesDir / "contacts.json");
  World& w = *s.world;
  const BodyId ball = *w.findBody("ball"), slider = *w.findBody("slider");
  const double dt = 1.0 / s.frame_rate_hz;
  // Ball: dropped from 2 m (lowest point), restitution 0.7 (ball and
  // ground): first rebound to 0.49 x 2 m, within 3 %.
  const double r = 0.25, drop = 2.0, e = 0.7;
  bool bounced = false, peaked = false;
  double peak = 0.0;
  // Slider: from rest on the 35 deg ramp (static box), mu_d 0.3 (mean of
  // two 0.3): a = g (sin 35 - 0.3 cos 35) along the ramp.
  const double tilt = 35.0 * std::numbers::pi / 180.0;
  const Vec3 downhill(std::cos(tilt), -std::sin(tilt), 0.0);
  const double a_expected = 9.81 * (std::sin(tilt) - 0.3 * std::cos(tilt));
  double v1 = 0.0, v2 = 0.0;
  for (int f = 1; f <= s.frameCount(); ++f) {
    w.step(dt);
    const BodyState& b = w.body(ball);
    if (!bounced) bounced = b.v.y() > 0.0;
    else if (!peaked && b.v.y() < 0.0) peaked = true;
    else if (!peaked) peak = b.x.y() - r;
    if (f == 12) v1 = w.body(slider).v.dot(downhill);
    if (f == 42) v2 = w.body(slider).v.dot(downhill);
  }
  const double a = (v2 - v1) / (30 * dt);
  std::printf("  ball rises to %.4f m (e^2 x 2 m = %.4f); slider a = %.4f m/s^2 (%.4f)\n", peak,
              e * e * drop, a, a_expected);
  EXPECT_NEAR(peak, e * e * drop, 0.03 * e * e * drop);
  EXPECT_NEAR(a, a_expected, 0.02 * a_expected);
  // The stack of three stands still: its top box within 2 mm of where it
  // was put (measured 0.6 mm at the scene's 20 x 4; 4 mm at 20 x 1, where
  // one Gauss-Seidel pass over ground and box-box contacts leaves the small
  // boxes rocking).
  const Vec3 top = w.body(*w.findBody("stack_3")).x;
  std::printf("  top of the stack moved %.3g m\n", (top - Vec3(6.5, 1.5, 0.0)).norm());
  EXPECT_LT((top - Vec3(6.5, 1.5, 0.0)).norm(), 2e-3);
}

}  // namespace
}  // namespace reeve::test
