// Issue 9, item 4: one cable zig-zagging over K = 2 .. 128 hinged wheels
// (1 g, then 1 kg) between 1 kg and 2 kg boxes meets its closed form within
// 0.1 % at one step of 10 iterations per frame: acceleration, all K + 1
// tensions, axles and stretch.
#include <gtest/gtest.h>

#include "run_machine.h"

namespace reeve {
namespace {

TEST(LongCables, ZigZagOverManyWheelsMeetsItsClosedFormAtOneStepOfTenIterations) {
  const machines::Budget paper{1, 10};
  for (const double wheel_kg : {1e-3, 1.0})
    for (const int K : {2, 8, 32, 128}) {
      machines::ZigZagSpec spec;
      spec.wheels = K;
      spec.wheel_kg = wheel_kg;
      spec.budget = paper;
      machines::ZigZag m = machines::zigzag(spec);
      const auto want = machines::zigzagMotion(K, spec.light_kg, spec.heavy_kg, wheel_kg, spec.gravity);
      World& w = *m.scene.world;
      const test::Worst worst = test::runAgainst(
          m.scene, m.cable, m.axles, 30, [&] { return -w.body(m.heavy).v.y() / w.time(); }, want.acceleration,
          want.tensions);
      test::print("zig-zag K = " + std::to_string(K) + ", wheels " + test::str(wheel_kg) + " kg", paper, worst);
      SCOPED_TRACE("K = " + std::to_string(K) + ", wheels " + test::str(wheel_kg) + " kg");
      EXPECT_LT(worst.acceleration, 1e-3);
      EXPECT_LT(worst.tension, 1e-3);
      EXPECT_LT(worst.axle, 1e-6);
      EXPECT_LT(worst.stretch, 1e-4);
    }
}

}  // namespace
}  // namespace reeve
