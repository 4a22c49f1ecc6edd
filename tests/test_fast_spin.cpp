// Fast spins: a wheel turning many times per substep keeps its speed (the
// velocity read-out is not wrapped to half a turn), and a thin body spun
// off its axes does not gain energy from the gyroscopic update.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "reeve/engine/world.h"

namespace reeve::test_fast_spin {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(FastSpin, FreeWheelKeepsManyTurnsPerSubstep) {
  // 25.3 turns per substep of 1/600 s, about its axis (no gyroscopic
  // torque): the speed read back after the substep is the speed it had.
  World world(SolverSettings{Vec3::Zero(), 10, 2});
  BodyDef def;
  def.shape = Shape::cylinder(0.001, 0.05);
  def.mass = 1.0;
  const double w = 25.3 * 2.0 * kPi * 600.0;
  def.angular_velocity = Vec3(0.0, 0.0, w);
  const BodyId id = world.addBody(def);
  world.step(1.0 / 60.0);
  EXPECT_NEAR(world.body(id).omega.z(), w, 1e-9 * w);
  EXPECT_NEAR(world.body(id).omega.head<2>().norm(), 0.0, 1e-9 * w);
}

TEST(FastSpin, ThinRodSpunOffItsAxesNeverGainsEnergy) {
  // A 1 m rod of radius 5 mm (I about its axis 1/6700 of the others)
  // spun at h |w| = 1.7 about a tilted axis: kinetic energy is conserved
  // by the motion, and an implicit gyroscopic step can only lose some.
  World world(SolverSettings{Vec3::Zero(), 1, 1});
  BodyDef def;
  def.shape = Shape::cylinder(0.005, 0.5);
  def.mass = 1.0;
  def.angular_velocity = Vec3(30.0, 0.0, 100.0);
  const BodyId id = world.addBody(def);
  const auto energy = [&] {
    const BodyState& b = world.body(id);
    const Vec3 w = b.q.conjugate() * b.omega;
    return 0.5 * w.dot(b.inertia * w);
  };
  const double e0 = energy();
  for (int f = 0; f < 600; ++f) {
    world.step(1.0 / 60.0);
    ASSERT_LE(energy(), e0 * (1.0 + 1e-12)) << "frame " << f;
  }
  EXPECT_GT(energy(), 0.0);
}

}  // namespace
}  // namespace reeve::test_fast_spin

namespace reeve::test_fast_spin {
namespace {

TEST(FastSpin, FlatBoxesSpunNearTheirMiddleAxisNeverGainEnergyOrMomentum) {
  // Three different moments: one Newton step of implicit Euler can blow up
  // near a spin about the middle axis at h |w| near 1 (its Jacobian goes
  // singular; one such plate gained 1e5 times its energy in a step). Over
  // many spins of flat boxes at h |w| from 0.2 to 4.5 per substep, the
  // kinetic energy and |L| (both conserved by the free motion) never grow.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const double h = 1.0 / 60.0;
  for (int run = 0; run < 100; ++run) {
    World world(SolverSettings{Vec3::Zero(), 1, 1});
    BodyDef def;
    def.shape = Shape::box(Vec3(1.0, 0.3 + 0.5 * std::abs(uniform(rng)), 0.02 + 0.1 * std::abs(uniform(rng))));
    def.mass = 1.0;
    def.angular_velocity = Vec3(uniform(rng), uniform(rng), uniform(rng)).normalized() *
                           (std::exp(1.5 * uniform(rng)) / h);
    const BodyId id = world.addBody(def);
    const auto energy = [&] {
      const BodyState& b = world.body(id);
      const Vec3 w = b.q.conjugate() * b.omega;
      return 0.5 * w.dot(b.inertia * w);
    };
    const auto momentum = [&] {
      const BodyState& b = world.body(id);
      return (b.inertia * (b.q.conjugate() * b.omega)).norm();
    };
    const double e0 = energy(), l0 = momentum();
    for (int f = 0; f < 120; ++f) {
      world.step(h);
      ASSERT_LE(energy(), e0 * (1.0 + 1e-9)) << "run " << run << ", frame " << f;
      ASSERT_LE(momentum(), l0 * (1.0 + 1e-9)) << "run " << run << ", frame " << f;
    }
  }
}

TEST(FastSpin, RotateExactlyIsTheExponentialMapAtEveryAngle) {
  // Small angles take a series, large ones sin and cos: both must give
  // the rotation by |phi| about phi (to rounding), on either side of 0.1.
  for (const double angle : {1e-12, 1e-6, 0.01, 0.0999999, 0.1, 0.2, 1.0, 3.0, 3.0 * kPi}) {
    const Vec3 axis = Vec3(0.3, -0.5, 0.8).normalized();
    const Quat start(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, -1.0).normalized()));
    Quat q = start;
    rotateExactly(q, angle * axis);
    const Quat expected = (Quat(Eigen::AngleAxisd(angle, axis)) * start).normalized();
    EXPECT_LT(q.angularDistance(expected), 1e-14) << angle;
  }
}

}  // namespace
}  // namespace reeve::test_fast_spin
