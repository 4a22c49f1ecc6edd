// A World and its CableSystem at a test budget, for tests that build a
// machine body by body (friction wraps, off-centre sections).
#pragma once

#include <cmath>

#include <gtest/gtest.h>

#include "reeve/cable/cable.h"
#include "solver_budgets.h"

namespace reeve::test {

/// Gravity -g along y (m/s^2) with g = kCableMachineG.
inline constexpr double kCableMachineG = 9.81;

struct CableMachine {
  World world;
  CableSystem cables{world};
  int cable = 0;       ///< the cable under test, once added
  double total = 0.0;  ///< its total length (m) when added
  explicit CableMachine(const Budget& b) : world(settings(b)) {
    world.settings().gravity = Vec3(0.0, -kCableMachineG, 0.0);
  }
  /// A 10 cm cube of `mass` (kg) at `at` (m).
  BodyId box(double mass, const Vec3& at) {
    BodyDef def;
    def.shape = Shape::box(Vec3::Constant(0.05));
    def.mass = mass;
    def.position = at;
    return world.addBody(def);
  }
  /// A static cylinder of radius `r` (m) at `at` (m), its axis along z.
  BodyId drum(double r, const Vec3& at) {
    BodyDef def;
    def.shape = Shape::cylinder(r, 0.05);
    def.is_static = true;
    def.position = at;
    return world.addBody(def);
  }
  /// `seconds` of 60 Hz frames.
  void run(double seconds) {
    const int frames = static_cast<int>(std::lround(seconds * 60.0));
    for (int f = 0; f < frames; ++f) world.step(1.0 / 60.0);
  }
  /// The bookkeeping held after every substep and the length is what it was.
  void expectLengthKept() const {
    EXPECT_FALSE(cables.firstBreach().has_value()) << cables.firstBreach()->what;
    EXPECT_NEAR(cables.totalLength(cable), total, 1e-9 * total);
  }
};

}  // namespace reeve::test
