// Issue 9, item 2: sheaves and wheels whose axles move (hinged to a moving
// block, to a swinging arm) are as right as wheels on fixed axles: the
// same bounds as test_wheel_mass.cpp.
#include <gtest/gtest.h>

#include "run_machine.h"

namespace reeve::test_moving_axles {
namespace {

using test::Bound;
using test::Worst;

TEST(MovingAxles, BlockAndTackleWithLightSheavesMeetsVirtualWork) {
  // Sheaves of 1e-3 of the 4 kg block on hinges to it; a 1.5 kg
  // counterweight lifts it (4 x 1.5 > 4.008), every strand's tension and
  // the block's acceleration as closed_forms.h derives them.
  for (const Bound& bound : test::kBounds) {
    machines::BlockAndTackleSpec spec;
    spec.counterweight_kg = 1.5;
    spec.budget = bound.budget;
    ASSERT_EQ(spec.sheave_kg, 1e-3 * spec.block_kg);
    machines::BlockAndTackle m = machines::blockAndTackle(spec);
    const auto want = machines::blockAndTackleMotion(spec.block_kg, spec.sheave_kg, spec.counterweight_kg, spec.gravity);
    World& w = *m.scene.world;
    const double cw_y = w.body(m.counterweight).x.y(), block_y = w.body(m.lower_block).x.y();
    const Worst worst = test::runAgainst(
        m.scene, m.cable, {m.lower_axles[0], m.lower_axles[1]}, 60,
        [&] { return w.body(m.lower_block).v.y() / w.time(); }, want.acceleration, want.tensions);
    test::print("block and tackle, sheaves 1e-3", bound.budget, worst);
    EXPECT_LT(worst.acceleration, bound.tolerance);
    EXPECT_LT(worst.tension, bound.tolerance);
    EXPECT_LT(worst.axle, 1e-6);
    EXPECT_LT(worst.stretch, 1e-4);
    // Four strands: the counterweight falls four times as far as the block rises.
    const double rise = w.body(m.lower_block).x.y() - block_y, fall = cw_y - w.body(m.counterweight).x.y();
    EXPECT_NEAR(fall / rise, 4.0, 4.0 * bound.tolerance);
  }
}

TEST(MovingAxles, BlockAndTackleInBalanceStaysPut) {
  // 4 m_c = m_block + 2 m_sheave: nothing moves; every strand carries the
  // counterweight's weight.
  for (const Bound& bound : test::kBounds) {
    machines::BlockAndTackleSpec spec;
    spec.counterweight_kg = (spec.block_kg + 2.0 * spec.sheave_kg) / 4.0;
    spec.budget = bound.budget;
    machines::BlockAndTackle m = machines::blockAndTackle(spec);
    World& w = *m.scene.world;
    const Vec3 start = w.body(m.lower_block).x;
    double drift = 0.0, tension = 0.0;
    for (int f = 0; f < 300; ++f) {  // 5 s
      w.step(1.0 / 60.0);
      drift = std::max(drift, (w.body(m.lower_block).x - start).norm());
      for (int j = 0; j < 5; ++j)
        tension = std::max(tension, std::abs(m.scene.cables->tension(m.cable, j) / (spec.counterweight_kg * spec.gravity) - 1.0));
    }
    std::printf("[ measured ] block and tackle in balance, %d x %d: drift %.2e m, tension %.2e\n", bound.budget.substeps,
                bound.budget.iterations, drift, tension);
    EXPECT_LT(drift, 1e-3);
    EXPECT_LT(tension, bound.tolerance);
  }
}

TEST(MovingAxles, AtwoodOnASwingingArmMeetsItsClosedFormForAnyWheelMass) {
  // The wheel hangs from the lower end of a 1 kg arm hinged above it: both
  // strands pull straight down through the pivot, so the arm hangs still
  // and the machine is Atwood's whatever the wheel weighs.
  for (const Bound& bound : test::kBounds)
    for (const double ratio : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
      machines::AtwoodSpec spec;
      spec.wheel_kg = ratio * spec.light_kg;
      spec.arm_kg = 1.0;
      spec.budget = bound.budget;
      machines::Atwood m = machines::atwood(spec);
      const auto want = machines::atwoodMotion(spec.light_kg, spec.heavy_kg, spec.wheel_kg, spec.gravity);
      World& w = *m.scene.world;
      const Worst worst = test::runAgainst(
          m.scene, m.cable, {m.axle}, 30, [&] { return -w.body(m.heavy).v.y() / w.time(); }, want.acceleration,
          {want.tension_light, want.tension_heavy});
      test::print("Atwood on an arm, wheel " + test::str(ratio) + " x light", bound.budget, worst);
      SCOPED_TRACE("wheel/light " + test::str(ratio));
      EXPECT_LT(worst.acceleration, bound.tolerance);
      EXPECT_LT(worst.tension, bound.tolerance);
      EXPECT_LT(worst.axle, 1e-6);
      EXPECT_LT(worst.stretch, 1e-4);
      EXPECT_LT(std::abs(w.hingeAngle(0)), 1e-6);  // the arm
    }
}

}  // namespace
}  // namespace reeve::test_moving_axles
