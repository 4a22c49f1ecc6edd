// Issue 9, item 4: one cable zig-zagging over K = 2 .. 128 hinged wheels
// (1 g, then 1 kg) between 1 kg and 2 kg boxes meets its closed form within
// 0.1 % at one step of 10 iterations per frame: acceleration, all K + 1
// tensions, axles and stretch.
#include <gtest/gtest.h>

#include <utility>

#include "run_machine.h"

namespace reeve::test_long_cables {
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

TEST(LongCables, ABeltOverWheelsOfEveryMassSpinsUpAtTheMotorsTorque) {
  // A belt round K wheels of one radius, neighbours up to 1e12 apart in
  // mass (1e-6 kg next to 1e6 kg), turned by a motor of at most 100 N m:
  // the belt moves every wheel at one speed, so the motor spins up the sum
  // of their inertias, w(t) = tau t / sum I, at every wheel. The belt's
  // last span is a dependent row (its spans cannot be stretched apart by
  // turning wheels); the very light wheels make the others nearly so.
  // Wheels of 1 kg: within 1e-6. With the heavy ones the belt creeps
  // (alpha r = 4e-5 m/s^2 for 64 wheels), so the solver's stop at rows met
  // to 1e-10 m a substep, 6e-9 m/s, is 1e-4 of its speed: within 1e-3.
  for (const auto& [K, spread] : {std::pair{8, 0.0}, std::pair{64, 0.0}, std::pair{256, 0.0}, std::pair{8, 6.0},
                                 std::pair{64, 6.0}}) {
    machines::BeltRingSpec spec;
    spec.wheels = K;
    spec.spread = spread;
    spec.budget = {10, 2};
    machines::BeltRing m = machines::beltRing(spec);
    World& w = *m.scene.world;
    double inertia = 0.0;
    for (const BodyId id : m.wheels) inertia += 0.5 * w.bodyMass(id) * spec.radius_m * spec.radius_m;
    const double alpha = spec.motor_torque_Nm / inertia;
    const double spin_up = spec.motor_speed_rad_per_s / alpha;
    double worst = 0.0, stretch = 0.0;
    for (int f = 1; f <= 60; ++f) {
      w.step(1.0 / 60.0);
      const double t = f / 60.0, expected = t < spin_up ? alpha * t : spec.motor_speed_rad_per_s;
      if (std::abs(t - spin_up) < 1.0 / 60.0) continue;  // the frame it reaches the target
      for (const BodyId id : m.wheels) worst = std::max(worst, std::abs(w.body(id).omega.z() / expected - 1.0));
      stretch = std::max(stretch, machines::maxStretch(*m.scene.cables, m.cable));
    }
    std::printf("[ measured ] belt round %d wheels of 1e+-%g kg: speed error %.2e, stretch %.1e\n", K, spread, worst,
                stretch);
    SCOPED_TRACE("K = " + std::to_string(K) + ", spread " + test::str(spread));
    EXPECT_FALSE(w.firstNonFiniteBody());
    EXPECT_LT(worst, spread == 0.0 ? 1e-6 : 1e-3);
    EXPECT_LT(stretch, 1e-6);
  }
}

}  // namespace
}  // namespace reeve::test_long_cables
