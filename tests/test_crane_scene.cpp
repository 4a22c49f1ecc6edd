// scenes/crane.json does what its description says: the hoist winch lifts
// the load 2 m at its speed with the pull of its weight, the luffing winch
// holds the boom with the moment the weights need, the turntable slews to
// its stop and the load is set down again; the cables' bookkeeping holds.
#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixture.h"

namespace reeve {
namespace {

TEST(CraneScene, LiftsSlewsAndSetsTheLoadDown) {
  Scene s = test::scene("crane");
  constexpr double g = 9.81, m = 500.0;
  const int hoist = test::cable(s, "hoist"), luff = test::cable(s, "luff");
  const BodyId load = test::body(s, "load"), turntable = test::body(s, "turntable");
  const double y0 = s.world->body(load).x.y();
  const double totals[2] = {s.cables->totalLength(hoist), s.cables->totalLength(luff)};
  const int drum = static_cast<int>(s.cables->cables()[hoist].links.size()) - 1;

  // Hauling at 0.6 m/s: the load rises at that speed (it hangs below the
  // tip sheave, slewing only swings it sideways) with the pull of its
  // weight, which the boom takes through the luffing rope: moment balance
  // about the boom's foot, rope 2.49 m from it, load 3.41 m out, boom
  // weight 1.61 m out, gives 8.1 kN.
  while (s.world->time() < 1.0 - 1e-9) test::frame(s);
  const double y1 = s.world->body(load).x.y();
  while (s.world->time() < 2.0 - 1e-9) test::frame(s);
  EXPECT_NEAR(s.world->body(load).x.y() - y1, 0.6, 0.02);
  // Reeled: 0.6 m/s for 2 s, less what the start's jerk (0 to 0.6 m/s in
  // a substep, on an inextensible rope) paid out at the 30 kN stall.
  EXPECT_NEAR(s.cables->cables()[hoist].links[drum].stored, 0.6 * 2.0, 0.01);
  EXPECT_NEAR(s.cables->winchPull(hoist), m * g, 0.05 * m * g);  // the swing's share
  EXPECT_NEAR(s.cables->winchPull(luff), 8.1e3, 0.1 * 8.1e3);

  // Length mode stops at 2 m on the drum (less what the jerk of the
  // sudden stop paid out); the load is 2 m up, and the boom's luff lifts
  // it 0.2 m more.
  while (s.world->time() < 7.0 - 1e-9) test::frame(s);
  EXPECT_NEAR(s.cables->cables()[hoist].links[drum].stored, 2.0, 0.02);
  EXPECT_NEAR(s.cables->cables()[luff].links[1].stored, 0.3, 0.02);
  EXPECT_GT(s.world->body(load).x.y(), y0 + 2.0);

  // Slewed to the stop, and set down: the load is back on the ground.
  for (int f = static_cast<int>(std::lround(s.world->time() * s.frame_rate_hz)); f < s.frameCount(); ++f)
    test::frame(s);
  const Vec3 heading = s.world->body(turntable).q * Vec3::UnitX();
  EXPECT_NEAR(std::atan2(-heading.z(), heading.x()), 1.2, 2e-3);
  EXPECT_NEAR(s.cables->cables()[hoist].links[drum].stored, 0.0, 1e-9);
  EXPECT_NEAR(s.world->body(load).x.y(), y0, 0.02);
  EXPECT_NEAR(s.cables->cables()[luff].links[1].stored, 0.0, 0.02);
  for (const int c : {hoist, luff}) EXPECT_NEAR(s.cables->totalLength(c), totals[c == hoist ? 0 : 1], 1e-9 * totals[c == hoist ? 0 : 1]);
  EXPECT_FALSE(s.cables->firstBreach().has_value());
  EXPECT_FALSE(s.world->firstNonFinite().has_value());
}

}  // namespace
}  // namespace reeve
