// A moving pulley under a frictionless rope over a sheave on a fixed axle:
// the rope runs from a ceiling anchor down under the lower pulley (the
// load, M kg), up over the upper sheave (a rotor) and down to a
// counterweight (m kg), every fall vertical, `mu: 0` on both wraps. The
// rope slides over both, so neither turns and the sheave's mass and spin
// do not matter; the length 2 (y_c - y_M) + (y_s - y_m) is fixed, so
// a_M = -a_m / 2 and, from 2 T - M g = M a_M and T - m g = m a_m,
//   a_m = g (M - 2 m) / (2 m + M / 2),   T = m (g + a_m).
// The run through the rotor's wrap is the path kernel's, its tangent
// points held on the sheave (cable_runs.cpp, buildRuns; DESIGN,
// "Fifty-fifth session"): at the ledger's four budgets, both projections
// and solvers, loads 1e-6 to 1e6 times the counterweight (loading and
// unloading), sheaves of 1e-6 and 1e6 kg, at rest or spun at 50 rad/s.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "reeve/scene/energy.h"
#include "reeve/scene/scene.h"
#include "scene_fixture.h"
#include "solver_budgets.h"

namespace reeve::test_frictionless_sheaves {
namespace {

using namespace test;

constexpr double kG = 9.81;  // m/s^2

Scene tackle(const Budget& b, double load, double counterweight, double sheave, double spin) {
  const auto num = [](double x) { return std::to_string(x); };
  Scene s = parseScene(R"({"name": "sheaves", "duration_s": 0.3, )" + solverJson(b) + R"(,
    "bodies": [
      {"name": "ceiling", "shape": {"type": "box", "half_extents_m": [0.05, 0.05, 0.05]}, "static": true,
       "position_m": [-0.4, 1, 0]},
      {"name": "sheave", "shape": {"type": "cylinder", "radius_m": 0.1, "half_length_m": 0.02}, "mass_kg": )" +
                           num(sheave) + R"(, "position_m": [0, 1, 0], "angular_velocity_rad_per_s": [0, 0, )" +
                           num(spin) + R"(]},
      {"name": "load", "shape": {"type": "cylinder", "radius_m": 0.1, "half_length_m": 0.02}, "mass_kg": )" +
                           num(load) + R"(, "position_m": [-0.2, -0.5, 0]},
      {"name": "counterweight", "shape": {"type": "box", "half_extents_m": [0.05, 0.05, 0.05]}, "mass_kg": )" +
                           num(counterweight) + R"(, "position_m": [0.1, -0.5, 0]}],
    "hinges": [{"body": "sheave", "anchor_m": [0, 1, 0], "axis": [0, 0, 1]}],
    "cables": [{"name": "rope", "links": [
      {"body": "ceiling", "type": "attachment", "point_m": [0.1, -0.05, 0]},
      {"body": "load", "type": "rolling", "orientation": "ccw", "mu": 0},
      {"body": "sheave", "type": "rolling", "orientation": "cw", "mu": 0},
      {"body": "counterweight", "type": "attachment", "point_m": [0, 0.05, 0]}]}]})",
                       "<sheaves>");
  s.world->settings().projection = b.projection;
  return s;
}

TEST(FrictionlessSheaves, AMovingPulleyUnderARopeOverARotorMeetsItsClosedFormAndLeavesTheSheaveAlone) {
  for (const Budget& b : fourBudgetsBothProjections())
    for (const auto& [load, counterweight] : {std::pair{2.0, 2.0}, {2.0, 0.5}, {1e6, 1.0}, {1.0, 1e6}})
      for (const double sheave : {1e-6, 1e6})
        for (const double spin : {0.0, 50.0}) {
          SCOPED_TRACE(name(b) + ", load " + std::to_string(load) + " kg, counterweight " +
                       std::to_string(counterweight) + " kg, sheave " + std::to_string(sheave) + " kg at " +
                       std::to_string(spin) + " rad/s");
          Scene s = tackle(b, load, counterweight, sheave, spin);
          const double a = kG * (load - 2 * counterweight) / (2 * counterweight + load / 2);
          const double tension = counterweight * (kG + a);
          EnergyWatch watch(s);
          for (int f = 1; f <= 18; ++f) {
            frame(s);
            ASSERT_FALSE(watch.check(s)) << "frame " << f;
            const double t = f / 60.0;
            ASSERT_NEAR(s.world->body(body(s, "counterweight")).v.y(), a * t, 1e-9 * 2 * kG * t) << "frame " << f;
            ASSERT_NEAR(s.world->body(body(s, "load")).v.y(), -a * t / 2, 1e-9 * kG * t) << "frame " << f;
            for (int span = 0; span < 3; ++span)
              ASSERT_NEAR(s.cables->tension(0, span), tension, 1e-9 * tension) << "frame " << f << ", span " << span;
            // The rope's pulls on the sheave cancel to their rounding, 1e-14
            // of T r, on its inertia (a 1e-6 kg sheave's 5e-9 kg m^2).
            const double rounding = 1e-14 * tension * 0.1 * t / (0.5 * sheave * 0.01);
            ASSERT_NEAR(s.world->body(body(s, "sheave")).omega.z(), spin, 1e-9 * (1.0 + spin) + rounding)
                << "frame " << f;
            ASSERT_NEAR(s.world->body(body(s, "load")).omega.z(), 0.0, 1e-9) << "frame " << f;
          }
        }
}

}  // namespace
}  // namespace reeve::test_frictionless_sheaves
