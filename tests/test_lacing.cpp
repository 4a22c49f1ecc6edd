// A rigid rope laced through four holes of one plate, its ends tied to the
// ceiling: the spans between holes run from the plate to the plate, so no
// motion of the plate changes their lengths (chords of one body). Hung
// still, the two end spans hold the plate, (T_left + T_right) cos(a) = m
// g with a the end spans' angle from the vertical, and the plate stays
// where it hangs.
//
// Before the fix, a chord's row had a gradient zero but for rounding:
// with friction in the holes (the links sticking, every span its own
// row), the direct solver divided rounding by rounding, read 5e4 N in the
// first frame and threw a 1 kg plate 1.8 m (non-finite at 32 x 32); the
// path kernel turned the plate by each hole's opposed share in turn and
// made up to 4.5e6 J (Gauss-Seidel, 32 x 32). DESIGN, "Fifty-third
// session".
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "reeve/cable/cable.h"
#include "reeve/scene/energy.h"
#include "reeve/scene/scene.h"
#include "scene_fixture.h"
#include "solver_budgets.h"

namespace reeve::test_lacing {
namespace {

using namespace test;

constexpr double kG = 9.81;

/// The plate (0.8 x 0.2 m, `mass` kg) hung at the origin by a rope tied
/// to the ceiling at x = -0.6 and 0.6, 1 m up, through holes at x = -0.3,
/// -0.1, 0.1, 0.3 (the outer ones 5 cm above the plate's centre, the inner
/// ones 5 cm below), each with friction `mu` (0: frictionless).
Scene laced(const Budget& b, double mass, double mu) {
  std::string holes;
  for (const char* at : {"[-0.3, 0.05, 0]", "[-0.1, -0.05, 0]", "[0.1, -0.05, 0]", "[0.3, 0.05, 0]"})
    holes += std::string(R"({"body": "plate", "type": "pinhole", "point_m": )") + at +
             R"(, "mu": )" + std::to_string(mu) + "},";
  Scene s = parseScene(R"({"name": "laced", "duration_s": 2, )" + solverJson(b) + R"(,
    "bodies": [
      {"name": "ceiling", "static": true, "shape": {"type": "box", "half_extents_m": [1, 0.05, 0.2]},
       "position_m": [0, 1, 0]},
      {"name": "plate", "shape": {"type": "box", "half_extents_m": [0.4, 0.1, 0.05]}, "mass_kg": )" +
                           std::to_string(mass) + R"(, "position_m": [0, 0, 0]}],
    "cables": [{"name": "rope", "links": [
      {"body": "ceiling", "type": "attachment", "point_m": [-0.6, 0, 0]}, )" +
                           holes + R"(
      {"body": "ceiling", "type": "attachment", "point_m": [0.6, 0, 0]}]}]})",
                       "<laced>");
  s.world->settings().projection = b.projection;
  return s;
}

TEST(Lacing, ARopeLacedThroughHolesOfOnePlateHoldsItStill) {
  const double cos_a = 0.95 / std::hypot(0.3, 0.95);
  for (const Budget& b : kFourBudgets)
    for (const double mass : {1e-3, 1.0, 1e3})
      for (const double mu : {0.0, 0.3}) {
        SCOPED_TRACE(name(b) + ", " + std::to_string(mass) + " kg, mu " + std::to_string(mu));
        Scene s = laced(b, mass, mu);
        const BodyId plate = body(s, "plate");
        EnergyWatch watch(s);
        // The sum's error at one substep a frame is the slip's (the rope
        // slides through the holes a substep, then sticks, by turns);
        // 1e-4 from 32 x 32.
        const double tolerance = b.substeps == 1 ? (b.iterations == 1 ? 0.2 : 3e-3) : b.substeps < 32 ? 1e-2 : 1e-4;
        for (int f = 1; f <= 120; ++f) {
          frame(s);
          ASSERT_FALSE(watch.check(s)) << "frame " << f;
          ASSERT_LT(s.world->body(plate).x.norm(), 1e-2) << "frame " << f;  // it hangs where it was hung
          if (f > 30) {
            const double held = (s.cables->tension(0, 0) + s.cables->tension(0, 4)) * cos_a;
            EXPECT_NEAR(held, mass * kG, tolerance * mass * kG) << "frame " << f;
          }
        }
        if (mu == 0.0) {
          // One tension throughout, so each end pulls m g / (2 cos a). XPBD
          // reads it to O(h^2): 2.6e-4 short at one substep a frame (one
          // solve's linearization leaves the rope 3.5e-7 m long), 2.6e-6 at
          // ten, where a second solve is not needed for the tolerance.
          const double off = (1e-6 + 5e-4 / (b.substeps * b.substeps)) * mass * kG;
          EXPECT_NEAR(s.cables->tension(0, 0), mass * kG / (2.0 * cos_a), off);
          EXPECT_NEAR(s.cables->tension(0, 4), mass * kG / (2.0 * cos_a), off);
        }
      }
}

}  // namespace
}  // namespace reeve::test_lacing
