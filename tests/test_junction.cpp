// Junctions: cables joined in one length constraint (an ideal floating
// pulley block; MuJoCo's pulley branches). Three loads hang from the
// beam: A on a cable of divisor 1 (run over a pinhole), B and C on cables
// of divisor 2, so L_A + (L_B + L_C) / 2 stays at most its rest length, A
// is pulled up with T and B and C with T / 2. With each body hanging
// straight, a_A = T / m_A - g, a_B = T / (2 m_B) - g, a_C = T / (2 m_C) - g
// and a_A = -(a_B + a_C) / 2 give
//   T = 2 g / (1 / m_A + 1 / (4 m_B) + 1 / (4 m_C)).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "reeve/cable/cable.h"
#include "reeve/scene/energy.h"
#include "ledger_ratchet.h"
#include "scene_fixture.h"

namespace reeve::test_junction {
namespace {

constexpr double kG = 9.81;

struct Masses {
  double a, b, c;
};

double tensionOf(const Masses& m) { return 2.0 * kG / (1.0 / m.a + 0.25 / m.b + 0.25 / m.c); }

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// The three loads below the beam; `cable_extra` goes into each cable
// (compliance, damping), `b_divisor` is B's divisor.
std::string junctionScene(const test::Budget& budget, const Masses& m, const std::string& cable_extra = "",
                          double b_divisor = 2.0) {
  const auto box = [](const std::string& name, double mass, double x) {
    return R"({"name": ")" + name + R"(", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": )" +
           number(mass) + R"(, "position_m": [)" + number(x) + ", -1, 0]}";
  };
  const auto straight = [&](const std::string& name, const std::string& body, double x) {
    return R"({"name": ")" + name + R"(", )" + cable_extra + R"("links": [
      {"body": "beam", "type": "attachment", "point_m": [)" + number(x) + R"(, 0, 0]},
      {"body": ")" + body + R"(", "type": "attachment", "point_m": [0, 0.1, 0]}]})";
  };
  return R"({"name": "junction test", )" + test::solverJson(budget) + R"(, "bodies": [
    {"name": "beam", "shape": {"type": "box", "half_extents_m": [3, 0.1, 0.1]}, "static": true, "position_m": [0, 0, 0]},
    )" + box("a", m.a, -1.0) + ", " + box("b", m.b, 0.5) + ", " + box("c", m.c, 1.5) + R"(],
  "cables": [
    {"name": "a", )" + cable_extra + R"("links": [
      {"body": "beam", "type": "attachment", "point_m": [0, 0, 0]},
      {"body": "beam", "type": "pinhole", "point_m": [-1, 0, 0]},
      {"body": "a", "type": "attachment", "point_m": [0, 0.1, 0]}]},
    )" + straight("b", "b", 0.5) + ", " + straight("c", "c", 1.5) + R"(],
  "junctions": [{"name": "block", "branches": [
    {"cable": "a"}, {"cable": "b", "divisor": )" + number(b_divisor) + R"(}, {"cable": "c", "divisor": 2}]}]})";
}

struct Case {
  test::Budget budget;
  Masses masses;
};

std::string caseName(const Case& c) {
  return test::name(c.budget) + " " + number(c.masses.a) + " " + number(c.masses.b) + " " + number(c.masses.c);
}

class JunctionClosedForm : public testing::TestWithParam<Case> {};

TEST_P(JunctionClosedForm, AccelerationsAndTensionsMeetTheFloatingPulleysClosedForm) {
  const Case& param = GetParam();
  const Masses& m = param.masses;
  Scene s = parseScene(junctionScene(param.budget, m), "junction.json");
  const double T = tensionOf(m);
  const double a_a = T / m.a - kG, a_b = T / (2.0 * m.b) - kG, a_c = T / (2.0 * m.c) - kG;
  const int frames = 12;
  for (int f = 0; f < frames; ++f) test::frame(s);
  const double t = frames / s.frame_rate_hz;
  const double scale = std::max({std::abs(a_a), std::abs(a_b), std::abs(a_c)}) * t;
  // Implicit Euler under constant forces: v = a t exactly, whatever h.
  EXPECT_NEAR(s.world->body(test::body(s, "a")).v.y(), a_a * t, 1e-7 * scale);
  EXPECT_NEAR(s.world->body(test::body(s, "b")).v.y(), a_b * t, 1e-7 * scale);
  EXPECT_NEAR(s.world->body(test::body(s, "c")).v.y(), a_c * t, 1e-7 * scale);
  // A's cable pulls with T on both sides of its pinhole; B's and C's with T / 2.
  EXPECT_NEAR(s.cables->tension(test::cable(s, "a"), 0), T, 1e-7 * T);
  EXPECT_NEAR(s.cables->tension(test::cable(s, "a"), 1), T, 1e-7 * T);
  EXPECT_NEAR(s.cables->tension(test::cable(s, "b"), 0), T / 2.0, 1e-7 * T);
  EXPECT_NEAR(s.cables->tension(test::cable(s, "c"), 0), T / 2.0, 1e-7 * T);
  EXPECT_FALSE(s.cables->invariantViolation()) << *s.cables->invariantViolation();
}

std::vector<Case> cases() {
  std::vector<Case> all;
  // Uneven (A rises, C falls), one 1e-6 and one 1e6 of the others, a
  // 1.6 kN load.
  for (const Masses& m : {Masses{1.0, 1.0, 3.0}, Masses{1e-6, 1.0, 1.0}, Masses{1e6, 1.0, 1.0},
                          Masses{1.0, 1e6, 1e-6}, Masses{200.0, 200.0, 400.0}})
    for (const test::Budget& b : test::kFourBudgets) all.push_back({b, m});
  return all;
}

INSTANTIATE_TEST_SUITE_P(Junction, JunctionClosedForm, testing::ValuesIn(cases()),
                         [](const testing::TestParamInfo<Case>& info) { return test::parameterName(caseName(info.param)); });

TEST(Junction, BalancedLoadsStayWhereTheyAreAndTheCableStaysInTheJunction) {
  // m_A = 2 m_B = 2 m_C: T = m_A g holds them all, nothing moves; the
  // junction's sum_b L_b / divisor_b is its rest length, each cable at equal
  // strain (its rest length its length), and the cable total kept.
  for (const test::Budget& budget : test::kFourBudgets) {
    Scene s = parseScene(junctionScene(budget, Masses{2.0, 1.0, 1.0}), "junction.json");
    const Junction& junction = s.cables->junctions()[0];
    const double joined = junction.total_length;
    for (int f = 0; f < 60; ++f) test::frame(s);
    for (const char* name : {"a", "b", "c"})
      EXPECT_NEAR(s.world->body(test::body(s, name)).v.norm(), 0.0, 1e-9) << test::name(budget) << " " << name;
    EXPECT_NEAR(s.cables->tension(test::cable(s, "a"), 0), 2.0 * kG, 1e-9 * kG) << test::name(budget);
    double sum = 0.0;
    for (std::size_t b = 0; b < 3; ++b) {
      const int c = junction.cables[b];
      const int spans = static_cast<int>(s.cables->cables()[c].joints.size());
      for (int j = 0; j < spans; ++j) {
        sum += junction.scales[b] * s.cables->restLength(c, j);
        EXPECT_NEAR(s.cables->length(c, j), s.cables->restLength(c, j), 1e-9) << test::name(budget);
      }
    }
    EXPECT_NEAR(sum, joined, 1e-12 * joined);
  }
}

TEST(Junction, TheLoadsTradeCableAtTheDivisorsRatio) {
  // A falls by d: B and C rise by d together (their lengths' sum shortens
  // by 2 d). Cable moves between the cables: each one's total length
  // changes, the junction's sum_b total_b / divisor_b does not.
  Scene s = parseScene(junctionScene(test::kFourBudgets[1], Masses{5.0, 1.0, 1.0}), "junction.json");
  const auto y = [&](const char* name) { return s.world->body(test::body(s, name)).x.y(); };
  const double a0 = y("a"), b0 = y("b"), c0 = y("c");
  const double total_a = s.cables->totalLength(test::cable(s, "a"));
  for (int f = 0; f < 30; ++f) test::frame(s);
  s.cables->update(s.world->time());  // the rest lengths shared at these poses
  const double fall = a0 - y("a");
  EXPECT_GT(fall, 0.5);
  EXPECT_NEAR((y("b") - b0) + (y("c") - c0), 2.0 * fall, 1e-9);
  EXPECT_NEAR(s.cables->totalLength(test::cable(s, "a")) - total_a, fall, 1e-9);
  EXPECT_FALSE(s.cables->invariantViolation()) << *s.cables->invariantViolation();
}

TEST(Junction, ACompliantJunctionStretchesByItsComplianceTimesItsTension) {
  // Each cable of compliance c (m/N, the whole cable's): the junction's
  // path stretches sum_b c / divisor_b^2 = c (1 + 1/4 + 1/4) per newton of
  // T. Balanced and damped, it comes to rest at T = m_A g.
  const double c = 1e-4;
  for (const test::Budget& budget : test::kFourBudgets) {
    Scene s = parseScene(junctionScene(budget, Masses{2.0, 1.0, 1.0},
                                       R"("compliance_m_per_N": 1e-4, "damping_N_s_per_m": 2000, )"),
                         "junction.json");
    const Junction& junction = s.cables->junctions()[0];
    const double rest = s.world->path(junction.path).rest_length;
    for (int f = 0; f < 240; ++f) test::frame(s);
    const double T = 2.0 * kG, stretch = s.world->pathLength(junction.path) - rest;
    EXPECT_NEAR(s.cables->tension(test::cable(s, "a"), 0), T, 1e-3 * T) << test::name(budget);
    EXPECT_NEAR(stretch, 1.5 * c * T, 1e-3 * 1.5 * c * T) << test::name(budget);
  }
}

TEST(Junction, ADivisorOfThreeCountsAThirdOfTheCable) {
  // B at divisor 3: T_B = T / 3, a_A = -(a_B / 3 + a_C / 2), and
  // T = g (1 + 1/3 + 1/2) / (1 / m_A + 1 / (9 m_B) + 1 / (4 m_C)).
  const Masses m{2.0, 1.0, 1.5};
  Scene s = parseScene(junctionScene(test::kFourBudgets[1], m, "", 3.0), "junction.json");
  const double T = kG * (1.0 + 1.0 / 3.0 + 0.5) / (1.0 / m.a + 1.0 / (9.0 * m.b) + 1.0 / (4.0 * m.c));
  for (int f = 0; f < 12; ++f) test::frame(s);
  const double t = 12.0 / 60.0;
  EXPECT_NEAR(s.cables->tension(test::cable(s, "b"), 0), T / 3.0, 1e-7 * T);
  EXPECT_NEAR(s.world->body(test::body(s, "a")).v.y(), (T / m.a - kG) * t, 1e-7);
  EXPECT_NEAR(s.world->body(test::body(s, "b")).v.y(), (T / (3.0 * m.b) - kG) * t, 1e-7);
}

TEST(Junction, ALoadOn1024CablesOfDivisor1024IsAnAtwoodMachine) {
  // Many rows through one body: a 3 m wide load B hung from the beam by
  // N = 1024 vertical cables of divisor N, against a counterweight A on one
  // cable. B rising by d shortens each of them by d, which counts d / N,
  // N times: d in all, as A's one cable. So T_A = N (T / N) = T and the two
  // are an Atwood machine: T = 2 m_A m_B g / (m_A + m_B), each of B's
  // cables pulling with T / N; both solvers, 1 x 1 and 1 x 10, m_A of 1e-3
  // and 1e3 times m_B.
  constexpr int n = 1024;
  for (const test::Budget& budget : {test::Budget{SolverKind::Direct, 1, 1}, test::Budget{SolverKind::Direct, 1, 10},
                                     test::Budget{SolverKind::GaussSeidel, 1, 1}, test::Budget{SolverKind::GaussSeidel, 1, 10}})
    for (const double m_a : {2e-3, 2e3}) {
      SCOPED_TRACE(test::name(budget) + ", " + number(m_a) + " kg");
      const double m_b = 2.0;
      std::string cables = R"({"name": "lift", "links": [
        {"body": "beam", "type": "attachment", "point_m": [-3, 0, 0]},
        {"body": "a", "type": "attachment", "point_m": [0, 0.1, 0]}]})";
      std::string branches = R"({"cable": "lift"})";
      for (int i = 0; i < n; ++i) {
        const std::string x = number(-1.5 + 3.0 * i / (n - 1)), name = "\"hoist" + std::to_string(i) + "\"";
        cables += R"(, {"name": )" + name + R"(, "links": [
          {"body": "beam", "type": "attachment", "point_m": [)" + x + R"(, 0, 0]},
          {"body": "b", "type": "attachment", "point_m": [)" + x + R"(, 0.1, 0]}]})";
        branches += R"(, {"cable": )" + name + R"(, "divisor": )" + std::to_string(n) + "}";
      }
      Scene s = parseScene(R"({"name": "many rows", )" + test::solverJson(budget) + R"(, "bodies": [
        {"name": "beam", "shape": {"type": "box", "half_extents_m": [4, 0.1, 0.1]}, "static": true, "position_m": [0, 0.1, 0]},
        {"name": "a", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": )" + number(m_a) +
                               R"(, "position_m": [-3, -1, 0]},
        {"name": "b", "shape": {"type": "box", "half_extents_m": [1.5, 0.1, 0.1]}, "mass_kg": )" + number(m_b) +
                               R"(, "position_m": [0, -1, 0]}],
        "cables": [)" + cables + R"(], "junctions": [{"name": "block", "branches": [)" + branches + "]}]}",
                           "many.json");
      const double T = 2.0 * m_a * m_b * kG / (m_a + m_b), a_b = T / m_b - kG;
      for (int f = 0; f < 6; ++f) test::frame(s);
      const double t = 6.0 / 60.0;
      EXPECT_NEAR(s.world->body(test::body(s, "b")).v.y(), a_b * t, 1e-7 * kG * t);
      EXPECT_NEAR(s.world->body(test::body(s, "a")).v.y(), -a_b * t, 1e-7 * kG * t);
      EXPECT_NEAR(s.world->body(test::body(s, "b")).omega.norm(), 0.0, 1e-9);
      EXPECT_NEAR(s.cables->tension(test::cable(s, "lift"), 0), T, 1e-7 * T);
      EXPECT_NEAR(s.cables->tension(test::cable(s, "hoist511"), 0), T / n, 1e-7 * T / n);
      EXPECT_FALSE(s.cables->invariantViolation()) << *s.cables->invariantViolation();
    }
}

TEST(JunctionScene, TheCounterweightSinksAndTheLoadsRiseAsItsDescriptionSays) {
  // scenes/junction.json: 2.2 kg against two 1 kg loads, T = 20.55 N,
  // the counterweight sinking at 0.467 m/s^2 and each load rising as fast.
  Scene s = test::scene("junction");
  const Masses m{2.2, 1.0, 1.0};
  const double T = tensionOf(m), a = T / m.a - kG;
  EXPECT_NEAR(T, 20.55, 0.005);
  EXPECT_NEAR(a, -0.467, 0.0005);
  for (int f = 0; f < s.frameCount(); ++f) test::frame(s);
  const double t = s.frameCount() / s.frame_rate_hz;
  EXPECT_NEAR(s.world->body(test::body(s, "counterweight")).v.y(), a * t, 1e-9);
  EXPECT_NEAR(s.world->body(test::body(s, "load_left")).v.y(), -a * t, 1e-9);
  EXPECT_NEAR(s.world->body(test::body(s, "load_right")).v.y(), -a * t, 1e-9);
  EXPECT_NEAR(s.cables->tension(test::cable(s, "lift"), 1), T, 1e-9);
  EXPECT_NEAR(s.cables->tension(test::cable(s, "hoist_left"), 0), T / 2.0, 1e-9);
}

TEST(Junction, CreatesNoEnergyAtAnyBudget) {
  // The uneven loads: the ledger's balance (kinetic + potential) never
  // rises, at every budget and both projections. For 0.5 s: A reaches
  // the beam's pinhole at 0.61 s, where a plain cable's tie point jams
  // and a junction's branch does not yet (DESIGN.md, "Junctions").
  constexpr int kFramesBeforeAReachesTheBeam = 30;
  for (const test::Budget& budget : test::fourBudgetsBothProjections()) {
    Scene s = parseScene(junctionScene(budget, Masses{1.0, 1.0, 3.0}), "junction.json");
    s.world->settings().projection = budget.projection;
    EnergyWatch watch(s);
    for (int f = 0; f < kFramesBeforeAReachesTheBeam; ++f) {
      test::frame(s);
      const auto created = watch.check(s);
      ASSERT_FALSE(created) << test::name(budget) << ": " << energyCreatedMessage(*created);
    }
  }
}

}  // namespace
}  // namespace reeve::test_junction
