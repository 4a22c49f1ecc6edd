#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "atwood_rig.h"

namespace reeve::test_camera {
namespace {

using test::AtwoodRig;
using test::projectToPixel;

// Every body centre and cable tangent point of the rig, in world space.
std::vector<Vec3> keyPoints(const AtwoodRig& rig) {
  std::vector<Vec3> points;
  for (BodyId id = 0; id < rig.world.bodyCount(); ++id) points.push_back(rig.world.body(id).x);
  for (int j = 0; j < 2; ++j) {
    points.push_back(rig.cables.startPoint(rig.cable, j));
    points.push_back(rig.cables.endPoint(rig.cable, j));
  }
  return points;
}

class FrameScene : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(FrameScene, PutsEveryBodyCentreAndCablePointInsideTheImage) {
  const auto [width, height] = GetParam();
  AtwoodRig rig;
  rig.run(20);
  const Camera camera = frameScene(rig.world, rig.cables, double(width) / height);
  double top = height, bottom = 0.0;
  for (const Vec3& p : keyPoints(rig)) {
    const Eigen::Vector2d px = projectToPixel(camera, p, width, height);
    EXPECT_GT(px.x(), 0.02 * width) << p.transpose();
    EXPECT_LT(px.x(), 0.98 * width) << p.transpose();
    EXPECT_GT(px.y(), 0.02 * height) << p.transpose();
    EXPECT_LT(px.y(), 0.98 * height) << p.transpose();
    top = std::min(top, px.y());
    bottom = std::max(bottom, px.y());
  }
  // It frames the scene, not just contains it: the rig is tall, so its
  // points span most of the image height.
  EXPECT_GT(bottom - top, 0.5 * height);
}

INSTANTIATE_TEST_SUITE_P(Aspects, FrameScene,
                         ::testing::Values(std::pair{1280, 720}, std::pair{600, 600},
                                           std::pair{720, 1280}));

TEST(FrameSceneView, LooksAlongMinusZFromSlightlyAbove) {
  AtwoodRig rig;
  const Camera camera = frameScene(rig.world, rig.cables, 16.0 / 9.0);
  const Vec3 forward = (camera.target - camera.eye).normalized();
  EXPECT_LT(forward.z(), -0.9);
  EXPECT_LT(forward.y(), -0.05);
  EXPECT_GT(forward.y(), -0.5);
  EXPECT_NEAR(forward.x(), 0.0, 1e-12);
  EXPECT_EQ(camera.up, Vec3::UnitY());
}

TEST(FrameSceneView, RejectsANonPositiveAspect) {
  AtwoodRig rig;
  for (double aspect : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(frameScene(rig.world, rig.cables, aspect), std::invalid_argument);
}

TEST(FrameSceneView, EmptySceneGivesTheDefaultCamera) {
  World world;
  CableSystem cables(world);
  const Camera camera = frameScene(world, cables, 1.5);
  EXPECT_EQ(camera.eye, Camera().eye);
  EXPECT_EQ(camera.target, Camera().target);
}

}  // namespace
}  // namespace reeve::test_camera
