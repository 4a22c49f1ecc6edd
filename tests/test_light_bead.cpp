// A light body that only cables hold, between a fixed anchor and a heavy
// load: sideways it is a pendulum of (h omega)^2 = |lambda| / (m length),
// which the direct solver's Newton steps hold only with the spans'
// sideways stiffness (DirectSolver::newtonResidual, bend_).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "reeve/cable/cable.h"
#include "reeve/scene/energy.h"
#include "scene_fixture.h"
#include "solver_budgets.h"

namespace reeve::test_light_bead {
namespace {

// A bead of `mass` kg on two rigid cables: up to a ceiling point `offset`
// m to the side of it, down 1 m to a box of `load` kg hanging below it.
// The chain starts at rest, bent by that offset. `ceiling`: the ceiling's
// JSON besides its shape and position ("static", or a motion).
Scene bead(const test::Budget& b, double mass, const std::string& ceiling = R"("static": true)", double load = 40.0,
           double offset = 0.01) {
  const std::string json = R"({"name": "bead", )" + test::solverJson(b) + R"(, "duration_s": 3.0,
    "bodies": [
      {"name": "ceiling", )" + ceiling + R"(, "shape": {"type": "box", "half_extents_m": [0.1, 0.02, 0.1]},
       "position_m": [)" + std::to_string(offset) + R"(, 1.02, 0]},
      {"name": "bead", "shape": {"type": "sphere", "radius_m": 0.02}, "mass_kg": )" + std::to_string(mass) + R"(,
       "position_m": [0, 0, 0]},
      {"name": "load", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": )" + std::to_string(load) + R"(,
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

// A bead a million times lighter than its load (5 g under 4 t), the chain
// bent 30 cm: the load falls 2.2 cm until the cables line up and swings.
// The bead has no motion of its own against such a load, and is placed on
// its spans as a massless one (engine/src/light_bodies.h). Before, the
// direct solver's Newton steps on the tightrope needed 3 to 8 iterations
// a substep as the chain lined up; with fewer the cables ended each
// substep millimetres long, and the next threw the load up at the stretch
// over h: 2.7e4, 7.8e4 and 1.3e5 J made in a frame at 1 x 1, 10 x 2 and
// 100 x 1. Gauss-Seidel's visits moved the bead, not the load: 9.4e2 and
// 1.4e3 J at 32 x 32 and 100 x 1; its run is now one row.
TEST(LightBead, AMillionTimesLighterThanItsLoadAndStartingBentItMakesNothingAtAnyBudget) {
  const double g = 9.81, load = 4000.0, mass = 0.005;
  const double upper_rest = std::hypot(0.3, 1.0), lower_rest = 1.0;
  std::vector<test::Budget> budgets;
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel})
    for (const auto& [substeps, iterations] : {std::pair{1, 1}, {1, 2}, {1, 10}, {10, 2}, {32, 32}, {100, 1}})
      budgets.push_back({solver, substeps, iterations});
  for (const test::Budget& b : budgets) {
    SCOPED_TRACE(test::name(b));
    Scene s = bead(b, mass, R"("static": true)", load, 0.3);
    EnergyWatch watch(s);
    const int upper = test::cable(s, "upper"), lower = test::cable(s, "lower");
    const BodyId bead_id = test::body(s, "bead"), load_id = test::body(s, "load");
    const Vec3 top(0.3, 1.0, 0.0);
    double most_stretch = 0.0, most_off_line = 0.0, most_kinetic = 0.0;
    for (int f = 0; f < 120; ++f) {
      test::frame(s);
      const auto created = watch.check(s);
      ASSERT_FALSE(created) << energyCreatedMessage(*created);
      const Vec3 bead_x = s.world->body(bead_id).x;
      const Vec3 hook = s.world->body(load_id).toWorld(Vec3(0.0, 0.1, 0.0));
      most_stretch = std::max({most_stretch, (bead_x - top).norm() - upper_rest, (hook - bead_x).norm() - lower_rest});
      // Once taut (from 0.1 s): on the line from the ceiling point to the
      // load's top, both cables pulling alike.
      if (f < 6) continue;
      const Vec3 along = (hook - top).normalized();
      most_off_line = std::max(most_off_line, ((bead_x - top) - along * along.dot(bead_x - top)).norm());
      const double t_upper = s.cables->tension(upper, 0), t_lower = s.cables->tension(lower, 0);
      EXPECT_NEAR(t_upper, t_lower, 1e-3 * t_lower + mass * g) << "frame " << f;
      EXPECT_GT(t_lower, 0.5 * load * g) << "frame " << f;
      most_kinetic = std::max(most_kinetic, 0.5 * load * s.world->body(load_id).v.squaredNorm());
    }
    EXPECT_LT(most_stretch, 1e-5);  // m; millimetres before (2.6 mm at 10 x 2)
    EXPECT_LT(most_off_line, 1e-4);
    // The load can go no lower than the straight chain below the ceiling
    // point, 4.4 cm under where it started: no more than m g h of that as
    // motion (the catch 2.2 cm down loses some).
    EXPECT_LT(most_kinetic, load * g * 0.044);
  }
}

// A massless bead moves as its chain does. Placed on its spans each
// substep, it kept the velocity its integration gave it, which no solve
// took back: hanging still under 40 kg, a 1 g bead read -49 m/s after 10 s
// (gravity's g h a substep), and its kinetic energy grew without a force
// doing work (1.2 J by then). The chain lowered at 0.5 m/s by a moving
// ceiling and stopped: the bead's velocity is the ceiling's, then none.
TEST(LightBead, APlacedBeadMovesWithItsChainNotWithGravity) {
  const std::string lowering = R"("motion": [{"t_s": 0, "velocity_m_per_s": [0, -0.5, 0]},
    {"t_s": 1, "velocity_m_per_s": [0, -0.5, 0]}, {"t_s": 1.5, "velocity_m_per_s": [0, 0, 0]}])";
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel})
    for (const bool lowered : {false, true}) {
      const test::Budget b{solver, 10, 2};
      SCOPED_TRACE(test::name(b) + (lowered ? ", lowered" : ", still"));
      Scene s = bead(b, 0.001, lowered ? lowering : R"("static": true)", 40.0, 0.0);
      const BodyId bead_id = test::body(s, "bead"), ceiling_id = test::body(s, "ceiling");
      double most_off = 0.0;
      for (int f = 0; f < 240; ++f) {
        test::frame(s);
        // Once the load, which falls free at first under the lowered
        // chain, is caught (0.5 s).
        if (f < 30) continue;
        const Vec3 v = s.world->body(bead_id).v, chain = s.world->body(ceiling_id).v;
        most_off = std::max(most_off, (v - chain).norm());
      }
      EXPECT_LT(most_off, 1e-6);  // m/s
    }
}

// The bead placed as massless is a limit, and the same motion at any
// scale: 1 mg under 1 kg and 4 g under 4 t (masses 4000 times, the same
// ratio) trace the same chain.
TEST(LightBead, AMasslessBeadsMotionIsTheSameAtAnyMassScale) {
  for (const test::Budget& b : {test::Budget{SolverKind::Direct, 1, 1}, test::Budget{SolverKind::Direct, 10, 2},
                                test::Budget{SolverKind::GaussSeidel, 10, 2}}) {
    SCOPED_TRACE(test::name(b));
    Scene small = bead(b, 1e-6, R"("static": true)", 1.0, 0.3);
    Scene large = bead(b, 4e-3, R"("static": true)", 4000.0, 0.3);
    for (int f = 0; f < 60; ++f) {
      test::frame(small);
      test::frame(large);
    }
    for (const char* name : {"bead", "load"}) {
      const Vec3 a = small.world->body(test::body(small, name)).x, c = large.world->body(test::body(large, name)).x;
      EXPECT_LT((a - c).norm(), 1e-9) << name;
    }
    EXPECT_NEAR(large.cables->tension(test::cable(large, "lower"), 0),
                4000.0 * small.cables->tension(test::cable(small, "lower"), 0), 1e-6 * 4000.0 * 9.81);
  }
}

// Three 1 g knots tied into a rigid cable to a 1 t load, the cable bent 30
// cm at the middle one: a run of light bodies, placed together
// (engine/src/light_bodies.h; each knot's neighbours are knots, so none is
// light against them alone). Before, 8.1e5, 9.5e3, 2.1e8 and 1.9e11 J
// were made in a frame at 1 x 1, 1 x 10, 10 x 2 and 100 x 1 (direct), 3.6e2
// and 6.2e2 J at 32 x 32 and 100 x 1 (Gauss-Seidel).
TEST(LightBead, AChainOfLightKnotsIsPlacedAsOneAndMakesNothing) {
  const double g = 9.81, load = 1000.0;
  std::string bodies = R"({"name": "ceiling", "static": true, "shape": {"type": "box", "half_extents_m": [0.1, 0.02, 0.1]},
    "position_m": [0.3, 1.02, 0]})";
  std::string cables;
  const Vec3 knots[] = {{0.15, 0.5, 0.0}, {0.0, 0.0, 0.0}, {0.0, -0.5, 0.0}};
  const auto tie = [](const std::string& body, double y) {
    return R"({"body": ")" + body + R"(", "type": "attachment", "point_m": [0, )" + std::to_string(y) + ", 0]}";
  };
  std::string last = "ceiling";
  double last_y = -0.02;
  for (int k = 0; k < 3; ++k) {
    const std::string name = "k" + std::to_string(k);
    bodies += R"(, {"name": ")" + name + R"(", "shape": {"type": "sphere", "radius_m": 0.01}, "mass_kg": 0.001,
      "position_m": [)" + std::to_string(knots[k].x()) + ", " + std::to_string(knots[k].y()) + ", 0]}";
    cables += R"({"name": "c)" + std::to_string(k) + R"(", "links": [)" + tie(last, last_y) + ", " + tie(name, 0.0) + "]}, ";
    last = name;
    last_y = 0.0;
  }
  bodies += R"(, {"name": "load", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": 1000.0,
    "position_m": [0, -1.1, 0]})";
  cables += R"({"name": "c3", "links": [)" + tie(last, 0.0) + ", " + tie("load", 0.1) + "]}";
  std::vector<test::Budget> budgets;
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel})
    for (const auto& [substeps, iterations] : {std::pair{1, 1}, {1, 10}, {10, 2}, {100, 1}})
      budgets.push_back({solver, substeps, iterations});
  for (const test::Budget& b : budgets) {
    SCOPED_TRACE(test::name(b));
    Scene s = parseScene(R"({"name": "knots", )" + test::solverJson(b) + R"(, "duration_s": 2.0, "bodies": [)" + bodies +
                             R"(], "cables": [)" + cables + "]}",
                         "knots");
    EnergyWatch watch(s);
    const Vec3 top(0.3, 1.0, 0.0);
    double most_stretch = 0.0, most_off_line = 0.0;
    for (int f = 0; f < 120; ++f) {
      test::frame(s);
      const auto created = watch.check(s);
      ASSERT_FALSE(created) << energyCreatedMessage(*created);
      for (int c = 0; c < 4; ++c)
        most_stretch = std::max(most_stretch, s.cables->length(c, 0) - s.cables->restLength(c, 0));
      if (f < 12) continue;  // taut from the catch on: one line, one tension
      const Vec3 hook = s.world->body(test::body(s, "load")).toWorld(Vec3(0.0, 0.1, 0.0));
      const Vec3 along = (hook - top).normalized();
      for (int k = 0; k < 3; ++k) {
        const Vec3 x = s.world->body(test::body(s, "k" + std::to_string(k))).x;
        most_off_line = std::max(most_off_line, ((x - top) - along * along.dot(x - top)).norm());
      }
      const double t_load = s.cables->tension(3, 0);
      EXPECT_GT(t_load, 0.5 * load * g) << "frame " << f;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.cables->tension(c, 0), t_load, 1e-3 * t_load) << "frame " << f;
    }
    // m. Gauss-Seidel's one visit of the run's row a sweep turns the load
    // about its tie point only to first order: at one iteration the catch
    // leaves the cable up to 0.84 mm long (1 x 1).
    const bool direct = b.solver == SolverKind::Direct;
    EXPECT_LT(most_stretch, direct ? 1e-5 : 2e-3);
    EXPECT_LT(most_off_line, direct ? 1e-4 : 1e-3);
  }
}

// Light knots hanging straight under a load, at rest or lifted at 1 m/s^2
// by a kinematic ceiling: the span under the lowest knot holds the load,
// M (g + a), and each span above it what hangs below it, the knots too.
// Placed as massless (light_bodies.h), a knot's weight and inertia are not
// all in the spans above it: the direct solver's read half of them (the
// knot is placed half-way into the excess its fall makes, and the solve
// lifts it by that half), Gauss-Seidel's none (its run is one row of the
// spans' summed length, one tension); at most kMasslessShare of the load
// is left out. Placed where it lies along the line instead, the direct
// solver's spans read it all, but a 1 g knot carried into a wheel
// (Jam.AKnotCarriedPastItsTangentPointAndBack...) drifted 9 mm on its rim
// (DESIGN, "Fifty-eighth session").
TEST(LightBead, APlacedKnotsSpansHoldTheLoadAndAtMostTheKnotsBelowThem) {
  const double g = 9.81;
  const auto tie = [](const std::string& body, double y) {
    return R"({"body": ")" + body + R"(", "type": "attachment", "point_m": [0, )" + std::to_string(y) + ", 0]}";
  };
  const std::string lifting = R"("motion": [{"t_s": 0, "velocity_m_per_s": [0, 0, 0]},
    {"t_s": 2, "velocity_m_per_s": [0, 2, 0]}])";
  struct Hang {
    double load, knot;
    std::vector<double> heights;  // the knots' y, m (the ceiling's point at 1, the load's hook at -1)
  };
  const Hang hangs[] = {{1.0, 1e-3, {0.0}},  {1.0, 2e-3, {0.7}},         {1.0, 1e-6, {-0.6}},
                        {4000.0, 4.0, {0.3}}, {1000.0, 1.0, {0.5, 0.0, -0.5}}};
  std::vector<test::Budget> budgets;
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel})
    for (const auto& [substeps, iterations] : {std::pair{1, 1}, {1, 10}, {10, 2}, {32, 32}, {100, 1}})
      budgets.push_back({solver, substeps, iterations});
  budgets.push_back({SolverKind::Direct, 10, 2, Projection::Start});
  for (const Hang& hang : hangs)
    for (const bool lifted : {false, true})
      for (const test::Budget& b : budgets) {
        const int n = static_cast<int>(hang.heights.size());
        SCOPED_TRACE(test::name(b) + ", " + std::to_string(n) + " knots of " + std::to_string(hang.knot) + " kg under " +
                     std::to_string(hang.load) + " kg" + (lifted ? ", lifted" : ", still"));
        std::string bodies = R"({"name": "ceiling", )" + std::string(lifted ? lifting : R"("static": true)") +
                             R"(, "shape": {"type": "box", "half_extents_m": [0.1, 0.02, 0.1]}, "position_m": [0, 1.02, 0]})";
        std::string cables, last = "ceiling";
        double last_y = -0.02;
        for (int k = 0; k < n; ++k) {
          const std::string name = "k" + std::to_string(k);
          bodies += R"(, {"name": ")" + name + R"(", "shape": {"type": "sphere", "radius_m": 0.01}, "mass_kg": )" +
                    std::to_string(hang.knot) + R"(, "position_m": [0, )" + std::to_string(hang.heights[k]) + ", 0]}";
          cables += R"({"name": "c)" + std::to_string(k) + R"(", "links": [)" + tie(last, last_y) + ", " + tie(name, 0.0) +
                    "]}, ";
          last = name;
          last_y = 0.0;
        }
        bodies += R"(, {"name": "load", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": )" +
                  std::to_string(hang.load) + R"(, "position_m": [0, -1.1, 0]})";
        cables += R"({"name": "c)" + std::to_string(n) + R"(", "links": [)" + tie(last, 0.0) + ", " + tie("load", 0.1) + "]}";
        Scene s = parseScene(R"({"name": "knots", )" + test::solverJson(b) + R"(, "duration_s": 1.0, "bodies": [)" +
                                 bodies + R"(], "cables": [)" + cables + "]}",
                             "knots");
        EnergyWatch watch(s);
        for (int f = 0; f < 60; ++f) {
          test::frame(s);
          const auto created = watch.check(s);
          ASSERT_FALSE(created) << energyCreatedMessage(*created);
        }
        const double a = lifted ? 1.0 : 0.0;  // m/s^2, up
        // N: rounding (lifted, the load's tension came out up to 1.6e-9 of
        // itself short).
        const double tolerance = 1e-8 * hang.load * (g + a);
        EXPECT_NEAR(s.cables->tension(n, 0), hang.load * (g + a), tolerance);
        // Span c holds the load and at most the knots c..n-1 below it, each
        // span no less than the one below it.
        for (int c = 0; c < n; ++c) {
          EXPECT_GE(s.cables->tension(c, 0), s.cables->tension(c + 1, 0) - tolerance) << "span " << c;
          EXPECT_LE(s.cables->tension(c, 0), (hang.load + (n - c) * hang.knot) * (g + a) + tolerance) << "span " << c;
        }
      }
}

// A knot tied in a cable where it comes off a hinged wheel (2 kg, r = 10
// cm): 100 kg hangs on the wheel's other side, 120 kg from the knot, the
// knot 5 cm off the line to the heavy box. Its wheel span's end rolls, so
// the knot was not placed: 4.9e3 J made in a frame at 1 x 1 with a 1 g
// knot, 3.4e5 J at 10 x 2 and 1.3e4 J at 100 x 1 with 1 mg (direct). The
// solve holds the rolling end's tangent point and counts what its turn
// pays out (light_bodies.h), and the knot is placed on its spans as on
// any other. Once lined up the machine is an Atwood machine with a
// massive wheel, a = (m_b - m_a) g / (m_a + m_b + I / r^2), the tension
// under the knot m_b (g - a). Both orders of the cable's links.
TEST(LightBead, AKnotInACableComingOffAWheelIsPlacedAndTheMachineRunsAsAnAtwoodMachine) {
  const double g = 9.81, m_a = 100.0, m_b = 120.0, r = 0.1, inertia = 0.5 * 2.0 * r * r;
  const double accel = (m_b - m_a) * g / (m_a + m_b + inertia / (r * r)), tension = m_b * (g - accel);
  const auto tie = [](const char* body, double y) {
    return std::string(R"({"body": ")") + body + R"(", "type": "attachment", "point_m": [0, )" + std::to_string(y) +
           ", 0]}";
  };
  const std::string wheel_cw = R"({"body": "wheel", "type": "rolling", "orientation": "cw"})";
  const std::string wheel_ccw = R"({"body": "wheel", "type": "rolling", "orientation": "ccw"})";
  // Gauss-Seidel from 32 x 32 (below, one visit of the run's row a sweep
  // leaves the spans up to 4 mm long at 10 x 2 and 1.7 m at 1 x 1).
  const test::Budget budgets[] = {{SolverKind::Direct, 1, 1},       {SolverKind::Direct, 1, 10},
                                  {SolverKind::Direct, 10, 2},      {SolverKind::Direct, 100, 1},
                                  {SolverKind::GaussSeidel, 32, 32}, {SolverKind::GaussSeidel, 100, 1}};
  for (const bool reversed : {false, true})
    for (const double knot : {1e-6, 1e-3})
      for (const test::Budget& b : budgets) {
        const int substeps = b.substeps, iterations = b.iterations;
        SCOPED_TRACE(test::name(b) + ", knot " + std::to_string(knot) + " kg" + (reversed ? ", reversed" : ""));
        const std::string rope = reversed ? tie("knot", 0.0) + ", " + wheel_ccw + ", " + tie("a", 0.05)
                                          : tie("a", 0.05) + ", " + wheel_cw + ", " + tie("knot", 0.0);
        const std::string tail =
            reversed ? tie("b", 0.05) + ", " + tie("knot", 0.0) : tie("knot", 0.0) + ", " + tie("b", 0.05);
        Scene s = parseScene(R"({"name": "knot_wheel", )" + test::solverJson(b) + R"(, "duration_s": 1.5,
          "bodies": [
            {"name": "wheel", "shape": {"type": "cylinder", "radius_m": 0.1, "half_length_m": 0.02}, "mass_kg": 2.0,
             "position_m": [0, 0, 0]},
            {"name": "a", "shape": {"type": "box", "half_extents_m": [0.05, 0.05, 0.05]}, "mass_kg": 100.0,
             "position_m": [-0.1, -1.05, 0]},
            {"name": "knot", "shape": {"type": "sphere", "radius_m": 0.01}, "mass_kg": )" + std::to_string(knot) + R"(,
             "position_m": [0.15, -0.5, 0]},
            {"name": "b", "shape": {"type": "box", "half_extents_m": [0.05, 0.05, 0.05]}, "mass_kg": 120.0,
             "position_m": [0.1, -1.05, 0]}],
          "hinges": [{"body": "wheel", "anchor_m": [0, 0, 0], "axis": [0, 0, 1]}],
          "cables": [{"name": "rope", "links": [)" + rope + R"(]}, {"name": "tail", "links": [)" + tail + "]}]}",
                             "knot_wheel");
        EnergyWatch watch(s);
        const int rope_id = test::cable(s, "rope"), tail_id = test::cable(s, "tail");
        const int wheel_span = reversed ? 0 : 1;
        const BodyId knot_id = test::body(s, "knot"), b_id = test::body(s, "b");
        double most_stretch = 0.0, most_off_line = 0.0;
        for (int f = 0; f < 60; ++f) {
          test::frame(s);
          const auto created = watch.check(s);
          ASSERT_FALSE(created) << energyCreatedMessage(*created);
          most_stretch =
              std::max({most_stretch, s.cables->length(rope_id, wheel_span) - s.cables->restLength(rope_id, wheel_span),
                        s.cables->length(tail_id, 0) - s.cables->restLength(tail_id, 0)});
          if (f < 20) continue;  // lined up and accelerating (Gauss-Seidel at 100 x 1 rings till 0.3 s)
          // On the line from the wheel's right rim (its tangent point) to
          // b's hook, one tension either side of it: that of the closed form.
          const Vec3 rim(r, 0.0, 0.0), hook = s.world->body(b_id).toWorld(Vec3(0.0, 0.05, 0.0));
          const Vec3 along = (hook - rim).normalized(), x = s.world->body(knot_id).x;
          most_off_line = std::max(most_off_line, ((x - rim) - along * along.dot(x - rim)).norm());
          const double t_tail = s.cables->tension(tail_id, 0), t_rope = s.cables->tension(rope_id, wheel_span);
          EXPECT_NEAR(t_tail, tension, 0.01 * tension) << "frame " << f;
          EXPECT_NEAR(t_rope, t_tail, 1e-3 * t_tail + knot * g) << "frame " << f;
        }
        // m: one Newton step a substep (1 x 1) leaves the wheel's span 0.2 mm
        // long; a second, 5e-7 m.
        EXPECT_LT(most_stretch, substeps * iterations == 1 ? 5e-4 : 1e-6);
        EXPECT_LT(most_off_line, 1e-4);  // m
        // The knot, on the line to b, moves as b does.
        const Vec3 v_b = s.world->body(b_id).v;
        EXPECT_LT((s.world->body(knot_id).v - v_b).norm(), 1e-2 * v_b.norm());
        // b's speed after 1 s: a t, the lining up taking next to nothing.
        EXPECT_NEAR(-s.world->body(b_id).v.y(), accel * 1.0, 5e-3 * accel);
      }
}

// A knot tied between two cables, each coming off a hinged wheel (2 kg, r
// = 10 cm, 1 m apart) with 100 and 101 kg hanging on their outer sides,
// the knot starting 40 cm below the wheels' tops. Neither of its run's
// end bodies is dynamic, so it is light against the wheels with what
// their other spans carry (findLightBodies); unplaced, the direct solver
// made 3.1e6 J in a frame at 10 x 2 (1 mg) and 8.7e3 J at 100 x 1 (1 g).
// The loads drop as the knot is pulled up onto the line over the
// wheels' tops, then run as an Atwood machine with two massive wheels.
TEST(LightBead, AKnotBetweenTwoWheelsIsPlacedOnTheLineOverThem) {
  const double g = 9.81, m_a = 100.0, m_b = 101.0, r = 0.1, inertia = 0.5 * 2.0 * r * r;
  const double accel = (m_b - m_a) * g / (m_a + m_b + 2.0 * inertia / (r * r)), tension = m_b * (g - accel);
  for (const double knot : {1e-6, 1e-3})
    for (const auto& [substeps, iterations] : {std::pair{1, 1}, {1, 10}, {10, 2}, {100, 1}}) {
      const test::Budget b{SolverKind::Direct, substeps, iterations};
      SCOPED_TRACE(test::name(b) + ", knot " + std::to_string(knot) + " kg");
      Scene s = parseScene(R"({"name": "knot_between_wheels", )" + test::solverJson(b) + R"(, "duration_s": 2.0,
        "bodies": [
          {"name": "left", "shape": {"type": "cylinder", "radius_m": 0.1, "half_length_m": 0.02}, "mass_kg": 2.0,
           "position_m": [0, 0, 0]},
          {"name": "right", "shape": {"type": "cylinder", "radius_m": 0.1, "half_length_m": 0.02}, "mass_kg": 2.0,
           "position_m": [1, 0, 0]},
          {"name": "a", "shape": {"type": "box", "half_extents_m": [0.05, 0.05, 0.05]}, "mass_kg": 100.0,
           "position_m": [-0.1, -1.05, 0]},
          {"name": "knot", "shape": {"type": "sphere", "radius_m": 0.01}, "mass_kg": )" + std::to_string(knot) + R"(,
           "position_m": [0.5, -0.3, 0]},
          {"name": "b", "shape": {"type": "box", "half_extents_m": [0.05, 0.05, 0.05]}, "mass_kg": 101.0,
           "position_m": [1.1, -1.05, 0]}],
        "hinges": [{"body": "left", "anchor_m": [0, 0, 0], "axis": [0, 0, 1]},
                   {"body": "right", "anchor_m": [1, 0, 0], "axis": [0, 0, 1]}],
        "cables": [
          {"name": "rope", "links": [{"body": "a", "type": "attachment", "point_m": [0, 0.05, 0]},
                                     {"body": "left", "type": "rolling", "orientation": "cw"},
                                     {"body": "knot", "type": "attachment", "point_m": [0, 0, 0]}]},
          {"name": "tail", "links": [{"body": "knot", "type": "attachment", "point_m": [0, 0, 0]},
                                     {"body": "right", "type": "rolling", "orientation": "cw"},
                                     {"body": "b", "type": "attachment", "point_m": [0, 0.05, 0]}]}]})",
                           "knot_between_wheels");
      EnergyWatch watch(s);
      const int rope = test::cable(s, "rope"), tail = test::cable(s, "tail");
      const BodyId knot_id = test::body(s, "knot"), b_id = test::body(s, "b");
      double most_off_line = 0.0;
      for (int f = 0; f < 120; ++f) {
        test::frame(s);
        const auto created = watch.check(s);
        ASSERT_FALSE(created) << energyCreatedMessage(*created);
        if (f < 30) continue;  // lined up over the wheels' tops, caught
        most_off_line = std::max(most_off_line, std::abs(s.world->body(knot_id).x.y() - r));
        EXPECT_NEAR(s.cables->tension(tail, 0), tension, 0.01 * tension) << "frame " << f;
        EXPECT_NEAR(s.cables->tension(rope, 1), s.cables->tension(tail, 0), 1e-3 * tension) << "frame " << f;
        // The knot goes along the line as fast as the cable: b's speed.
        const Vec3 v = s.world->body(knot_id).v;
        EXPECT_NEAR(v.x(), s.world->body(b_id).v.norm(), 1e-2 * s.world->body(b_id).v.norm() + 1e-6) << "frame " << f;
      }
      EXPECT_LT(most_off_line, 1e-4);  // m
    }
}

}  // namespace
}  // namespace reeve::test_light_bead
