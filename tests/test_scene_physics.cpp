// Physics of the shipped scenes: the paper's mass-scaling experiment
// (Fig. 12, density 1 vs 1000), the Simple scene's equilibrium tensions,
// the Atwood scene against its closed form, and the springs scene's
// statics.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "reeve/scene/scene.h"

namespace reeve::test_scene_physics {
namespace {

const std::string kScenes = REEVE_SCENES_DIR;

TEST(MassScaling, DensityOneAndThousandGiveTheSameTrajectoriesAndScaledTensions) {
  // XPBD corrections depend on mass ratios only, so scaling every mass by k
  // leaves positions unchanged and scales every lambda, hence tension, by k.
  Scene light = loadScene(kScenes + "/simple.json");
  Scene dense = loadScene(kScenes + "/simple_dense.json");
  ASSERT_EQ(light.world->bodyCount(), dense.world->bodyCount());
  const double dt = 1.0 / light.frame_rate_hz;
  double max_tension = 0.0;
  for (int f = 0; f < light.frameCount(); ++f) {
    light.world->step(dt);
    dense.world->step(dt);
    for (BodyId b = 0; b < light.world->bodyCount(); ++b) {
      const Vec3& x1 = light.world->body(b).x;
      const Vec3& x2 = dense.world->body(b).x;
      ASSERT_LE((x1 - x2).norm(), 1e-9 * std::max(1.0, x1.norm())) << "frame " << f << " body " << b;
    }
    for (int j = 0; j < 4; ++j) {
      const double t1 = light.cables->tension(0, j), t2 = dense.cables->tension(0, j);
      ASSERT_NEAR(t2, 1000.0 * t1, 1e-9 * std::abs(t2) + 1e-9) << "frame " << f << " joint " << j;
      max_tension = std::max(max_tension, t1);
    }
  }
  EXPECT_GT(max_tension, 5.0);  // the cable carried load throughout
}

TEST(SimpleScene, AtRestTheCableCarriesTheWeightsBelowEachJoint) {
  // Without the initial push the paper's set-up is in equilibrium: the
  // bottom-left span holds 1 kg, the rest of the cable 2 kg (g = 10).
  Scene s = loadScene(kScenes + "/simple.json");
  const BodyId pushed = *s.world->findBody("left_bottom");
  s.world->body(pushed).v.setZero();
  for (int f = 0; f < 120; ++f) s.world->step(1.0 / s.frame_rate_hz);
  const double expected[] = {10.0, 20.0, 20.0, 20.0};
  for (int j = 0; j < 4; ++j) EXPECT_NEAR(s.cables->tension(0, j), expected[j], 0.01 * expected[j]) << j;
  EXPECT_LT(s.world->body(pushed).v.norm(), 1e-6);
}

TEST(AtwoodScene, FallsWithTheAnalyticAcceleration) {
  // m1 = 1, m2 = 2, wheel M = 2 kg solid: a = (m2 - m1) g / (m1 + m2 + M/2).
  Scene s = loadScene(kScenes + "/atwood.json");
  const BodyId heavy = *s.world->findBody("heavy");
  const double g = 9.81, a = g / 4.0;
  for (int f = 0; f < 30; ++f) s.world->step(1.0 / s.frame_rate_hz);
  EXPECT_NEAR(-s.world->body(heavy).v.y() / s.world->time(), a, 0.01 * a);
  EXPECT_NEAR(s.cables->tension(0, 0), 1.0 * (g + a), 0.01 * 1.0 * (g + a));
  EXPECT_NEAR(s.cables->tension(0, 1), 2.0 * (g - a), 0.01 * 2.0 * (g - a));
}

}  // namespace
}  // namespace reeve::test_scene_physics

namespace reeve::test_scene_physics {
namespace {

// The two knobs (DESIGN.md): one step with many iterations (the paper),
// many substeps with one iteration (SCA 2020), and a mix, must each meet
// what the tests expect of a scene, and so agree with each other.
TEST(SubstepsAndIterations, EverySplitOfTheBudgetMeetsTheAnalyticValues) {
  const int splits[][2] = {{1, 20}, {20, 1}, {5, 4}};
  for (const auto& split : splits) {
    const std::string at = std::to_string(split[0]) + " x " + std::to_string(split[1]);
    {  // Atwood: a = g / 4, T1 = m1 (g + a), T2 = m2 (g - a)
      Scene s = loadScene(kScenes + "/atwood.json");
      s.world->settings().substeps = split[0];
      s.world->settings().iterations = split[1];
      for (int f = 0; f < 30; ++f) s.world->step(1.0 / s.frame_rate_hz);
      const double g = 9.81, a = g / 4.0;
      EXPECT_NEAR(-s.world->body(*s.world->findBody("heavy")).v.y() / s.world->time(), a, 0.01 * a) << at;
      EXPECT_NEAR(s.cables->tension(0, 0), g + a, 0.01 * (g + a)) << at;
      EXPECT_NEAR(s.cables->tension(0, 1), 2.0 * (g - a), 0.01 * 2.0 * (g - a)) << at;
    }
    {  // Simple scene at rest: 10 N below the middle box, 20 N above it
      Scene s = loadScene(kScenes + "/simple.json");
      s.world->settings().substeps = split[0];
      s.world->settings().iterations = split[1];
      s.world->body(*s.world->findBody("left_bottom")).v.setZero();
      for (int f = 0; f < 60; ++f) s.world->step(1.0 / s.frame_rate_hz);
      const double expected[] = {10.0, 20.0, 20.0, 20.0};
      for (int j = 0; j < 4; ++j) EXPECT_NEAR(s.cables->tension(0, j), expected[j], 0.01 * expected[j]) << at;
    }
    {  // The 1:4 gear stays balanced
      Scene s = loadScene(kScenes + "/gear_1_to_4.json");
      s.world->settings().substeps = split[0];
      s.world->settings().iterations = split[1];
      const BodyId w = *s.world->findBody("weight_small");
      const Vec3 x0 = s.world->body(w).x;
      for (int f = 0; f < 120; ++f) s.world->step(1.0 / s.frame_rate_hz);
      EXPECT_LT((s.world->body(w).x - x0).norm(), 1e-3) << at;
    }
  }
}

// springs.json at rest: each spring hinge of the limb holds the moment of
// the weights beyond it about its axle (exactly, at the bent geometry):
// the drive's torque on the outer segment is -stiffness x angle = -M, and
// the block rests m g / k below its spring's target.
TEST(SpringsScene, EachSpringHoldsTheMomentBeyondItAndTheBlockRestsAtWeightOverStiffness) {
  Scene s = loadScene(kScenes + "/springs.json");
  World& w = *s.world;
  for (int f = 0; f < 600; ++f) w.step(1.0 / s.frame_rate_hz);  // 10 s: at rest
  const double g = -w.settings().gravity.y();
  ASSERT_EQ(w.hinges().size(), 5u);
  for (HingeId i = 0; i < 5; ++i) {
    const HingeJoint& hinge = w.hinge(i);
    const Vec3 axle = w.worldPoint(hinge.a, hinge.frame.anchor_a);
    double moment = 0.0;  // of the weights beyond it (listed after it, but the block), about +z
    for (BodyId b = hinge.a; b < w.bodyCount(); ++b)
      if (w.bodyDef(b).name != "block") moment -= w.bodyMass(b) * g * (w.body(b).x.x() - axle.x());
    const double k = hinge.drive.stiffness, angle = w.hingeAngle(i);
    std::printf("[ measured ] springs.json hinge %d: angle %.9f vs moment / k %.9f rad, drive torque %.9f "
                "vs -moment %.9f N m\n",
                i, angle, moment / k, w.hingeDriveTorque(i), -moment);
    EXPECT_NEAR(angle, moment / k, 1e-6 * std::abs(moment / k)) << "hinge " << i;
    EXPECT_NEAR(w.hingeDriveTorque(i), -moment, 1e-6 * std::abs(moment)) << "hinge " << i;
  }
  const PrismaticJoint& rail = w.prismatic(0);
  const double m = w.bodyMass(rail.a), k = rail.drive.stiffness;
  EXPECT_NEAR(w.prismaticSlide(0), -m * g / k, 1e-6);
  EXPECT_NEAR(w.prismaticDriveForce(0), m * g, 1e-6 * m * g);
}

}  // namespace
}  // namespace reeve::test_scene_physics
