// Convex cross-sections (paper sec. 3.2, Fig. 5-6): the cable wraps the
// hull and surface distances are measured along it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "reeve/cable/cable.h"
#include "scene_fixture.h"

namespace reeve::test_square_wheel {
namespace {

TEST(SquareWheel, OneFullTurnPaysOutExactlyThePerimeter) {
  // Turn the scene's square spool by hand in small exact steps; it starts
  // turned by 0.3 rad, so no edge lies along the cable at either end.
  Scene s = test::scene("square_wheel");
  const BodyId square = test::body(s, "square");
  const double before = s.cables->restLength(0, 0);
  const double stored = s.cables->cables()[0].links[0].stored;
  const int steps = 720;
  for (int i = 0; i < steps; ++i) {
    // cw, the paying-out sense of this cw-wound spool
    rotateExactly(s.world->body(square).q, Vec3(0, 0, -2.0 * std::numbers::pi / steps));
    s.cables->update();
  }
  EXPECT_NEAR(s.cables->restLength(0, 0) - before, 2.0, 1e-9);
  EXPECT_NEAR(stored - s.cables->cables()[0].links[0].stored, 2.0, 1e-9);
  // And back: the other sense winds it up again.
  for (int i = 0; i < steps / 4; ++i) {
    rotateExactly(s.world->body(square).q, Vec3(0, 0, 2.0 * std::numbers::pi / steps));
    s.cables->update();
  }
  EXPECT_NEAR(s.cables->restLength(0, 0) - before, 1.5, 1e-9);
}

TEST(SquareWheel, ASpoolTurningTwiceInOneSubstepPaysOutTwoPerimeters) {
  // 2.04 turns within one substep of h: the whole turns come from the
  // spool's own rotation, h omega, the rest from the geometry.
  Scene s = test::scene("square_wheel");
  const BodyId square = test::body(s, "square");
  const double before = s.cables->restLength(0, 0);
  const double perimeter = s.cables->cables()[0].links[0].section.perimeter();
  const double h = 1e-3, turns = 2.04;
  BodyState& spool = s.world->body(square);
  spool.omega = Vec3(0.0, 0.0, -turns * 2.0 * std::numbers::pi / h);  // cw: paying out
  rotateExactly(spool.q, h * spool.omega);
  // The spool starts turned 0.3 rad: the same corner touches the vertical
  // cable until it has turned cw by 0.3 rad (an edge then hangs plumb), so
  // after 0.04 turn (0.25 rad) the tangent vertex is the one it was, and
  // the cable paid out is exactly the two perimeters.
  s.cables->update(0.0, h);
  EXPECT_NEAR(s.cables->restLength(0, 0) - before, 2.0 * perimeter, 1e-9);
}

TEST(SquareWheel, TheWeightUnwindsTheSquareAndTheCableStaysTautAndWhole) {
  Scene s = test::scene("square_wheel");
  const BodyId weight = test::body(s, "weight"), square = test::body(s, "square");
  const double total = s.cables->totalLength(0);
  const double y0 = s.world->body(weight).x.y();
  const double rest0 = s.cables->restLength(0, 0);
  double turned = 0.0;
  for (int f = 0; f < s.frameCount(); ++f) {
    test::frame(s);
    turned += s.world->body(square).omega.z() / s.frame_rate_hz;
    ASSERT_NEAR(s.cables->totalLength(0), total, 1e-9 * total);
  }
  // The cable pays out one side (0.5 m) each time the next corner takes
  // over, a quarter turn apart; the weight hangs the rest length below the
  // tangent corner, which moves by at most the half diagonal.
  const double paid = s.cables->restLength(0, 0) - rest0;
  EXPECT_GT(-turned, 2.0 * std::numbers::pi);  // more than one turn
  EXPECT_NEAR(paid, -turned / (2.0 * std::numbers::pi) * 2.0, 0.5);
  EXPECT_NEAR(y0 - s.world->body(weight).x.y(), paid, 0.25 * std::sqrt(2.0) + 1e-3);
}

}  // namespace
}  // namespace reeve::test_square_wheel
