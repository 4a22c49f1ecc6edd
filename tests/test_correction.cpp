// The XPBD scalar-row kernel (SCA 2020 sec. 3.3) and compliance, checked
// against mechanics: momentum, a finite-difference check of the
// generalized inverse mass, and Hooke's law for a compliant distance.
#include <gtest/gtest.h>

#include <fenv.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "reeve/engine/correction.h"
#include "reeve/engine/world.h"

namespace reeve::test_correction {
namespace {

BodyState freeBox(double mass, const Vec3& half, const Vec3& x) {
  BodyDef def;
  def.shape = Shape::box(half);
  def.mass = mass;
  def.position = x;
  return makeBodyState(def);
}

TEST(Correction, RigidDistanceIsMetInOneStepAndConservesMomentum) {
  BodyState a = freeBox(1.0, Vec3(0.1, 0.1, 0.1), Vec3(0, 0, 0));
  BodyState b = freeBox(3.0, Vec3(0.1, 0.1, 0.1), Vec3(2, 0, 0));
  DistanceConstraint c;
  c.unilateral = false;
  c.rest_length = 1.0;
  solveDistanceConstraint(c, a, b, 0.0, 1.0 / 60.0);
  EXPECT_NEAR((b.x - a.x).norm(), 1.0, 1e-14);
  // Arms through the centres: no rotation, and m_a dx_a + m_b dx_b = 0.
  EXPECT_NEAR((1.0 * a.x + 3.0 * (b.x - Vec3(2, 0, 0))).norm(), 0.0, 1e-14);
  EXPECT_NEAR(a.x.x(), 0.75, 1e-14);  // the light body moves 3x as far
  EXPECT_NEAR(a.q.angularDistance(Quat::Identity()), 0.0, 1e-14);
}

TEST(Correction, GeneralizedInverseMassMatchesFiniteDifferenceOfTheConstraint) {
  // An off-centre arm on a tumbling box: dC = (w_a + w_b) dlambda to first
  // order, with C the separation of the two anchors along n.
  BodyDef def;
  def.shape = Shape::box(Vec3(0.3, 0.7, 0.2));
  def.mass = 2.5;
  def.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  BodyState a = makeBodyState(def);
  def.mass = 1.3;
  def.position = Vec3(1.0, 0.5, -0.2);
  BodyState b = makeBodyState(def);
  const Vec3 la(0.3, -0.4, 0.1), lb(-0.2, 0.6, 0.2);
  const Vec3 n = Vec3(0.2, 1.0, -0.4).normalized();
  const auto C = [&] { return (b.toWorld(lb) - a.toWorld(la)).dot(n); };
  const Vec3 r_a = a.q * la, r_b = b.q * lb;
  const double w = generalizedInverseMass(a, r_a, n) + generalizedInverseMass(b, r_b, n);
  const double dl = 1e-7, before = C();
  applyPositionalImpulse(a, b, r_a, r_b, dl * n);
  EXPECT_NEAR((C() - before) / dl, w, 1e-6 * w);
}

TEST(Correction, StaticBodiesDoNotMove) {
  BodyState wall;  // default state: static
  BodyState b = freeBox(1.0, Vec3(0.1, 0.1, 0.1), Vec3(0, -2, 0));
  DistanceConstraint c;
  c.rest_length = 1.0;
  solveDistanceConstraint(c, wall, b, 0.0, 1.0 / 60.0);
  EXPECT_EQ(wall.x, Vec3::Zero());
  EXPECT_NEAR(b.x.y(), -1.0, 1e-14);
}

// A mass m on a compliant bilateral distance of compliance alpha under
// gravity: Hooke's law gives the elongation alpha m g at rest.
struct HangingSpring {
  double mass = 2.0, compliance = 0.01, g = 10.0, rest = 1.0;
  World world;
  BodyId body;
  DistanceId spring;
  explicit HangingSpring(double start_stretch) {
    world.settings().gravity = Vec3(0, -g, 0);
    world.settings().substeps = 20;
    world.settings().iterations = 1;
    BodyDef anchor;
    anchor.is_static = true;
    const BodyId top = world.addBody(anchor);
    BodyDef def;
    def.shape = Shape::sphere(0.05);
    def.mass = mass;
    def.position = Vec3(0, -(rest + start_stretch), 0);
    body = world.addBody(def);
    DistanceConstraint c;
    c.a = top;
    c.b = body;
    c.rest_length = rest;
    c.compliance = compliance;
    c.unilateral = false;
    spring = world.addDistance(c);
  }
  double elongation() const { return -world.body(body).x.y() - rest; }
};

TEST(Compliance, StartedAtHookeEquilibriumAMassStaysThere) {
  HangingSpring s(0.01 * 2.0 * 10.0);
  for (int f = 0; f < 120; ++f) s.world.step(1.0 / 60.0);
  EXPECT_NEAR(s.elongation(), 0.2, 1e-6);
  EXPECT_NEAR(s.world.tension(s.spring), 20.0, 1e-4);
}

TEST(Compliance, ReleasedUnstretchedAMassOscillatesAboutHookeElongation) {
  // Period 2 pi sqrt(m alpha) = 0.8886 s; averaged over whole periods (9 of
  // them, 480 frames) the elongation is the static alpha m g = 0.2 m.
  HangingSpring s(0.0);
  const double period = 2.0 * 3.141592653589793 * std::sqrt(s.mass * s.compliance);
  const int frames = static_cast<int>(std::lround(9 * period * 60.0));
  double sum = 0.0;
  for (int f = 0; f < frames; ++f) {
    s.world.step(1.0 / 60.0);
    sum += s.elongation();
  }
  EXPECT_NEAR(sum / frames, 0.2, 0.002);
}

TEST(Integration, AFreeWheelKeepsItsSpin) {
  // No torque: angular momentum and energy are conserved. A first-order
  // quaternion update would lose about h omega^3 / 8 per second here.
  World world;
  BodyDef def;
  def.shape = Shape::cylinder(0.3, 0.05);
  def.mass = 2.0;
  def.angular_velocity = Vec3(0, 0, 40.0);
  const BodyId wheel = world.addBody(def);
  world.settings().gravity = Vec3::Zero();
  for (int f = 0; f < 600; ++f) world.step(1.0 / 60.0);
  EXPECT_NEAR(world.body(wheel).omega.z(), 40.0, 1e-9);
  // 10 s at 40 rad/s: the wheel has turned 400 rad.
  const double turned = 2.0 * std::atan2(world.body(wheel).q.z(), world.body(wheel).q.w());
  EXPECT_NEAR(std::remainder(turned - 400.0, 2.0 * 3.141592653589793), 0.0, 1e-9);
}

TEST(Integration, SpeedGuardCapsAFallingBodyAtTheLimit) {
  // Free fall reaches 5 m/s after 5 / g s; from then on the guard holds it.
  World world;
  world.settings().gravity = Vec3(0, -10.0, 0);
  world.settings().max_linear_speed = 5.0;
  BodyDef def;
  def.shape = Shape::sphere(0.1);
  def.mass = 1.0;
  def.angular_velocity = Vec3(0, 0, 100.0);
  world.settings().max_angular_speed = 30.0;
  const BodyId ball = world.addBody(def);
  for (int f = 0; f < 15; ++f) world.step(1.0 / 60.0);  // 0.25 s: still free
  EXPECT_NEAR(world.body(ball).v.y(), -2.5, 1e-9);
  for (int f = 0; f < 60; ++f) world.step(1.0 / 60.0);
  EXPECT_NEAR(world.body(ball).v.norm(), 5.0, 1e-9);
  EXPECT_NEAR(world.body(ball).omega.norm(), 30.0, 1e-9);
}

TEST(Integration, MassesAndInertiasBeyondWhatDoublePrecisionInvertsAreRefused) {
  // A 1e300 kg body once stepped to NaN orientations: energies and the
  // solver's mass products square it. The engine now refuses what the
  // scene loader refuses, with no JSON path to give.
  World world;
  BodyDef def;
  def.shape = Shape::sphere(0.1);
  for (const double mass : {1e300, 1e154, 1e101, 1e-101, 1e-300, std::numeric_limits<double>::infinity()}) {
    def.mass = mass;
    EXPECT_THROW(world.addBody(def), std::invalid_argument) << mass;
  }
  def.mass = 0.0;
  def.density = 1e95;  // x 4.2e-3 m^3: 4e92 kg, allowed; 0.4 m r^2 of it too
  EXPECT_NO_THROW(world.addBody(def));
  def.shape = Shape::box(Vec3(500, 500, 500));  // 1e9 m^3: 1e104 kg
  EXPECT_THROW(world.addBody(def), std::invalid_argument);
  def.density = 1000.0;
  def.shape = Shape::sphere(1e-40);  // 4e-117 kg
  EXPECT_THROW(world.addBody(def), std::invalid_argument);
  EXPECT_EQ(world.bodyCount(), 1);

  // At the bounds a body still moves as mechanics says: a spinning stone
  // of 1e100 kg and one of 1e-100 kg (radius 2 m: inertia 1.6e-100) fall
  // 1 s at g and keep their spin; a tumbling plate of 1e100 kg turns as
  // one of 1 kg does (the gyroscopic step divides by its inertia's
  // determinant, about 1e297 here).
  World bounds;
  def.density = 0.0;
  def.angular_velocity = Vec3(0.0, 0.0, 3.0);
  def.shape = Shape::sphere(0.1);
  def.mass = 1e100;
  const BodyId heavy = bounds.addBody(def);
  def.shape = Shape::sphere(2.0);
  def.mass = 1e-100;
  const BodyId light = bounds.addBody(def);
  def.shape = Shape::box(Vec3(1.0, 0.5, 0.05));
  def.angular_velocity = Vec3(0.3, 0.2, 4.0);  // about the major axis, off it a little
  def.mass = 1e100;
  const BodyId plate = bounds.addBody(def);
  def.mass = 1.0;
  const BodyId unit_plate = bounds.addBody(def);
  EXPECT_THROW(bounds.setMass(light, 1e-101), std::invalid_argument);
  EXPECT_THROW(bounds.setMass(heavy, 1e300), std::invalid_argument);
  for (int f = 0; f < 60; ++f) bounds.step(1.0 / 60.0);
  ASSERT_FALSE(bounds.firstNonFinite());
  for (const BodyId b : {heavy, light}) {
    EXPECT_NEAR(bounds.body(b).v.y(), -9.81, 1e-9);
    EXPECT_NEAR(bounds.body(b).omega.z(), 3.0, 1e-9);
    EXPECT_NEAR(bounds.body(b).q.norm(), 1.0, 1e-12);
  }
  const Vec3 w = bounds.body(plate).omega, w1 = bounds.body(unit_plate).omega;
  EXPECT_GT((w1 - Vec3(0.3, 0.2, 4.0)).norm(), 0.1) << "the plate does tumble";
  EXPECT_LT((w - w1).norm(), 1e-9 * w1.norm()) << w.transpose() << " vs " << w1.transpose();
}

TEST(Integration, NonFiniteStateIsReportedByBody) {
  // This test makes NaNs on purpose: lift the traps of fp_main.cpp for it.
  const int traps = fedisableexcept(FE_ALL_EXCEPT);
  World world;
  BodyDef def;
  def.shape = Shape::sphere(0.1);
  def.mass = 1.0;
  def.name = "calm";
  world.addBody(def);
  def.name = "wild";
  def.linear_velocity = Vec3(std::numeric_limits<double>::infinity(), 0, 0);
  const BodyId wild = world.addBody(def);
  EXPECT_FALSE(World().firstNonFiniteBody().has_value());
  world.step(1.0 / 60.0);
  ASSERT_TRUE(world.firstNonFiniteBody().has_value());
  EXPECT_EQ(*world.firstNonFiniteBody(), wild);
  ASSERT_TRUE(world.firstNonFinite().has_value());
  EXPECT_EQ(world.firstNonFinite()->body, wild);
  EXPECT_EQ(world.firstNonFinite()->quantity, NonFiniteState::Quantity::Position);
  feclearexcept(FE_ALL_EXCEPT);
  feenableexcept(traps);
}

TEST(Integration, TheGuardNamesTheBodyWhereNonFiniteWasBornNotTheFirstItReached) {
  // "calm" (index 0) hangs from "wild" (index 1) on a rod. wild overflows
  // its position in the first substep's integration; the rod then spreads
  // NaN to calm in the same substep, so that afterwards both are non-finite
  // and an index-order scan names calm. The guard names wild.
  const int traps = fedisableexcept(FE_ALL_EXCEPT);
  World world;
  world.settings().substeps = 4;
  BodyDef def;
  def.shape = Shape::sphere(0.1);
  def.mass = 1.0;
  def.name = "calm";
  const BodyId calm = world.addBody(def);
  def.name = "wild";
  def.position = Vec3(std::numeric_limits<double>::max(), 1.0, 0);
  def.linear_velocity = Vec3(std::numeric_limits<double>::max(), 0, 0);
  const BodyId wild = world.addBody(def);
  DistanceConstraint rod;
  rod.a = calm;
  rod.b = wild;
  rod.unilateral = false;
  world.addDistance(rod);
  world.step(1.0 / 60.0);
  ASSERT_EQ(world.firstNonFiniteBody(), calm) << "both are non-finite by the end of the frame";
  ASSERT_TRUE(world.firstNonFinite().has_value());
  EXPECT_EQ(world.firstNonFinite()->body, wild);
  EXPECT_EQ(world.firstNonFinite()->quantity, NonFiniteState::Quantity::Position);
  EXPECT_DOUBLE_EQ(world.firstNonFinite()->time_s, 1.0 / 240.0) << "the first substep";
  feclearexcept(FE_ALL_EXCEPT);
  feenableexcept(traps);
}

TEST(Integration, TheGuardNamesATensionThatOverflowsWhileTheBodiesStayFinite) {
  // Two 1e100 kg bodies (the most a body may have) 1 m apart on a rod of
  // rest length 0, one substep of 1e-105 s: the rod closes the gap (moves
  // of 0.5 m, speeds of 5e104 m/s, all finite), but its tension
  // m C / (2 h^2) = 5e309 N overflows.
  const int traps = fedisableexcept(FE_ALL_EXCEPT);
  World world;
  world.settings().gravity = Vec3::Zero();
  world.settings().substeps = 1;
  BodyDef def;
  def.shape = Shape::sphere(0.1);
  def.mass = 1e100;
  def.name = "left";
  const BodyId left = world.addBody(def);
  def.name = "right";
  def.position = Vec3(1.0, 0, 0);
  const BodyId right = world.addBody(def);
  DistanceConstraint rod;
  rod.a = left;
  rod.b = right;
  rod.unilateral = false;
  world.addDistance(rod);
  world.step(1e-105);
  EXPECT_FALSE(world.firstNonFiniteBody().has_value());
  ASSERT_TRUE(world.firstNonFinite().has_value());
  EXPECT_EQ(world.firstNonFinite()->quantity, NonFiniteState::Quantity::Tension);
  EXPECT_EQ(world.firstNonFinite()->body, left);
  EXPECT_EQ(world.firstNonFinite()->other, right);
  EXPECT_STREQ(quantityName(world.firstNonFinite()->quantity), "tension");
  feclearexcept(FE_ALL_EXCEPT);
  feenableexcept(traps);
}

}  // namespace
}  // namespace reeve::test_correction
