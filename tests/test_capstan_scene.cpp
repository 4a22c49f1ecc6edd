// scenes/capstan.json does what its description says: the bollard and the
// friction pinhole hold, the frictionless drum is an ideal pulley, the
// slipping rope keeps the capstan ratio (closed forms from the masses).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene_fixture.h"

namespace reeve::test_capstan_scene {
namespace {

TEST(CapstanScene, HoldsSlidesAndRunsFreeAsItsDescriptionSays) {
  Scene s = test::scene("capstan");
  constexpr double g = 9.81, pi = std::numbers::pi;
  const int hole = test::cable(s, "hole_rope");
  const double hole_rest = s.cables->restLength(hole, 1);
  const double totals[4] = {s.cables->totalLength(0), s.cables->totalLength(1), s.cables->totalLength(2),
                            s.cables->totalLength(3)};
  for (int f = 0; f < 30; ++f) test::frame(s);  // the slides' first substep sticks
  const BodyState& ideal = s.world->body(test::body(s, "ideal_heavy"));
  const BodyState& slipping = s.world->body(test::body(s, "slipping_heavy"));
  const double v_ideal = ideal.v.y(), v_slipping = slipping.v.y(), t0 = s.world->time();
  for (int f = 30; f < s.frameCount(); ++f) test::frame(s);
  const double t = s.world->time() - t0;

  // The bollard: 1 kg holds 15 kg through 3 pi at mu 0.3 (bound 16.9).
  const int bollard = test::cable(s, "bollard_rope");
  EXPECT_LT(s.world->body(test::body(s, "bollard_load")).v.norm(), 1e-6);
  EXPECT_NEAR(s.cables->tension(bollard, 0), 1.0 * g, 1e-3 * g);
  EXPECT_NEAR(s.cables->tension(bollard, 1), 15.0 * g, 1e-3 * 15.0 * g);
  EXPECT_EQ(s.cables->slipSpeed(bollard, 1), 0.0);

  // The ideal pulley: massless Atwood, equal tensions.
  const int ideal_rope = test::cable(s, "ideal_rope");
  const double a = g * 0.2 / 2.2, T = 2.0 * 1.0 * 1.2 * g / 2.2;
  EXPECT_NEAR((ideal.v.y() - v_ideal) / t, -a, 1e-3 * a);
  EXPECT_NEAR(s.cables->tension(ideal_rope, 0), T, 1e-3 * T);
  EXPECT_NEAR(s.cables->tension(ideal_rope, 1), T, 1e-3 * T);
  // The cable slides over the drum at the boxes' speed.
  EXPECT_NEAR(s.cables->slipSpeed(ideal_rope, 1), -ideal.v.y(), 1e-3 * std::abs(ideal.v.y()));

  // Slipping over half a turn at mu 0.3: the capstan acceleration and ratio.
  const int slipping_rope = test::cable(s, "slipping_rope");
  const double k = std::exp(0.3 * pi), a_slip = g * (3.0 / k - 1.0) / (3.0 / k + 1.0);
  EXPECT_NEAR((slipping.v.y() - v_slipping) / t, -a_slip, 1e-2 * a_slip);
  EXPECT_NEAR(s.cables->tension(slipping_rope, 1) / s.cables->tension(slipping_rope, 0), k, 1e-2 * k);

  // The friction pinhole holds 1.5 kg against 1 kg: the boxes swing on
  // their own spans, and no cable passes the hole.
  EXPECT_EQ(s.cables->restLength(hole, 1), hole_rest);
  EXPECT_EQ(s.cables->slipSpeed(hole, 1), 0.0);

  for (int c = 0; c < 4; ++c) EXPECT_NEAR(s.cables->totalLength(c), totals[c], 1e-9 * totals[c]);
  EXPECT_FALSE(s.cables->firstBreach().has_value());
}

}  // namespace
}  // namespace reeve::test_capstan_scene
