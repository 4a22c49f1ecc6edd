#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "atwood_rig.h"
#include "reeve/render/cable_path.h"

namespace reeve {
namespace {

using test::AtwoodRig;

constexpr double kStep = 2.0 * std::numbers::pi / 96.0;

double maxY(const std::vector<Vec3>& path) {
  double y = -INFINITY;
  for (const Vec3& p : path) y = std::max(y, p.y());
  return y;
}

// The Atwood cable runs from the light box up its span, clockwise over the
// top of the wheel (orientation -1) and down to the heavy box.
void expectOverTheTop(const AtwoodRig& rig) {
  const auto path = cablePath(rig.cables, rig.cable, kStep);
  const World& w = rig.world;
  EXPECT_TRUE(path.front().isApprox(w.body(rig.light_box).toWorld(Vec3(0, 0.12, 0)), 1e-12));
  EXPECT_TRUE(path.back().isApprox(w.body(rig.heavy_box).toWorld(Vec3(0, 0.15, 0)), 1e-12));
  // path: span 0 start, span 0 end (arrival), arc..., span 1 start (departure), span 1 end.
  ASSERT_GT(path.size(), 4u);
  const double r = AtwoodRig::kRadius;
  const Vec3 centre = w.body(rig.wheel).x;
  double arc_length = 0.0;
  for (std::size_t i = 1; i + 2 < path.size(); ++i) {
    const Vec3 a = path[i] - centre, b = path[i + 1] - centre;
    EXPECT_NEAR(b.norm(), r, 1e-9) << "arc point " << i + 1;
    EXPECT_NEAR(b.z(), 0.0, 1e-9);
    const double turn = std::atan2(a.cross(b).z(), a.dot(b));
    EXPECT_LT(turn, 0.0) << "clockwise, point " << i;
    EXPECT_GE(turn, -kStep - 1e-9);
    arc_length += (b - a).norm();
  }
  EXPECT_GT(maxY(path), r * std::cos(kStep));
  EXPECT_LT(maxY(path), r + 1e-9);
  EXPECT_NEAR(arc_length, rig.cables.cables()[rig.cable].links[1].stored, 1e-3 * r);
}

TEST(CablePath, AtwoodCableWrapsClockwiseOverTheTopOfTheWheel) {
  AtwoodRig rig;
  expectOverTheTop(rig);
}

TEST(CablePath, ArcFollowsTheTangentPointsAfterTheWheelTurned) {
  AtwoodRig rig;
  rig.run(30);
  ASSERT_GT(std::abs(rig.world.body(rig.wheel).omega.z()), 0.5);  // it did turn
  expectOverTheTop(rig);
}

TEST(CablePath, CounterClockwiseLinkWrapsUnderTheWheel) {
  // A sling: from an anchor up-left, counter-clockwise under the wheel, to
  // an anchor up-right.
  World world;
  CableSystem cables(world);
  BodyDef anchor;
  anchor.shape = Shape::box(Vec3(1.2, 0.05, 0.05));
  anchor.is_static = true;
  anchor.position = Vec3(0.0, 1.0, 0.0);
  const BodyId top = world.addBody(anchor);
  BodyDef wheel_def;
  wheel_def.shape = Shape::cylinder(0.3, 0.05);
  wheel_def.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3::UnitZ()));  // local != world
  const BodyId wheel = world.addBody(wheel_def);
  CableDef def;
  def.links = {{top, LinkType::Attachment, 1, Vec3(-1.0, 0.0, 0.0)},
               {wheel, LinkType::Rolling, 1, Vec3::Zero()},
               {top, LinkType::Attachment, 1, Vec3(1.0, 0.0, 0.0)}};
  const int c = cables.addCable(def);
  const auto path = cablePath(cables, c, kStep);
  double min_y = INFINITY;
  for (const Vec3& p : path) min_y = std::min(min_y, p.y());
  EXPECT_LT(min_y, -0.3 * std::cos(kStep));
  EXPECT_GT(min_y, -0.3 - 1e-9);
  // Counter-clockwise: each arc point is ahead of the last by a positive angle.
  for (std::size_t i = 1; i + 2 < path.size(); ++i) {
    const double turn = std::atan2(path[i].cross(path[i + 1]).z(), path[i].dot(path[i + 1]));
    EXPECT_GT(turn, 0.0);
    EXPECT_LE(turn, kStep + 1e-9);
  }
}

}  // namespace
}  // namespace reeve
