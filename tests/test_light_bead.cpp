// A light body that only cables hold, between a fixed anchor and a heavy
// load: sideways it is a pendulum of (h omega)^2 = |lambda| / (m length),
// which the direct solver's Newton steps hold only with the spans'
// sideways stiffness (DirectSolver::newtonResidual, bend_).
#include <gtest/gtest.h>

#include <string>

#include "reeve/cable/cable.h"
#include "reeve/scene/energy.h"
#include "scene_fixture.h"
#include "solver_budgets.h"

namespace reeve::test_light_bead {
namespace {

// A bead of `mass` kg on two rigid 1 m cables: up to a ceiling point 1 cm
// to the side of it, down to a 40 kg box hanging below it. The chain
// starts at rest, bent by that centimetre. `ceiling`: the ceiling's
// JSON besides its shape and position ("static", or a motion).
Scene bead(const test::Budget& b, double mass, const std::string& ceiling = R"("static": true)") {
  const std::string json = R"({"name": "bead", )" + test::solverJson(b) + R"(, "duration_s": 3.0,
    "bodies": [
      {"name": "ceiling", )" + ceiling + R"(, "shape": {"type": "box", "half_extents_m": [0.1, 0.02, 0.1]},
       "position_m": [0.01, 1.02, 0]},
      {"name": "bead", "shape": {"type": "sphere", "radius_m": 0.02}, "mass_kg": )" + std::to_string(mass) + R"(,
       "position_m": [0, 0, 0]},
      {"name": "load", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": 40.0,
       "position_m": [0, -1.1, 0]}],
    "cables": [
      {"name": "upper", "links": [{"body": "ceiling", "type": "attachment", "point_m": [0, -0.02, 0]},
                                  {"body": "bead", "type": "attachment", "point_m": [0, 0, 0]}]},
      {"name": "lower", "links": [{"body": "bead", "type": "attachment", "point_m": [0, 0, 0]},
                                  {"body": "load", "type": "attachment", "point_m": [0, 0.1, 0]}]}]})";
  return parseScene(json, "bead");
}

TEST(LightBead, BetweenACeilingAndALoadEightHundredToEightThousandTimesHeavierItHangsStill) {
  // Before the spans' sideways stiffness, at 1 x 10: the 50 g bead was
  // flung metres sideways in a solve, the cables stretched 8 cm with no
  // tension, and 6e4 J were made in a frame (3e3 J at 1 x 1). The chain
  // settles straight under the ceiling point, each cable holding what
  // hangs below it; the 1 cm bend it starts with swings the load 0.3 mm.
  const double g = 9.81, load = 40.0;
  // At one iteration a substep (1 x 1) the substep's one solve has no
  // lambda yet to stiffen the bead sideways: the first solve moved it past
  // its line and back (360 J in a frame, the cables 0 to 4.8 kN) until a
  // span's fixed ends moved past their closest approach stiffened the
  // lighter one (DirectSolver::stiffenMoves).
  const test::Budget budgets[] = {{SolverKind::Direct, 1, 1},
                                  {SolverKind::Direct, 1, 10},
                                  {SolverKind::Direct, 10, 2},
                                  {SolverKind::Direct, 32, 32},
                                  {SolverKind::Direct, 100, 1}};
  for (const test::Budget& b : budgets)
    for (const double mass : {0.05, 0.005}) {
      SCOPED_TRACE(test::name(b) + ", bead " + std::to_string(mass) + " kg");
      Scene s = bead(b, mass);
      EnergyWatch watch(s);
      for (int f = 0; f < 180; ++f) {
        test::frame(s);
        const auto created = watch.check(s);
        ASSERT_FALSE(created) << energyCreatedMessage(*created);
      }
      const int upper = test::cable(s, "upper"), lower = test::cable(s, "lower");
      EXPECT_NEAR(s.cables->tension(upper, 0), (load + mass) * g, 0.01 * load * g);
      EXPECT_NEAR(s.cables->tension(lower, 0), load * g, 0.01 * load * g);
      // On the line from the ceiling point to the load's top, and the
      // cables their rest length.
      const Vec3 top(0.01, 1.0, 0.0), bead_x = s.world->body(test::body(s, "bead")).x;
      const Vec3 hook = s.world->body(test::body(s, "load")).toWorld(Vec3(0.0, 0.1, 0.0));
      const Vec3 along = (hook - top).normalized();
      EXPECT_LT(((bead_x - top) - along * along.dot(bead_x - top)).norm(), 2e-3);
      EXPECT_NEAR((bead_x - top).norm(), 1.0, 1e-3);
      EXPECT_NEAR((hook - bead_x).norm(), 1.0, 1e-3);
    }
}

// Turned round: the ceiling lowers the chain at 0.5 m/s for a second and
// stops. The load falls away from it at first and is caught 5 cm down,
// the bead right above it; on the catch the first solve swings the bead
// sideways, across the lower span's closest approach already (s* ~ 0).
// Stiffened by that share, the bead was 1e13 times heavier in the solve
// and the upper cable booked 4.7e13 N against the lowering ceiling: 3.9e11
// J made in a frame at 1 x 1 (DirectSolver::stiffenMoves, kLeastMoveShare).
// Nothing is made, and once the ceiling stops the cables hold the load.
TEST(LightBead, LoweredByAMovingCeilingAndStoppedItMakesNothing) {
  const double g = 9.81, load = 40.0;
  const std::string lowering = R"("motion": [{"t_s": 0, "velocity_m_per_s": [0, -0.5, 0]},
    {"t_s": 1, "velocity_m_per_s": [0, -0.5, 0]}, {"t_s": 1.5, "velocity_m_per_s": [0, 0, 0]}])";
  const test::Budget budgets[] = {{SolverKind::Direct, 1, 1}, {SolverKind::Direct, 1, 10}, {SolverKind::Direct, 10, 2}};
  for (const test::Budget& b : budgets) {
    SCOPED_TRACE(test::name(b));
    Scene s = bead(b, 0.005, lowering);
    EnergyWatch watch(s);
    for (int f = 0; f < 180; ++f) {
      test::frame(s);
      const auto created = watch.check(s);
      ASSERT_FALSE(created) << energyCreatedMessage(*created);
    }
    EXPECT_NEAR(s.cables->tension(test::cable(s, "upper"), 0), (load + 0.005) * g, 0.01 * load * g);
    EXPECT_NEAR(s.cables->tension(test::cable(s, "lower"), 0), load * g, 0.01 * load * g);
  }
}

}  // namespace
}  // namespace reeve::test_light_bead
