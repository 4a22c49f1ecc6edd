// Issue 9, item 5: a wheel that turns many times in one substep moves
// exactly as much cable as it turns (the whole turns count), so a 1 mm
// wheel on a 1:100 Atwood machine at one substep of one iteration per
// frame meets the closed form within 1 %.
#include <gtest/gtest.h>

#include <numbers>
#include <utility>

#include "run_machine.h"

namespace reeve::test_fast_wheel {
namespace {

TEST(FastWheel, OneMillimetreWheelOnA1To100AtwoodAtOneStepOfOneIteration) {
  // Also 0.2 mm: there the solve alone turns the wheel a h^2 / r = 13.6 rad
  // per substep, over two turns, besides the integration's h omega.
  for (const auto& [radius, wheel_kg] : {std::pair{1e-3, 1e-3}, std::pair{1e-3, 1.0}, std::pair{2e-4, 1e-3}}) {
    machines::AtwoodSpec spec;
    spec.radius_m = radius;
    spec.heavy_kg = 100.0 * spec.light_kg;
    spec.wheel_kg = wheel_kg;
    spec.budget = {1, 1};
    machines::Atwood m = machines::atwood(spec);
    const auto want = machines::atwoodMotion(spec.light_kg, spec.heavy_kg, wheel_kg, spec.gravity);
    World& w = *m.scene.world;
    const double y0 = w.body(m.heavy).x.y(), rest0 = m.scene.cables->restLength(m.cable, 1);
    const double total = m.scene.cables->totalLength(m.cable);
    // 0.7 s: the light box rises 2.4 m of the 2.9 m below the wheel; the
    // wheel ends at v / (r h) = 18 turns per substep.
    const test::Worst worst = test::runAgainst(
        m.scene, m.cable, {m.axle}, 42, [&] { return -w.body(m.heavy).v.y() / w.time(); }, want.acceleration,
        {want.tension_light, want.tension_heavy});
    const double turns_per_substep = std::abs(w.body(m.wheel).omega.z()) / 60.0 / (2.0 * std::numbers::pi);
    std::printf("[ measured ] %g mm wheel of %g kg, 1:100: %.1f turns per substep at the end\n", 1e3 * radius,
                wheel_kg, turns_per_substep);
    test::print("Atwood 1:100 on a " + test::str(1e3 * radius) + " mm wheel", spec.budget, worst);
    EXPECT_GT(turns_per_substep, 15.0);
    EXPECT_LT(worst.acceleration, 1e-2);
    EXPECT_LT(worst.tension, 1e-2);
    EXPECT_LT(worst.axle, 1e-6);
    // Every turn paid out its 2 pi r = 6.3 mm: the heavy side's rest length
    // grew by exactly the heavy box's drop. (The bookkeeping runs at the
    // start of a substep; one more update counts the last solve's turn.)
    m.scene.cables->update(w.time());
    EXPECT_NEAR(m.scene.cables->restLength(m.cable, 1) - rest0, y0 - w.body(m.heavy).x.y(), 1e-6);
    EXPECT_NEAR(m.scene.cables->totalLength(m.cable), total, 1e-9 * total);
  }
}

}  // namespace
}  // namespace reeve::test_fast_wheel
