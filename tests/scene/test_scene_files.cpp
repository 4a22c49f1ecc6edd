// The scene files load and say what the paper's experiments need.
#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "scene_test_util.h"

namespace reeve::test {
namespace {

using std::numbers::pi;

BodyId bodyNamed(const Scene& s, const std::string& name) {
  const std::optional<BodyId> id = s.world->findBody(name);
  EXPECT_TRUE(id.has_value()) << name;
  return id.value_or(0);
}

void expectVec(const Vec3& actual, const Vec3& expected, double tol = 1e-12) {
  EXPECT_LE((actual - expected).norm(), tol)
      << actual.transpose() << " vs " << expected.transpose();
}

// Paper Fig. 12: bodies of 1, 1 and 2 m^3 and two wheels, times `density`.
void expectFigure12(const Scene& s, double density) {
  EXPECT_DOUBLE_EQ(s.frame_rate_hz, 60.0);
  EXPECT_DOUBLE_EQ(s.duration_s, 5.0);
  EXPECT_EQ(s.frameCount(), 300);
  const World& w = *s.world;
  expectVec(w.settings().gravity, Vec3(0, -10, 0));
  EXPECT_EQ(w.settings().substeps, 10);
  EXPECT_EQ(w.settings().iterations, 2);

  ASSERT_EQ(w.bodyCount(), 5);
  const double wheel_mass = density * pi * 0.5 * 0.5 * 0.5;  // pi r^2 L, L = 2 x 0.25
  EXPECT_NEAR(w.bodyMass(bodyNamed(s, "wheel_left")), wheel_mass, 1e-12 * density);
  EXPECT_NEAR(w.bodyMass(bodyNamed(s, "wheel_right")), wheel_mass, 1e-12 * density);
  EXPECT_NEAR(w.bodyMass(bodyNamed(s, "left_top")), 1.0 * density, 1e-12 * density);
  EXPECT_NEAR(w.bodyMass(bodyNamed(s, "left_bottom")), 1.0 * density, 1e-12 * density);
  EXPECT_NEAR(w.bodyMass(bodyNamed(s, "right")), 2.0 * density, 1e-12 * density);
  expectVec(w.body(bodyNamed(s, "wheel_left")).x, Vec3(-1.5, 0, 0));
  expectVec(w.body(bodyNamed(s, "wheel_right")).x, Vec3(1.5, 0, 0));
  expectVec(w.body(bodyNamed(s, "left_top")).x, Vec3(-2.0, -2.5, 0));
  expectVec(w.body(bodyNamed(s, "left_bottom")).x, Vec3(-2.0, -4.5, 0));
  expectVec(w.body(bodyNamed(s, "right")).x, Vec3(2.0, -3.0, 0));
  expectVec(w.body(bodyNamed(s, "left_bottom")).v, Vec3(1.0, 0, 0));
  expectVec(w.body(bodyNamed(s, "left_top")).v, Vec3::Zero());
  EXPECT_EQ(w.bodyDef(bodyNamed(s, "wheel_left")).shape.type, Shape::Type::Cylinder);
  expectVec(w.bodyDef(bodyNamed(s, "right")).shape.half_extents, Vec3(0.5, 1.0, 0.5));

  ASSERT_EQ(w.hinges().size(), 2u);
  for (const HingeJoint& h : w.hinges()) {
    EXPECT_EQ(h.b, kWorldBody);
    expectVec(h.frame.anchor_a, Vec3::Zero());  // at the wheel's centre
    expectVec(h.frame.axis_b, Vec3::UnitZ());
  }
  EXPECT_EQ(w.hinges()[0].a, bodyNamed(s, "wheel_left"));
  EXPECT_EQ(w.hinges()[1].a, bodyNamed(s, "wheel_right"));

  ASSERT_EQ(s.cables->cables().size(), 1u);
  const Cable& cable = s.cables->cables()[0];
  EXPECT_EQ(cable.name, "cable");
  ASSERT_EQ(cable.links.size(), 5u);
  EXPECT_EQ(cable.joints.size(), 4u);  // paper Table 1: Simple, 4 cable joints
  const char* order[] = {"left_bottom", "left_top", "wheel_left", "wheel_right", "right"};
  const LinkType types[] = {LinkType::Attachment, LinkType::Attachment, LinkType::Rolling,
                            LinkType::Rolling, LinkType::Attachment};
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(cable.links[k].body, bodyNamed(s, order[k])) << k;
    EXPECT_EQ(cable.links[k].type, types[k]) << k;
  }
  EXPECT_EQ(cable.links[2].orientation, -1);
  EXPECT_EQ(cable.links[3].orientation, -1);
  expectVec(cable.links[0].point, Vec3(0, 0.5, 0));
  expectVec(cable.links[1].point, Vec3::Zero());
  expectVec(cable.links[4].point, Vec3(0, 1.0, 0));
  // Taut at the start: up the left side of wheel_left, over both tops, down
  // the right side of wheel_right.
  EXPECT_NEAR(s.cables->restLength(0, 0), 1.5, 1e-12);
  EXPECT_NEAR(s.cables->restLength(0, 1), 2.5, 1e-12);
  EXPECT_NEAR(s.cables->restLength(0, 2), 3.0, 1e-12);
  EXPECT_NEAR(s.cables->restLength(0, 3), 2.0, 1e-12);
  expectVec(s.cables->startPoint(0, 2), Vec3(-1.5, 0.5, 0), 1e-12);
  expectVec(s.cables->endPoint(0, 2), Vec3(1.5, 0.5, 0), 1e-12);

  ASSERT_TRUE(s.camera.has_value());
  expectVec(s.camera->eye, Vec3(0, -2, 13));
  expectVec(s.camera->target, Vec3(0, -2, 0));
  expectVec(s.camera->up, Vec3::UnitY());
  EXPECT_DOUBLE_EQ(s.camera->fov_y_deg, 40.0);
}

TEST(SceneFiles, SimpleIsPaperFigure12Left) {
  const Scene s = loadScene(kScenesDir / "simple.json");
  EXPECT_EQ(s.name, "simple");
  EXPECT_FALSE(s.description.empty());
  expectFigure12(s, 1.0);
}

TEST(SceneFiles, SimpleDenseIsSimpleWithDensity1000) {
  const Scene s = loadScene(kScenesDir / "simple_dense.json");
  EXPECT_EQ(s.name, "simple_dense");
  expectFigure12(s, 1000.0);
}

// Paper sec. 6: densities 1 and 1000 behave identically; tensions scale.
TEST(SceneFiles, SimpleAndSimpleDenseMoveIdentically) {
  Scene light = loadScene(kScenesDir / "simple.json");
  Scene dense = loadScene(kScenesDir / "simple_dense.json");
  for (int f = 0; f < 60; ++f) {
    light.world->step(1.0 / light.frame_rate_hz);
    dense.world->step(1.0 / dense.frame_rate_hz);
  }
  for (BodyId b = 0; b < light.world->bodyCount(); ++b) {
    expectVec(dense.world->body(b).x, light.world->body(b).x, 1e-9);
    EXPECT_LT(light.world->body(b).x.norm(), 10.0);  // nothing flew away
  }
  EXPECT_GT(light.world->body(bodyNamed(light, "left_bottom")).x.x(), -2.0);  // the push
  for (int j = 0; j < 4; ++j) {
    EXPECT_GT(light.cables->tension(0, j), 0.0) << j;
    EXPECT_NEAR(dense.cables->tension(0, j), 1000.0 * light.cables->tension(0, j),
                1e-6 * dense.cables->tension(0, j))
        << j;
  }
}

TEST(SceneFiles, AtwoodMatchesAnalyticAccelerationAndTensions) {
  Scene s = loadScene(kScenesDir / "atwood.json");
  EXPECT_EQ(s.frameCount(), 84);  // 1.4 s: until the light box nears the wheel
  const World& w = *s.world;
  const BodyId light = bodyNamed(s, "light"), heavy = bodyNamed(s, "heavy");
  EXPECT_DOUBLE_EQ(w.bodyMass(bodyNamed(s, "wheel")), 2.0);
  EXPECT_DOUBLE_EQ(w.bodyMass(light), 1.0);
  EXPECT_DOUBLE_EQ(w.bodyMass(heavy), 2.0);
  ASSERT_EQ(s.cables->cables().size(), 1u);
  EXPECT_EQ(s.cables->cables()[0].links[1].orientation, -1);
  ASSERT_TRUE(s.camera.has_value());

  const double g = 9.81, m1 = 1.0, m2 = 2.0, wheel = 2.0;
  const double a = (m2 - m1) * g / (m1 + m2 + wheel / 2.0);  // I / r^2 = M / 2
  for (int f = 0; f < 30; ++f) s.world->step(1.0 / s.frame_rate_hz);
  const double t = s.world->time();
  EXPECT_NEAR(-w.body(heavy).v.y(), a * t, 0.01 * a * t);
  EXPECT_NEAR(w.body(light).v.y(), a * t, 0.01 * a * t);
  EXPECT_NEAR(s.cables->tension(0, 0), m1 * (g + a), 0.01 * m1 * (g + a));
  EXPECT_NEAR(s.cables->tension(0, 1), m2 * (g - a), 0.01 * m2 * (g - a));
}

TEST(SceneFiles, EverySceneFileLoads) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kScenesDir)) {
    const std::filesystem::path& p = entry.path();
    if (p.extension() != ".json" || p.filename() == "scene.schema.json") continue;
    SCOPED_TRACE(p.string());
    const Scene s = loadScene(p);
    EXPECT_FALSE(s.name.empty());
    EXPECT_GT(s.frameCount(), 0);
    EXPECT_GT(s.world->bodyCount(), 0);
    ++count;
  }
  EXPECT_GE(count, 3);
}

TEST(SceneFiles, DefaultSceneJsonIsSimpleJson) {
  EXPECT_EQ(std::string(defaultSceneJson()), readFile(kScenesDir / "simple.json"));
  const Scene s = parseScene(std::string(defaultSceneJson()), "<default>");
  expectFigure12(s, 1.0);
}

TEST(SceneFiles, SceneSchemaJsonIsTheSchemaFile) {
  EXPECT_EQ(std::string(sceneSchemaJson()), readFile(kScenesDir / "scene.schema.json"));
}

TEST(SceneFiles, SceneStaysUsableAfterAMove) {
  Scene moved = loadScene(kScenesDir / "atwood.json");
  Scene s = std::move(moved);
  const double total = s.cables->totalLength(0);
  for (int f = 0; f < 10; ++f) s.world->step(1.0 / s.frame_rate_hz);
  EXPECT_GT(s.world->time(), 0.0);
  EXPECT_NEAR(s.cables->totalLength(0), total, 1e-9 * total);
}

// Scene::joint_kinds maps each "joints" entry to World's joints of its kind.
TEST(SceneFiles, JointKindsFollowTheJointsArray) {
  const Scene s = loadScene(kScenesDir / "joints.json");
  const nlohmann::json doc = nlohmann::json::parse(readFile(kScenesDir / "joints.json"));
  ASSERT_EQ(s.joint_kinds.size(), doc.at("joints").size());
  int prismatic = 0, spherical = 0, fixed = 0;
  for (std::size_t k = 0; k < s.joint_kinds.size(); ++k) {
    const std::string type = doc["joints"][k].at("type").get<std::string>();
    const JointKind kind = s.joint_kinds[k];
    EXPECT_EQ(kind, type == "prismatic" ? JointKind::Prismatic
                    : type == "spherical" ? JointKind::Spherical
                                          : JointKind::Fixed) << k;
    // The k-th of its kind joins the bodies the entry names.
    const BodyId a = *s.world->findBody(doc["joints"][k].at("body").get<std::string>());
    const BodyId joined = kind == JointKind::Prismatic   ? s.world->prismatic(prismatic++).a
                          : kind == JointKind::Spherical ? s.world->spherical(spherical++).a
                                                         : s.world->fixedJoint(fixed++).a;
    EXPECT_EQ(joined, a) << k;
  }
  EXPECT_EQ(prismatic, static_cast<int>(s.world->prismatics().size()));
  EXPECT_EQ(spherical, static_cast<int>(s.world->sphericals().size()));
  EXPECT_EQ(fixed, static_cast<int>(s.world->fixedJoints().size()));
  EXPECT_TRUE(loadScene(kScenesDir / "atwood.json").joint_kinds.empty());
}

}  // namespace
}  // namespace reeve::test
