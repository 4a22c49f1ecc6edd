// scenes/crane.json does what its description says: the hoist winch lifts
// the load 2 m at its speed with the pull of its weight, the luffing winch
// holds the boom with the moment the weights need, the turntable slews to
// its stop and the load is set down again; the cables' bookkeeping holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "reeve/scene/energy.h"
#include "scene_fixture.h"

namespace reeve::test_crane_scene {
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

TEST(CraneScene, ATorqueLimitedAngleDriveSlewsToItsTargetWithoutRopeChatter) {
  // Issue 14's open problem: slewed by a torque-limited angle drive, the
  // crane's hoist and luffing ropes went slack and taut from substep to
  // substep (0, then the 30 kN stall) and the turntable overshot to
  // 2.2 rad, so crane.json slews by a velocity drive. Here its drive is an
  // angle drive to 1.2 rad (no end stop) at 600, 2500 and 25000 N m. It
  // brakes in time for the turntable, mast and boom and the load hung from
  // the boom tip (World::brakingInverseInertia); the load's swing still
  // carries a weak drive on (0.01 rad at 600 N m, 0.22 rad at 2500: the
  // swing's pull, about m g theta R, is 1.7 kN m at 0.1 rad), a strong one
  // not. While it slews and after (to the hoist's stop at 3.3 s, and from
  // there to the pay-out at 9 s) the hoist rope holds the load, never
  // slack; the drive ends on its target; and no energy is made (the load
  // swings out of the tip sheave's plane while it is hoisted: the 25 kN m
  // slew made about 1 kJ before a rolling end paid out r a radian out of
  // plane).
  constexpr double m = 500.0, g = 9.81, target = 1.2;
  for (const double torque : {600.0, 2500.0, 25000.0}) {
    SCOPED_TRACE(std::to_string(torque) + " N m");
    Scene s = test::scene("crane");
    HingeJoint& slew = s.world->hinge(0);
    ASSERT_EQ(slew.a, test::body(s, "turntable"));
    slew.drive.mode = HingeDrive::Mode::Angle;
    slew.drive.target = target;
    slew.drive.max_torque = torque;
    slew.limit.enabled = false;
    const int hoist = test::cable(s, "hoist");
    EnergyWatch watch(s);
    double least = INFINITY, highest = 0.0;
    for (int f = 0; f < s.frameCount(); ++f) {
      test::frame(s);
      ASSERT_FALSE(s.world->firstNonFinite()) << "t = " << s.world->time();
      const auto created = watch.check(s);
      ASSERT_FALSE(created) << created->created_J << " J at t = " << created->time_s;
      highest = std::max(highest, s.world->hingeAngle(0));
      const double t = s.world->time();
      if ((t > 0.2 && t < 3.3) || (t > 3.6 && t < 9.0))
        for (int j = 0; j < static_cast<int>(s.cables->cables()[hoist].joints.size()); ++j)
          least = std::min(least, s.cables->tension(hoist, j));
    }
    std::printf("[ measured ] crane slewed by a %g N m angle drive: to %.4f rad, at %.6f at the end; hoist at least %.0f N\n",
                torque, highest, s.world->hingeAngle(0), least);
    EXPECT_NEAR(s.world->hingeAngle(0), target, 1e-4);
    EXPECT_GT(least, 0.05 * m * g);
    if (torque > 10000.0) {
      EXPECT_LT(highest, target + 0.01);
    }
  }
}

TEST(CraneScene, PayingOutAtOneIterationASubstepTheRopesHoldTheLoadSteadily) {
  // At 100 x 1, from 9 s, both winches pay out. After integration one
  // hoist span either side of the tip sheave was stretched and the other
  // slack, both having pulled; the first pass solved both (and the luffing
  // rope) to C = 0, all three came out pushing and were held at zero
  // together, and nothing freed the stretched one again: it stayed unmet,
  // the next substep caught it at twice the pull, and up to 50 J a frame
  // (500 J in one event) was made while the ropes went slack and taut on
  // alternate substeps. Freed again, nothing was made, but a catch held at
  // the winches' 30 kN left the load slack for the next three to six
  // substeps (0 and 30 kN by turns, the mean right). With every row held
  // at a bound that the motion leaves wanting to come off it solved again
  // (DirectSolver::solveActiveSet), the hoist holds the load at every
  // substep at its weight less the swing's share (4.75 to 4.86 kN) as it
  // descends at the winch's speed, at one iteration and any substeps.
  constexpr double m = 500.0, g = 9.81;
  for (const int substeps : {100, 20, 1}) {
    SCOPED_TRACE(std::to_string(substeps) + " x 1");
    Scene s = test::scene("crane", substeps, 1);
    const int hoist = test::cable(s, "hoist");
    double least = INFINITY, most = 0.0;
    s.world->addSubstepHook([&](World& w, double) {  // before each solve: the last one's tension
      if (w.time() < 9.5 || w.time() > 11.5) return;
      least = std::min(least, s.cables->tension(hoist, 1));
      most = std::max(most, s.cables->tension(hoist, 1));
    });
    EnergyWatch watch(s);
    for (int f = 0; f < s.frameCount(); ++f) {
      test::frame(s);
      ASSERT_FALSE(s.world->firstNonFinite()) << "t = " << s.world->time();
      const auto created = watch.check(s);
      ASSERT_FALSE(created) << created->created_J << " J at t = " << created->time_s;
    }
    std::printf("[ measured ] crane at %d x 1, paying out (9.5 to 11.5 s): hoist tension %.0f to %.0f N (m g %.0f N)\n",
                substeps, least, most, m * g);
    EXPECT_GT(least, 0.95 * m * g);
    EXPECT_LT(most, 1.05 * m * g);
    EXPECT_FALSE(s.cables->firstBreach().has_value());
  }
}

}  // namespace
}  // namespace reeve::test_crane_scene
