// The energy ledger (issue 28): each channel against a closed form of the
// integrator it measures (symplectic Euler: positions from the substep's
// end velocity), at wheel/load masses from 1e-3 to 1e3 kg, both solvers and
// budgets from 1 x 1 to 32 x 32; and the watch that tells energy created.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "reeve/cable/cable.h"
#include "reeve/scene/energy.h"
#include "solver_budgets.h"

namespace reeve::test_energy {
namespace {

constexpr double kG = 9.81;

using test::Budget;
using test::kFourBudgets;
using test::name;

World worldWith(const Budget& b, const Vec3& gravity) {
  SolverSettings s;
  s.gravity = gravity;
  s.solver = b.solver;
  s.substeps = b.substeps;
  s.iterations = b.iterations;
  return World(s);
}

void run(World& world, int frames) {
  for (int f = 0; f < frames; ++f) world.step(1.0 / 60.0);
}

double total(const WorldEnergy& e) { return e.kinetic + e.gravity + e.elastic; }

TEST(EnergyLedger, AFallingBodyLosesExactlyWhatSymplecticEulerLoses) {
  // v += g h, x += v h: each substep trades m g . dx of potential for
  // kinetic energy and loses m g^2 h^2 / 2, so after time T the balance is
  // down by m g^2 h T / 2 (0.41 mJ per kg at 10 x 2 over 1 s).
  for (const Budget& b : kFourBudgets)
    for (const double mass : {1e-3, 1.0, 1e3}) {
      SCOPED_TRACE(name(b) + ", " + std::to_string(mass) + " kg");
      World world = worldWith(b, Vec3(0.0, -kG, 0.0));
      BodyDef def;
      def.shape = Shape::box(Vec3::Constant(0.1));
      def.mass = mass;
      def.linear_velocity = Vec3(1.0, 2.0, 0.0);
      world.addBody(def);
      const double start = total(world.energy());
      run(world, 60);
      const double h = 1.0 / (60.0 * b.substeps);
      const double lost = 0.5 * mass * kG * kG * h * 1.0;
      EXPECT_NEAR(total(world.energy()) - start, -lost, 1e-9 * mass * kG * kG);
    }
}

TEST(EnergyLedger, UnderTheStartProjectionAFallingBodyKeepsItsEnergyExactly) {
  // The start projection's ledger pairs the half step's velocity v with
  // the height half a step back, x - v h / 2. Free, v += g h and x += v h,
  // so E = m |v|^2 / 2 - m g . (x - v h / 2) changes in a substep by
  // m g . (v_n + v_n+1) h / 2 - m g . (v_n+1 + v_n) h / 2 = 0. Only the
  // first substep, read from the full x of the body as placed (h = 0
  // before any step), adds m g . v_0 h / 2 once.
  for (const Budget& b : kFourBudgets)
    for (const double mass : {1e-3, 1.0, 1e3}) {
      if (b.solver != SolverKind::Direct) continue;  // the start projection is the direct solver's
      SCOPED_TRACE(name(b) + ", " + std::to_string(mass) + " kg");
      World world = worldWith(b, Vec3(0.0, -kG, 0.0));
      world.settings().projection = Projection::Start;
      BodyDef def;
      def.shape = Shape::box(Vec3::Constant(0.1));
      def.mass = mass;
      def.linear_velocity = Vec3(1.0, -2.0, 0.0);
      world.addBody(def);
      const double start = total(world.energy());
      const double h = 1.0 / (60.0 * b.substeps);
      const double once = 0.5 * mass * kG * 2.0 * h;  // m g . v_0 h / 2, g . v_0 = 2 kG
      run(world, 1);
      const double first = total(world.energy());
      EXPECT_NEAR(first - start, once, 1e-12 * mass * kG);
      const double y = world.body(0).x.y();
      run(world, 60);
      // To the rounding of the velocities read from positions over a
      // substep (measured 6e-12 of the m g dy traded, 69 J per kg); the
      // end pairing's m g^2 h T / 2 would be 6e-4 of it at 32 x 32.
      const double traded = mass * kG * (y - world.body(0).x.y());
      EXPECT_NEAR(total(world.energy()), first, 1e-10 * traded);
    }
}

TEST(EnergyLedger, AMotorPutsInWhatTheWheelHoldsPlusTheImplicitStepsLoss) {
  // A 0.5 N m velocity drive spins a wheel (I = 0.09 kg m^2, or 1e3 times
  // lighter or heavier) up from rest: w_k = k tau h / I after k substeps, so
  // the work sum tau w_k h = I w_n^2 (1 + 1/n) / 2 while the wheel holds
  // I w_n^2 / 2. Then, turned round, the drive brakes it to rest in as many
  // substeps: its work is -I w_n^2 (1 - 1/n) / 2, so 2 / n of the spin is
  // what the two implicit halves lost.
  for (const Budget& b : kFourBudgets)
    for (const double scale : {1e-3, 1.0, 1e3}) {
      SCOPED_TRACE(name(b) + ", wheel x " + std::to_string(scale));
      World world = worldWith(b, Vec3(0.0, -kG, 0.0));
      BodyDef def;
      def.shape = Shape::cylinder(0.3, 0.05);
      def.mass = 2.0 * scale;
      const BodyId wheel = world.addBody(def);
      const double inertia = 0.5 * def.mass * 0.09;
      const double tau = 0.5 * scale;
      HingeDef hinge(wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ());
      hinge.drive.mode = HingeDrive::Mode::Velocity;
      hinge.drive.target = 100.0;  // not reached in 0.5 s: 0.5 / 0.09 x 0.5 = 2.8 rad/s
      hinge.drive.max_torque = tau;
      const HingeId id = world.addHinge(hinge);
      run(world, 30);
      const int n = 30 * b.substeps;
      const double w = n * tau * (1.0 / (60.0 * b.substeps)) / inertia;
      // Gauss-Seidel keeps the wheel on its axle by rows that the drive's
      // row shares the sweep with: 1e-6 of the spin.
      const double tolerance = b.solver == SolverKind::Direct ? 1e-9 : 1e-6;
      ASSERT_NEAR(world.body(wheel).omega.z(), w, tolerance * w);
      const WorldEnergy up = world.energy();
      const double spin = 0.5 * inertia * w * w;
      EXPECT_NEAR(up.kinetic, spin, tolerance * spin);
      EXPECT_NEAR(up.drive_work, spin * (1.0 + 1.0 / n), tolerance * spin);
      world.hinge(id).drive.target = 0.0;  // brake
      run(world, 60);
      const WorldEnergy down = world.energy();
      EXPECT_NEAR(world.body(wheel).omega.z(), 0.0, tolerance * w);
      EXPECT_NEAR(down.drive_work, spin * 2.0 / n, tolerance * spin);
    }
}

TEST(EnergyLedger, AnAppliedForcePutsInMv2Over2PlusTheImplicitStepsLoss) {
  for (const Budget& b : kFourBudgets) {
    SCOPED_TRACE(name(b));
    World world = worldWith(b, Vec3::Zero());
    BodyDef def;
    def.shape = Shape::sphere(0.1);
    def.mass = 3.0;
    const BodyId id = world.addBody(def);
    world.body(id).applied_force = Vec3(6.0, 0.0, 0.0);
    run(world, 60);
    const int n = 60 * b.substeps;
    const double v = 2.0;  // F t / m
    const WorldEnergy e = world.energy();
    EXPECT_NEAR(e.kinetic, 0.5 * 3.0 * v * v, 1e-9);
    EXPECT_NEAR(e.load_work, 0.5 * 3.0 * v * v * (1.0 + 1.0 / n), 1e-9);
  }
}

TEST(EnergyLedger, DampingTakesOutExactlyWhatTheSpinLoses) {
  // A box spinning about a principal axis in zero gravity with angular
  // damping c: w = w0 exp(-c t), and the ledger's damping is all of it.
  for (const Budget& b : kFourBudgets) {
    SCOPED_TRACE(name(b));
    World world = worldWith(b, Vec3::Zero());
    BodyDef def;
    def.shape = Shape::box(Vec3(0.3, 0.2, 0.1));
    def.mass = 5.0;
    def.angular_velocity = Vec3(0.0, 0.0, 4.0);
    def.angular_damping = 0.7;
    const BodyId id = world.addBody(def);
    const double start = world.energy().kinetic;
    run(world, 120);
    const WorldEnergy e = world.energy();
    EXPECT_NEAR(world.body(id).omega.z(), 4.0 * std::exp(-0.7 * 2.0), 1e-12);
    EXPECT_NEAR(e.damping_loss, start - e.kinetic, 1e-12 * start);
  }
}

// A load of `mass` kg hanging 3 m below a winch drum fixed at the origin,
// on an inextensible cable, or one of `compliance` (m/N).
struct WinchRig {
  World world;
  CableSystem cables{world};
  BodyId load = 0;
  int cable = 0;
  WinchRig(const Budget& b, double mass, double compliance = 0.0) : world(worldWith(b, Vec3(0.0, -kG, 0.0))) {
    BodyDef frame;
    frame.is_static = true;
    frame.shape = Shape::box(Vec3::Constant(0.1));
    const BodyId top = world.addBody(frame);
    BodyDef def;
    def.shape = Shape::box(Vec3::Constant(0.1));
    def.mass = mass;
    def.position = Vec3(0.0, -3.0, 0.0);
    def.linear_damping = compliance > 0.0 ? 5.0 : 0.0;  // settles an elastic cable
    load = world.addBody(def);
    CableDef c;
    c.compliance = compliance;
    c.links = {LinkDef::attachment(load, Vec3::Zero()), LinkDef::attachment(top, Vec3::Zero())};
    cable = cables.addCable(c);
  }
};

TEST(EnergyLedger, AWinchPutsInTheLiftAndTakesItBackLosingOnlyItsFourJerks) {
  // 5 kg or 500 kg hauled at 0.2 m/s for 1 s, held, paid out at 0.2 m/s for
  // 1 s and held again: back where it started, at rest. A rigid cable
  // changes the load's speed by 0.2 m/s within one substep four times, each
  // an inelastic jerk of m (0.2)^2 / 2 that the implicit step loses, so the
  // winch's net work is 0.08 m J, never less (less would be energy made).
  // Under the start projection (direct solver) the motion is the same (a
  // straight cable's gradient does not turn), and the ledger reads the
  // load's height half a substep back: m g 0.2 h / 2 lower while it rises.
  for (const Budget& b : kFourBudgets)
    for (const double mass : {5.0, 500.0})
      for (const Projection projection : {Projection::End, Projection::Start}) {
        if (projection == Projection::Start && b.solver != SolverKind::Direct) continue;
        SCOPED_TRACE(name(b) + ", " + std::to_string(mass) + " kg" + (projection == Projection::Start ? ", start" : ""));
        WinchRig rig(b, mass);
        rig.world.settings().projection = projection;
        const double h = 1.0 / (60.0 * b.substeps);
        const double lag = projection == Projection::Start ? mass * kG * 0.2 * h / 2.0 : 0.0;
        const double start = total(rig.world.energy());
        WinchDef w;
        for (const double speed : {0.2, 0.0, -0.2, 0.0}) {
          w.speed = speed;
          rig.cables.setWinch(rig.cable, w);
          run(rig.world, 60);
          const double work = rig.cables.winchWork(), gained = total(rig.world.energy()) - start;
          EXPECT_GE(work, gained - 1e-9 * mass) << "at " << rig.world.time() << " s";
          if (speed > 0.0) {
            EXPECT_NEAR(gained, mass * (kG * 0.2 + 0.5 * 0.2 * 0.2) - lag, 1e-9 * mass);
          }
        }
        EXPECT_NEAR(rig.world.body(rig.load).x.y(), -3.0, 1e-9);
        EXPECT_NEAR(rig.cables.winchWork(), 4.0 * 0.5 * mass * 0.2 * 0.2, 1e-6 * mass);
      }
}

TEST(EnergyLedger, AnElasticCableHoldsHalfItsComplianceTimesTheTensionSquared) {
  // 2 kg at rest on a cable of 1e-3 m/N: stretch alpha m g, elastic energy
  // alpha (m g)^2 / 2 = 0.192 J.
  for (const Budget& b : kFourBudgets) {
    SCOPED_TRACE(name(b));
    WinchRig rig(b, 2.0, 3e-3);  // 3 m long: 1e-3 m/N per metre x 3 m
    run(rig.world, 600);
    const double weight = 2.0 * kG;
    EXPECT_NEAR(rig.cables.tension(rig.cable, 0), weight, 1e-6 * weight);
    EXPECT_NEAR(rig.world.energy().elastic, 0.5 * 3e-3 * weight * weight, 1e-6);
  }
}

TEST(EnergyWatch, AKickNothingPutInIsEnergyCreatedAndTheScaleSetsTheTolerance) {
  const std::string pendulum = R"({
    "name": "pendulum", "duration_s": 5,
    "solver": {"frame_rate_hz": 60, "substeps": 10, "iterations": 2},
    "bodies": [{"name": "pin", "shape": {"type": "sphere", "radius_m": 0.01}, "static": true,
                "position_m": [0, 0, 0]},
               {"name": "bob", "shape": {"type": "sphere", "radius_m": 0.05}, "mass_kg": 1.0,
                "position_m": [1, 0, 0]}],
    "cables": [{"name": "rope", "links": [
      {"body": "pin", "type": "attachment", "point_m": [0, 0, 0]},
      {"body": "bob", "type": "attachment", "point_m": [0, 0, 0]}]}]})";
  Scene scene = parseScene(pendulum, "<pendulum>");
  EnergyWatch watch(scene);
  for (int f = 0; f < 300; ++f) {
    scene.world->step(1.0 / 60.0);
    ASSERT_FALSE(watch.check(scene)) << "frame " << f;  // a swinging pendulum creates nothing
  }
  EXPECT_LE(watch.residual_J(), 0.0);
  // A push by hand, which no actuator made: 1 kg given 3 m/s more.
  scene.world->body(1).v += Vec3(0.0, 0.0, 3.0);
  const double kick = 0.5 * (scene.world->body(1).v.squaredNorm() - (scene.world->body(1).v - Vec3(0, 0, 3)).squaredNorm());
  scene.world->step(1.0 / 60.0);
  const auto created = watch.check(scene);
  ASSERT_TRUE(created);
  EXPECT_NEAR(created->created_J, kick, 0.05 * kick);
  EXPECT_TRUE(created->over_frame);
  EXPECT_NE(energyCreatedMessage(*created).find("energy created at t = 5.01667 s"), std::string::npos)
      << energyCreatedMessage(*created);
}

TEST(EnergyWatch, AWinchHaulingOverAFrictionDrumCreatesNothingAndItsFrictionIsCountedInTime) {
  // 10 kg hauled at 0.2 m/s over a static drum wrapped half a turn with
  // mu 0.2, then paid out: the winch pulls m g exp(mu pi) = 183.9 N hauling
  // (friction taking (exp(mu pi) - 1) m g = 85.8 N x the rope's travel) and
  // m g exp(-mu pi) = 52.3 N paying out. Friction's work was booked at the
  // update after the solve that did it: at one substep a frame, a frame
  // late, and the balance rose by it (+2.3 J at the haul's start, 1 % of
  // the scale), which the watch took for energy made.
  const std::string capstan = R"({
    "name": "capstan", "duration_s": 2,
    "solver": {"frame_rate_hz": 60, "substeps": 1, "iterations": 1},
    "bodies": [
      {"name": "drum", "static": true, "shape": {"type": "cylinder", "radius_m": 0.1, "half_length_m": 0.05},
       "position_m": [0, 0, 0]},
      {"name": "anchor", "static": true, "shape": {"type": "sphere", "radius_m": 0.02}, "position_m": [0.1, -2, 0]},
      {"name": "load", "shape": {"type": "box", "half_extents_m": [0.05, 0.05, 0.05]}, "mass_kg": 10,
       "position_m": [-0.1, -2, 0]}],
    "cables": [{"name": "rope", "links": [
      {"body": "load", "type": "attachment", "point_m": [0, 0, 0]},
      {"body": "drum", "type": "rolling", "orientation": "cw", "mu": 0.2},
      {"body": "anchor", "type": "attachment", "point_m": [0, 0, 0]}],
      "winch": {"end": "last", "max_speed_m_per_s": 1,
                "commands": [{"from_s": 0, "speed_m_per_s": 0.2}, {"from_s": 1, "speed_m_per_s": -0.2}]}}]})";
  const double weight = 10.0 * kG, k = std::exp(0.2 * std::acos(-1.0));
  for (const Budget& b : kFourBudgets) {
    SCOPED_TRACE(name(b));
    Scene scene = parseScene(capstan, "<capstan>");
    scene.world->settings().solver = b.solver;
    scene.world->settings().substeps = b.substeps;
    scene.world->settings().iterations = b.iterations;
    EnergyWatch watch(scene);
    double friction_at_half = 0.0;
    for (int f = 0; f < 120; ++f) {
      scene.world->step(1.0 / 60.0);
      const auto created = watch.check(scene);
      ASSERT_FALSE(created) << energyCreatedMessage(*created);
      if (f == 29) friction_at_half = scene.cables->frictionLoss();
      if (f == 59) {  // hauled steadily from 0.5 s to 1 s: 0.1 m against (k - 1) m g
        EXPECT_NEAR(scene.cables->frictionLoss() - friction_at_half, (k - 1.0) * weight * 0.1, 1e-6 * weight);
        EXPECT_NEAR(scene.cables->winchPull(0), k * weight, 1e-6 * weight);
      }
    }
    EXPECT_NEAR(scene.cables->winchPull(0), weight / k, 1e-6 * weight);
  }
}

}  // namespace
}  // namespace reeve::test_energy
