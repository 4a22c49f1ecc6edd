// Closed cables (belts) transmit rotation with the radius ratio: the
// paper's one-to-four gear (Fig. 16).
#include <gtest/gtest.h>

#include <cmath>

#include "reeve/cable/cable.h"
#include "scene_fixture.h"
#include "solver_budgets.h"

namespace reeve::test_gear {
namespace {

// Generalized coordinate: the small wheel's angle t (ccw). The large wheel
// turns k t with k = R_small / R_large (belt without slip); the small
// weight falls h t, the large one rises h k t (hubs of radius h). Lagrange:
// t'' = g h (m_s - k m_l) / (I_s + m_s h^2 + k^2 (I_l + m_l h^2)).
double smallWeightAcceleration(double m_small, double m_large) {
  const double g = 9.81, h = 0.25, k = 0.25 / 1.0;
  const double I_small = 0.5 * 1.0 * 0.25 * 0.25, I_large = 0.5 * 4.0 * 1.0 * 1.0;
  const double M = I_small + m_small * h * h + k * k * (I_large + m_large * h * h);
  return h * g * h * (m_small - k * m_large) / M;
}

TEST(Gear, OneToFourMassesBalanceThroughTheBelt) {
  Scene s = test::scene("gear_1_to_4");
  const BodyId small = test::body(s, "weight_small"), large = test::body(s, "weight_large");
  const Vec3 x_small = s.world->body(small).x, x_large = s.world->body(large).x;
  for (int f = 0; f < s.frameCount(); ++f) test::frame(s);  // 5 s
  EXPECT_LT((s.world->body(small).x - x_small).norm(), 1e-3);
  EXPECT_LT((s.world->body(large).x - x_large).norm(), 1e-3);
  // The belt carries the torque: tension difference m_s g h / R_small.
  const double diff = s.cables->tension(0, 0) - s.cables->tension(0, 1);
  EXPECT_NEAR(std::abs(diff), 1.0 * 9.81 * 0.25 / 0.25, 0.01 * 9.81);
}

TEST(Gear, OtherRatiosAccelerateAsDerived) {
  for (const double m_large : {2.0, 8.0}) {
    Scene s = test::scene("gear_1_to_4");
    const BodyId small = test::body(s, "weight_small"), large = test::body(s, "weight_large");
    s.world->setMass(large, m_large);
    for (int f = 0; f < 30; ++f) test::frame(s);
    const double a = smallWeightAcceleration(1.0, m_large);
    const double t = s.world->time();
    EXPECT_NEAR(-s.world->body(small).v.y() / t, a, 0.01 * std::abs(a)) << "m_large " << m_large;
    // The large weight moves k = 1/4 as fast, the other way.
    EXPECT_NEAR(s.world->body(large).v.y() / t, 0.25 * a, 0.01 * std::abs(a)) << "m_large " << m_large;
  }
}

TEST(Gear, AccelerateAsDerivedAtFourBudgetsUnderBothSolvers) {
  // Both belt spans run between two wheels on fixed axles: under
  // Gauss-Seidel each is visited with its line, moments and w taken once a
  // solve (span_ends.h, fixed_line), its length from the wheels' turns.
  // Lighter and heavier than the balance, so the belt turns both ways.
  for (const test::Budget& b : test::kFourBudgets) {
    for (const double m_large : {2.0, 8.0}) {
      Scene s = test::scene("gear_1_to_4", b.substeps, b.iterations);
      s.world->settings().solver = b.solver;
      const BodyId small = test::body(s, "weight_small"), large = test::body(s, "weight_large");
      s.world->setMass(large, m_large);
      const double total = s.cables->totalLength(0);
      for (int f = 0; f < 30; ++f) test::frame(s);
      const double a = smallWeightAcceleration(1.0, m_large), t = s.world->time();
      const std::string at = test::name(b) + ", m_large " + std::to_string(m_large);
      EXPECT_NEAR(-s.world->body(small).v.y() / t, a, 1e-3 * std::abs(a)) << at;
      EXPECT_NEAR(s.world->body(large).v.y() / t, 0.25 * a, 1e-3 * std::abs(a)) << at;
      const double w_small = s.world->body(test::body(s, "small")).omega.z();
      const double w_large = s.world->body(test::body(s, "large")).omega.z();
      EXPECT_NEAR(w_small, 4.0 * w_large, 1e-3 * std::abs(w_small)) << at;
      EXPECT_NEAR(s.cables->totalLength(0), total, 1e-9 * total) << at;
    }
  }
}

TEST(Gear, TheBeltTransmitsTheRadiusRatioWithoutSlipAndKeepsItsLength) {
  Scene s = test::scene("gear_1_to_4");
  s.world->setMass(test::body(s, "weight_large"), 2.0);
  const double total = s.cables->totalLength(0);
  for (int f = 0; f < 60; ++f) test::frame(s);
  EXPECT_NEAR(s.cables->totalLength(0), total, 1e-9 * total);
  // No slip: the wheels turn in the inverse ratio of their radii, 4:1.
  const double w_small = s.world->body(test::body(s, "small")).omega.z();
  const double w_large = s.world->body(test::body(s, "large")).omega.z();
  EXPECT_NEAR(w_small, 4.0 * w_large, 1e-3 * std::abs(w_small));
  for (int j = 0; j < 2; ++j)  // taut and inextensible to 1e-4 relative
    EXPECT_NEAR(s.cables->length(0, j), s.cables->restLength(0, j), 1e-4 * s.cables->restLength(0, j));
}

}  // namespace
}  // namespace reeve::test_gear

namespace reeve::test_gear {
namespace {

TEST(MotorBelt, ATorqueLimitedMotorSpinsUpTheBeltDrivenWheelsAsDerived) {
  // Belt without slip: w_b = w_a r_a / r_b, w_c = w_a r_a / r_c. The motor
  // (2 N m) sees I = I_a + I_b (r_a/r_b)^2 + I_c (r_a/r_c)^2 = 0.07 kg m^2
  // and spins up at 2 / 0.07 rad/s^2 until 10 rad/s at 0.35 s.
  Scene s = test::scene("motor_belt");
  const BodyId a = test::body(s, "motor_wheel"), b = test::body(s, "big_wheel"), c = test::body(s, "small_wheel");
  const double alpha = 2.0 / 0.07;
  for (int f = 0; f < 12; ++f) test::frame(s);  // 0.2 s
  const double w = s.world->body(a).omega.z();
  EXPECT_NEAR(w, alpha * s.world->time(), 0.01 * alpha * s.world->time());
  EXPECT_NEAR(s.world->body(b).omega.z(), w * 0.2 / 0.4, 0.01 * w);
  EXPECT_NEAR(s.world->body(c).omega.z(), w * 0.2 / 0.1, 0.01 * w * 2.0);
  for (int f = 12; f < 60; ++f) test::frame(s);  // 1 s: at speed
  EXPECT_NEAR(s.world->body(a).omega.z(), 10.0, 0.05);
  EXPECT_NEAR(s.world->body(b).omega.z(), 5.0, 0.025);
  EXPECT_NEAR(s.world->body(c).omega.z(), 20.0, 0.1);
}

}  // namespace
}  // namespace reeve::test_gear
