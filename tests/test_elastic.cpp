// Elastic cables (paper Fig. 15): compliance in the XPBD sense gives
// Hooke's law; zero compliance is inextensible.
#include <gtest/gtest.h>

#include <algorithm>

#include "reeve/cable/cable.h"
#include "scene_fixture.h"

namespace reeve {
namespace {

TEST(Elastic, HangingWeightsStretchTheirCablesByComplianceTimesTension) {
  Scene s = test::scene("elastic");
  const double g = 9.81, compliance = 0.01;
  // Cable 0 is one span; cable 1 runs over a wheel, and its compliance is
  // shared by length, so its free spans stretch by their share of it.
  const double total_right = s.cables->totalLength(1);
  for (int f = 0; f < s.frameCount(); ++f) test::frame(s);
  EXPECT_LT(s.world->body(test::body(s, "light")).v.norm(), 1e-3);  // at rest
  EXPECT_LT(s.world->body(test::body(s, "heavy")).v.norm(), 1e-3);
  const double T_light = 1.0 * g, T_heavy = 2.0 * g;
  EXPECT_NEAR(s.cables->tension(0, 0), T_light, 0.01 * T_light);
  EXPECT_NEAR(s.cables->length(0, 0) - s.cables->restLength(0, 0), compliance * T_light, 0.01 * compliance * T_light);
  double spans = 0.0, stretch = 0.0;
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(s.cables->tension(1, j), T_heavy, 0.01 * T_heavy) << j;
    spans += s.cables->restLength(1, j);
    stretch += s.cables->length(1, j) - s.cables->restLength(1, j);
  }
  const double expected = compliance * T_heavy * spans / total_right;
  EXPECT_NEAR(stretch, expected, 0.01 * expected);
}

TEST(Elastic, ZeroComplianceIsInextensibleAtTwentyIterations) {
  Scene s = test::scene("atwood");
  s.world->settings().iterations = 20;
  double worst = 0.0;
  for (int f = 0; f < s.frameCount(); ++f) {
    test::frame(s);
    for (int j = 0; j < 2; ++j)
      worst = std::max(worst, (s.cables->length(0, j) - s.cables->restLength(0, j)) / s.cables->restLength(0, j));
  }
  EXPECT_LT(worst, 1e-4);
}

}  // namespace
}  // namespace reeve

namespace reeve {
namespace {

TEST(Elastic, ASoftCableLetsItsWeightRestOnTheGround) {
  // Fig. 15 right. Beam underside at 2.0 m, rest length 1.5 m, 1 kg boxes
  // 0.2 m tall. Stiff (0.01 m/N): hangs with stretch 0.0981 m, bottom at
  // 2.0 - 1.5 - 0.0981 - 0.2 = 0.2019 m. Soft (0.1 m/N): would stretch
  // 0.981 m, so it rests on the ground; its cable spans 2.0 - 0.2 = 1.8 m,
  // tension (1.8 - 1.5) / 0.1 = 3 N, the ground carries 9.81 - 3 N.
  Scene s = test::scene("elastic_ground");
  for (int f = 0; f < s.frameCount(); ++f) test::frame(s);
  const BodyState& stiff = s.world->body(test::body(s, "stiff"));
  const BodyState& soft = s.world->body(test::body(s, "soft"));
  EXPECT_LT(stiff.v.norm() + soft.v.norm(), 1e-3);  // at rest
  EXPECT_NEAR(stiff.x.y() - 0.1, 0.2019, 1e-3);
  EXPECT_NEAR(s.cables->tension(0, 0), 9.81, 0.01 * 9.81);
  EXPECT_NEAR(soft.x.y(), 0.1, 1e-3);  // on the ground
  EXPECT_NEAR(s.cables->tension(1, 0), 3.0, 0.03);
}

}  // namespace
}  // namespace reeve
