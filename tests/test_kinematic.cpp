// Kinematic bodies (issue 28): moved along a prescribed motion whatever
// pushes on them, infinite mass to the solver, their velocity seen by
// cables, joints and contacts, their work counted by the energy ledger.
// Closed forms at the energy ledger's four budgets, both solvers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "reeve/cable/cable.h"
#include "reeve/engine/world.h"

#include "solver_budgets.h"

namespace reeve::test_kinematic {
namespace {

constexpr double kG = 9.81;

World worldWith(const test::Budget& b) {
  SolverSettings s;
  s.solver = b.solver;
  s.substeps = b.substeps;
  s.iterations = b.iterations;
  s.projection = b.projection;
  s.gravity = Vec3(0.0, -kG, 0.0);
  return World(s);
}

void run(World& world, int frames) {
  for (int f = 0; f < frames; ++f) world.step(1.0 / 60.0);
}

BodyId addLoad(World& world, double mass, const Vec3& at) {
  BodyDef def;
  def.shape = Shape::box(Vec3::Constant(0.05));
  def.mass = mass;
  def.position = at;
  return world.addBody(def);
}

// The ledger's balance: total - work + losses (scenes' EnergyLedger, here
// from the World alone: no winch, no friction).
double balance(const WorldEnergy& e) {
  return e.kinetic + e.gravity + e.elastic - e.drive_work - e.load_work - e.kinematic_work + e.damping_loss +
         e.contact_loss;
}

TEST(Kinematic, ADrumSweptAtConstantSpeedPaysOutROmega) {
  // A kinematic drum of radius r = 0.2 m turned at omega = -2 or +2 rad/s
  // about z, a rope wound on it (5 m stored) down to m kg: the drum pays out
  // (or hauls in) r |omega| = 0.4 m/s whatever the load, the rope holds
  // m g, the stored cable changes by r omega t, and the drum's work is
  // m g times the load's rise. Both directions, loads 1e-3 to 1e3 kg.
  constexpr double r = 0.2;
  for (const test::Budget& b : test::fourBudgetsBothProjections())
    for (const double omega : {-2.0, 2.0})
      for (const double m : {1e-3, 1.0, 1e3}) {
        SCOPED_TRACE(test::name(b) + ", omega " + std::to_string(omega) + ", load " + std::to_string(m) + " kg");
        World world = worldWith(b);
        CableSystem cables(world);
        BodyDef drum;
        drum.shape = Shape::cylinder(r, 0.05);
        drum.motion = {{0.0, Vec3::Zero(), Vec3(0.0, 0.0, omega)}};
        const BodyId d = world.addBody(drum);
        const BodyId load = addLoad(world, m, Vec3(r, -3.0, 0.0));
        LinkDef spool = LinkDef::rolling(d, -1);
        spool.stored = 5.0;
        CableDef rope;
        rope.links = {spool, LinkDef::attachment(load, Vec3(0.0, 0.05, 0.0))};
        cables.addCable(rope);
        const double start = balance(world.energy());
        run(world, 60);
        const double t = 1.0, speed = r * omega;  // > 0: hauling, the load rises
        EXPECT_NEAR(world.body(d).omega.z(), omega, 1e-15);
        EXPECT_NEAR(cables.cables()[0].links[0].stored, 5.0 + speed * t, 1e-9);
        EXPECT_NEAR(world.body(load).x.y(), -3.0 + speed * t, 1e-9);
        EXPECT_NEAR(world.body(load).v.y(), speed, 1e-9);
        EXPECT_NEAR(cables.tension(0, 0), m * kG, 1e-6 * m * kG);
        const WorldEnergy e = world.energy();
        // The drum's work is the load's rise times its weight, and the
        // start's m v^2 either way: hauling, the jerk to v in the first
        // substep (half of it lost); paying out, the load falls free for
        // 2 v / g while the drum pays out 2 v^2 / g unloaded (m g of it not
        // braked: +2 m v^2), until the rope catches it at 2 v and brakes it
        // to v (-m v^2).
        const double rise = m * kG * speed * t;
        EXPECT_NEAR(e.kinematic_work, rise + m * speed * speed, 1e-6 * std::abs(rise));
        EXPECT_LE(balance(e) - start, 1e-9 * std::abs(rise));  // nothing made
      }
}

TEST(Kinematic, ABoxPutOnABeltSlipsUntilItRidesAndFrictionTakesHalfTheBeltsWork) {
  // A kinematic belt running at v = 1 m/s under a 1 kg box put on it at
  // rest (mu_d 0.3): friction mu_d m g drives the box up to v in v / (mu_d
  // g), while the belt slips v^2 / (2 mu_d g) = 0.170 m under it; the belt
  // does m v^2 of work, half of it the box's kinetic energy and half lost
  // to friction, whatever mu_d. Measured: the slip 0.1706 m at 10 x 2 and
  // 0.1760 at one substep a frame; the work 1.0000 J; lost 0.4963 and
  // 0.4989 J from ten substeps a frame, 0.4634 J at one. At one substep a
  // frame the ledger's balance also rises 1.3 mJ in the first frame (the
  // box pushed out of the belt 0.13 mm higher than it sat, while the
  // friction at its base turns it 0.74 rad/s each substep, which the next
  // normal rows take back): not checked there (DESIGN, "Thirty-fifth
  // session").
  constexpr double v = 1.0, m = 1.0, mu_d = 0.3;
  for (const test::Budget& b : test::fourBudgetsBothProjections()) {
    SCOPED_TRACE(test::name(b));
    World world = worldWith(b);
    ContactMaterial rubber;
    rubber.static_friction = 0.5;
    rubber.dynamic_friction = mu_d;
    rubber.restitution = 0.0;
    BodyDef belt;
    belt.shape = Shape::box(Vec3(20.0, 0.1, 1.0));
    belt.position = Vec3(0.0, -0.1, 0.0);
    belt.material = rubber;
    belt.collides = true;
    belt.motion = {{0.0, Vec3(v, 0.0, 0.0), Vec3::Zero()}};
    const BodyId belt_id = world.addBody(belt);
    BodyDef box;
    box.shape = Shape::box(Vec3::Constant(0.1));
    box.mass = m;
    box.position = Vec3(0.0, 0.1, 0.0);
    box.material = rubber;
    box.collides = true;
    const BodyId box_id = world.addBody(box);
    const double start = balance(world.energy());
    double most = 0.0;  // the balance's largest rise
    for (int f = 0; f < 120; ++f) {
      world.step(1.0 / 60.0);
      most = std::max(most, balance(world.energy()) - start);
    }
    const double h = 1.0 / (60.0 * b.substeps);
    const double slip = world.body(belt_id).x.x() - world.body(box_id).x.x();  // both started at x = 0
    EXPECT_NEAR(world.body(box_id).v.x(), v, 1e-9);
    EXPECT_NEAR(slip, v * v / (2.0 * mu_d * kG), v * h);  // to the belt's travel in a substep
    const WorldEnergy e = world.energy();
    EXPECT_NEAR(e.kinetic, 0.5 * m * v * v, 1e-9);
    EXPECT_NEAR(e.kinematic_work, m * v * v, 1e-3 * m * v * v);
    EXPECT_NEAR(e.contact_loss, 0.5 * m * v * v, (b.substeps == 1 ? 0.08 : 0.01) * 0.5 * m * v * v);
    if (b.substeps > 1) {
      EXPECT_LE(most, 1e-9);  // nothing made
    }
  }
}

TEST(Kinematic, AHandLiftsALoadAndTurnedRoundLowersIt) {
  // A kinematic hand (no mass) rising at 1 m/s for 1 s, holding, then
  // lowering at 1 m/s, with a 2 kg load on a rigid rope: the load follows
  // it exactly, the rope holds m g but for the jerks, and the hand's work
  // nets to the kinetic energy the jerks took out, never more.
  for (const test::Budget& b : test::kFourBudgets) {
    SCOPED_TRACE(test::name(b));
    World world = worldWith(b);
    CableSystem cables(world);
    BodyDef hand;
    hand.shape = Shape::box(Vec3::Constant(0.1));
    hand.motion = {{0.0, Vec3(0.0, 1.0, 0.0), Vec3::Zero()},
                   {1.0, Vec3(0.0, 1.0, 0.0), Vec3::Zero()},
                   {1.0 + 1e-9, Vec3::Zero(), Vec3::Zero()},
                   {2.0, Vec3::Zero(), Vec3::Zero()},
                   {2.0 + 1e-9, Vec3(0.0, -1.0, 0.0), Vec3::Zero()}};
    const BodyId h = world.addBody(hand);
    const BodyId load = addLoad(world, 2.0, Vec3(0.0, -2.0, 0.0));
    CableDef rope;
    rope.links = {LinkDef::attachment(h, Vec3::Zero()), LinkDef::attachment(load, Vec3(0.0, 0.05, 0.0))};
    cables.addCable(rope);
    const WorldEnergy start = world.energy();
    run(world, 30);
    EXPECT_NEAR(world.body(h).x.y(), 0.5, 1e-12);
    EXPECT_NEAR(world.body(load).x.y(), -1.5, 1e-9);
    EXPECT_NEAR(cables.tension(0, 0), 2.0 * kG, 1e-6);
    run(world, 150);  // 3 s: up 1 m, held, down 1 m
    EXPECT_NEAR(world.body(h).x.y(), 0.0, 1e-9);
    const WorldEnergy e = world.energy();
    EXPECT_NEAR(world.body(load).x.y(), -2.0, 1e-9);  // back where it started, the rope taut
    EXPECT_NEAR(world.body(load).v.y(), -1.0, 1e-9);
    // The hand put in at least the kinetic energy the load has now (the
    // rest went in the jerks and the snatch when it stopped), and the
    // balance never rose.
    EXPECT_GE(e.kinematic_work, e.kinetic - 1e-9);
    EXPECT_LE(balance(e) - balance(start), 1e-9);
  }
}

TEST(Kinematic, AWheelHingedToACarriageIsCarriedAndPendulumsSwingAsAtRest) {
  // A carriage moving at a constant 3 m/s sideways is an inertial frame: a
  // wheel hinged at its centre goes along (with the direct solver not a
  // rotor: its axle moves), and a pendulum hinged to it swings with the
  // period of one hinged at rest, 2 pi sqrt(L / g) for a small point-like
  // bob.
  for (const test::Budget& b : test::kFourBudgets) {
    if (b.substeps == 1) continue;  // a pendulum's period wants substeps
    SCOPED_TRACE(test::name(b));
    World world = worldWith(b);
    BodyDef carriage;
    carriage.shape = Shape::box(Vec3(0.5, 0.1, 0.1));
    carriage.motion = {{0.0, Vec3(3.0, 0.0, 0.0), Vec3::Zero()}};
    const BodyId c = world.addBody(carriage);
    BodyDef def;
    def.shape = Shape::cylinder(0.2, 0.05);
    def.mass = 1.0;
    def.position = Vec3(0.3, 0.0, 0.0);
    def.linear_velocity = Vec3(3.0, 0.0, 0.0);  // at rest in the carriage's frame
    const BodyId wheel = world.addBody(def);
    world.addHinge(HingeDef(wheel, c, Vec3(0.3, 0.0, 0.0), Vec3::UnitZ()));
    def.shape = Shape::sphere(0.001);
    def.position = Vec3(-0.3 + 1.0 * std::sin(0.05), -1.0 * std::cos(0.05), 0.0);
    const BodyId bob = world.addBody(def);
    DistanceConstraint rod;
    rod.a = c;
    rod.b = bob;
    rod.local_a = Vec3(-0.3, 0.0, 0.0);
    rod.rest_length = 1.0;
    rod.unilateral = false;
    world.addDistance(rod);
    // Zero crossings of the bob relative to its pivot, rising.
    const double period = 2.0 * std::numbers::pi * std::sqrt(1.0 / kG);
    double first = -1.0, last = -1.0, before = world.body(bob).x.x() - (world.body(c).x.x() - 0.3);
    int crossings = 0;
    for (int f = 1; f <= 240; ++f) {
      world.step(1.0 / 60.0);
      const double rel = world.body(bob).x.x() - (world.body(c).x.x() - 0.3);
      if (before < 0.0 && rel >= 0.0) {
        const double t = (f - rel / (rel - before)) / 60.0;
        if (first < 0.0) first = t;
        last = t;
        ++crossings;
      }
      before = rel;
    }
    EXPECT_NEAR(world.body(wheel).x.x(), 0.3 + 3.0 * 4.0, 1e-6);
    EXPECT_NEAR(world.body(wheel).v.x(), 3.0, 1e-6);
    ASSERT_GE(crossings, 2);
    EXPECT_NEAR((last - first) / (crossings - 1), period, 0.01 * period);
  }
}

TEST(Kinematic, ADrumHaulingOverAWheelFixedInTheWorldIsStoppedUnlessTheCableCanSlideOrTheWheelTurn) {
  // A kinematic drum (r = 0.1 m) hauls at r |omega| = 0.2 m/s over a wheel
  // of 0.1 m fixed in the world (static) to a 5 kg load. Without slip on
  // the fixed wheel (no mu) nothing can pull the drum's span in: a rigid
  // cable cannot stretch, and the run is stopped (firstBreach) within two
  // substeps, the load unmoved. Turned round: a frictionless fixed wheel
  // (mu 0) lets the cable slide, a wheel on an axle turns, and the load
  // rises at 0.2 m/s holding m g (or is lowered, the drum paying out);
  // paying out over the fixed wheel leaves the drum's span slack.
  constexpr double r = 0.1, m = 5.0;
  enum class Wheel { Fixed, Frictionless, Hinged };
  for (const test::Budget& b : test::kFourBudgets)
    for (const Wheel wheel : {Wheel::Fixed, Wheel::Frictionless, Wheel::Hinged})
      for (const double omega : {-2.0, 2.0}) {  // -2: hauling
        SCOPED_TRACE(test::name(b) + ", wheel " + std::to_string(static_cast<int>(wheel)) + ", omega " +
                     std::to_string(omega));
        World world = worldWith(b);
        CableSystem cables(world);
        BodyDef drum;
        drum.name = "drum";
        drum.shape = Shape::cylinder(r, 0.05);
        drum.position = Vec3(-1.0, 0.0, 0.0);
        drum.motion = {{0.0, Vec3::Zero(), Vec3(0.0, 0.0, omega)}};
        const BodyId d = world.addBody(drum);
        BodyDef sheave;
        sheave.name = "sheave";
        sheave.shape = Shape::cylinder(r, 0.05);
        sheave.position = Vec3(1.0, 0.5, 0.0);
        sheave.is_static = wheel != Wheel::Hinged;
        sheave.mass = wheel == Wheel::Hinged ? 1.0 : 0.0;
        const BodyId s = world.addBody(sheave);
        if (wheel == Wheel::Hinged) world.addHinge(HingeDef(s, kWorldBody, Vec3(1.0, 0.5, 0.0), Vec3::UnitZ()));
        const BodyId load = addLoad(world, m, Vec3(1.0 + r, -1.0, 0.0));
        LinkDef spool = LinkDef::rolling(d, 1);
        spool.stored = 2.0;
        LinkDef over = LinkDef::rolling(s, -1);
        if (wheel == Wheel::Frictionless) over.mu = 0.0;
        CableDef rope;
        rope.name = "rope";
        rope.links = {spool, over, LinkDef::attachment(load, Vec3(0.0, 0.05, 0.0))};
        cables.addCable(rope);
        run(world, 60);
        const bool hauling = omega < 0.0;
        if (wheel == Wheel::Fixed && hauling) {
          ASSERT_TRUE(cables.firstBreach());
          EXPECT_TRUE(cables.firstBreach()->held_stretched);
          EXPECT_LE(cables.firstBreach()->time_s, 2.0 / (60.0 * b.substeps) + 1e-12);
          EXPECT_NE(cables.firstBreach()->what.find("cable 'rope': its run from 'drum' to 'sheave'"),
                    std::string::npos) << cables.firstBreach()->what;
          EXPECT_NEAR(world.body(load).x.y(), -1.0, 1e-6);
          continue;
        }
        ASSERT_FALSE(cables.firstBreach()) << cables.firstBreach()->what;
        if (wheel == Wheel::Fixed) {  // paying out: its span slack, the load hangs where it was
          EXPECT_NEAR(world.body(load).x.y(), -1.0, 1e-6);
          EXPECT_EQ(cables.tension(0, 0), 0.0);
          continue;
        }
        // Hauled up, or lowered, at r |omega|. (Gauss-Seidel's one sweep
        // a substep leaves the 1 kg wheel between the drum and the 5 kg
        // load unconverged, 5 to 15 % off: README, its limits.)
        if (wheel == Wheel::Hinged && b.solver == SolverKind::GaussSeidel && b.iterations == 1) continue;
        EXPECT_NEAR(world.body(load).v.y(), r * -omega, 1e-6);
        EXPECT_NEAR(world.body(load).x.y(), -1.0 + r * -omega, 2e-3);
        EXPECT_NEAR(cables.tension(0, 1), m * kG, 1e-3 * m * kG);
      }
}

TEST(Kinematic, ABreakableCableHauledOverAWheelFixedInTheWorldParts) {
  // The drum and fixed wheel above, the cable rated 200 N (four times the
  // load): holding the drum's span takes an unbounded tension, so it parts
  // there within two substeps, as an overloaded cable does (a Break event
  // at its rating), and the run goes on. The fixed wheel holds the cable
  // without slipping, so the load still hangs from it, unmoved.
  constexpr double r = 0.1, m = 5.0;
  for (const test::Budget& b : test::kFourBudgets) {
    SCOPED_TRACE(test::name(b));
    World world = worldWith(b);
    CableSystem cables(world);
    BodyDef drum;
    drum.shape = Shape::cylinder(r, 0.05);
    drum.position = Vec3(-1.0, 0.0, 0.0);
    drum.motion = {{0.0, Vec3::Zero(), Vec3(0.0, 0.0, -2.0)}};
    BodyDef sheave = drum;
    sheave.motion.clear();
    sheave.is_static = true;
    sheave.position = Vec3(1.0, 0.5, 0.0);
    const BodyId d = world.addBody(drum), s = world.addBody(sheave);
    const BodyId load = addLoad(world, m, Vec3(1.0 + r, -1.0, 0.0));
    LinkDef spool = LinkDef::rolling(d, 1);
    spool.stored = 2.0;
    CableDef rope;
    rope.breaking_tension = 200.0;
    rope.links = {spool, LinkDef::rolling(s, -1), LinkDef::attachment(load, Vec3(0.0, 0.05, 0.0))};
    cables.addCable(rope);
    std::vector<CableEvent> events;
    for (int f = 0; f < 60; ++f) {
      world.step(1.0 / 60.0);
      for (const CableEvent& e : cables.takeEvents()) events.push_back(e);
    }
    ASSERT_FALSE(cables.firstBreach()) << cables.firstBreach()->what;
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, CableEvent::Kind::Break);
    EXPECT_EQ(events[0].link, 0);
    EXPECT_EQ(events[0].tension, 200.0);
    EXPECT_LE(events[0].time_s, 2.0 / (60.0 * b.substeps) + 1e-12);
    EXPECT_TRUE(cables.cables()[0].joints[0].parted);
    EXPECT_NEAR(world.body(load).x.y(), -1.0, 1e-6);
    EXPECT_NEAR(cables.tension(0, 1), m * kG, 1e-3 * m * kG);
  }
}

TEST(Kinematic, WorldRefusesABadMotion) {
  World world;
  BodyDef def;
  def.shape = Shape::sphere(0.1);
  def.motion = {{0.0, Vec3::Zero(), Vec3::Zero()}, {0.0, Vec3::Zero(), Vec3::Zero()}};
  EXPECT_THROW(world.addBody(def), std::invalid_argument);
  def.motion = {{0.0, Vec3(std::nan(""), 0.0, 0.0), Vec3::Zero()}};
  EXPECT_THROW(world.addBody(def), std::invalid_argument);
  def.motion = {{0.0, Vec3::Zero(), Vec3::Zero()}};
  def.is_static = true;
  EXPECT_THROW(world.addBody(def), std::invalid_argument);
}

}  // namespace
}  // namespace reeve::test_kinematic
