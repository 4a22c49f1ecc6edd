// Winches (CableSystem::setWinch, beyond the paper): a load lifted at the
// commanded speed, a stall at the maximum pull with the acceleration that
// force gives, length mode stopping at its length, and the stored cable
// equal to what was reeled; both solvers, 20 x 1 and 1 x 10.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "reeve/cable/cable.h"
#include "solver_budgets.h"

namespace reeve::test_winch {
namespace {

constexpr double kG = 9.81;

struct Crane {
  World world;
  CableSystem cables{world};
  BodyId load = 0;
  int cable = 0;
  double total = 0.0;
  // A load of `mass` kg hanging 3 m below a winch fixed at the origin, on
  // a cable of `compliance` m/N and `damping` N s/m (the whole 3 m).
  Crane(double mass, SolverKind solver, int substeps, int iterations, double compliance = 0.0,
        double damping = 0.0) {
    world.settings().gravity = Vec3(0.0, -kG, 0.0);
    world.settings().solver = solver;
    world.settings().substeps = substeps;
    world.settings().iterations = iterations;
    BodyDef frame;
    frame.is_static = true;
    frame.shape = Shape::box(Vec3::Constant(0.1));
    const BodyId top = world.addBody(frame);
    BodyDef def;
    def.shape = Shape::box(Vec3::Constant(0.1));
    def.mass = mass;
    def.position = Vec3(0.0, -3.0, 0.0);
    load = world.addBody(def);
    CableDef c;
    c.links = {LinkDef::attachment(load, Vec3::Zero()), LinkDef::attachment(top, Vec3::Zero())};
    c.compliance = compliance;
    c.damping = damping;
    cable = cables.addCable(c);
    total = cables.totalLength(cable);
  }
  void run(double seconds) {
    for (int f = 0; f < std::lround(seconds * 60.0); ++f) world.step(1.0 / 60.0);
  }
  double stored() const { return cables.cables()[cable].links[1].stored; }
};

using test::Budget;
using test::kBudgets;
using test::name;

TEST(Winch, LiftsAtTheCommandedSpeedAndStoresWhatItReeled) {
  for (const Budget& b : kBudgets)
    for (const double mass : {5.0, 500.0}) {  // 49 N and 4.9 kN
      SCOPED_TRACE(name(b) + ", " + std::to_string(mass) + " kg");
      Crane c(mass, b.solver, b.substeps, b.iterations);
      WinchDef w;
      w.speed = 0.2;
      c.cables.setWinch(c.cable, w);
      c.run(1.0);
      EXPECT_NEAR(c.world.body(c.load).v.y(), 0.2, 2e-4);
      EXPECT_NEAR(c.stored(), 0.2 * c.world.time(), 1e-9);
      EXPECT_NEAR(c.world.body(c.load).x.y(), -3.0 + c.stored(), 1e-6);
      // Holding at speed: the pull is the weight.
      EXPECT_NEAR(c.cables.winchPull(c.cable), mass * kG, 1e-3 * mass * kG);
      EXPECT_NEAR(c.cables.totalLength(c.cable), c.total, 1e-9 * c.total);
      EXPECT_FALSE(c.cables.firstBreach().has_value());
    }
}

TEST(Winch, StallsAtItsMaximumPullAndTheLoadMovesAsThatForceSays) {
  // 5 kg (49 N), lifted at 0.5 m/s for 1 s (0.5 m on the drum), then
  // overloaded: a 40 N winch cannot hold it, which slows at g - 40 / 5 and
  // falls, the drum paying out; a 60 N winch asked for 1 m/s gets there at
  // 60 / 5 - g and then holds that speed.
  for (const Budget& b : kBudgets)
    for (const double pull : {40.0, 60.0}) {
      SCOPED_TRACE(name(b) + ", max pull " + std::to_string(pull) + " N");
      Crane c(5.0, b.solver, b.substeps, b.iterations);
      WinchDef w;
      w.speed = 0.5;
      c.cables.setWinch(c.cable, w);
      c.run(1.0);
      w.speed = 1.0;
      w.max_pull = pull;
      c.cables.setWinch(c.cable, w);
      c.run(0.1);
      const double v0 = c.world.body(c.load).v.y(), t0 = c.world.time(), stored0 = c.stored();
      c.run(0.1);
      const double a = (c.world.body(c.load).v.y() - v0) / (c.world.time() - t0);
      EXPECT_NEAR(a, pull / 5.0 - kG, 1e-3 * std::abs(pull / 5.0 - kG));
      EXPECT_NEAR(c.cables.winchPull(c.cable), pull, 1e-6 * pull);
      EXPECT_NEAR(c.cables.totalLength(c.cable), c.total, 1e-9 * c.total);
      EXPECT_FALSE(c.cables.firstBreach().has_value());
      c.run(0.5);
      if (pull > 50.0) {
        EXPECT_NEAR(c.world.body(c.load).v.y(), 1.0, 1e-3);
      } else {  // falling by now, the drum paying out under it
        EXPECT_NEAR(c.world.body(c.load).v.y(), 0.5 + (pull / 5.0 - kG) * (c.world.time() - 1.0), 1e-3);
        EXPECT_LT(c.stored(), stored0);
      }
      EXPECT_NEAR(c.cables.totalLength(c.cable), c.total, 1e-9 * c.total);
    }
}

TEST(Winch, LengthModeStopsAtItsLength) {
  for (const Budget& b : kBudgets) {
    SCOPED_TRACE(name(b));
    Crane c(5.0, b.solver, b.substeps, b.iterations);
    WinchDef w;
    w.max_speed = 0.3;
    w.target_stored = 0.5;
    c.cables.setWinch(c.cable, w);
    c.run(1.0);
    EXPECT_NEAR(c.world.body(c.load).v.y(), 0.3, 3e-4);  // on its way at max speed
    c.run(2.0);
    EXPECT_NEAR(c.stored(), 0.5, 1e-12);
    EXPECT_NEAR(c.world.body(c.load).x.y(), -2.5, 1e-3);  // within 1 mm
    EXPECT_LT(std::abs(c.world.body(c.load).v.y()), 1e-6);
    // Paying out again: to 0.2 m stored.
    w.target_stored = 0.2;
    c.cables.setWinch(c.cable, w);
    c.run(2.0);
    EXPECT_NEAR(c.world.body(c.load).x.y(), -2.8, 1e-3);
    EXPECT_NEAR(c.cables.totalLength(c.cable), c.total, 1e-9 * c.total);
  }
}

TEST(Winch, BadCommandsAreRefused) {
  Crane c(1.0, SolverKind::Direct, 10, 1);
  WinchDef w;
  w.max_pull = 0.0;
  EXPECT_THROW(c.cables.setWinch(c.cable, w), std::invalid_argument);
  w = WinchDef();
  w.max_speed = 0.1;
  w.speed = 0.2;
  EXPECT_THROW(c.cables.setWinch(c.cable, w), std::invalid_argument);
  w = WinchDef();
  w.target_stored = -1.0;
  EXPECT_THROW(c.cables.setWinch(c.cable, w), std::invalid_argument);
  w = WinchDef();
  w.speed = std::nan("");
  EXPECT_THROW(c.cables.setWinch(c.cable, w), std::invalid_argument);
  EXPECT_FALSE(c.cables.cables()[c.cable].winch.has_value());
}

TEST(Winch, FollowsItsScheduleFromEachCommandsTime) {
  // Hauls 0.2 m/s from the start, pays out at 0.1 m/s from 0.5 s, then
  // goes to 0.02 m stored from 1 s: 0.1 m at 0.5 s, 0.05 m at 1 s, 0.02 m
  // (and holding) by 1.5 s. Commands take over at substep starts, so the
  // stored cable is exact where the times fall on substeps.
  for (const Budget& b : kBudgets) {
    SCOPED_TRACE(name(b));
    Crane c(5.0, b.solver, b.substeps, b.iterations);
    WinchDef w;
    w.max_speed = 0.3;
    w.speed = 0.2;
    w.schedule = {{0.5, -0.1, std::nullopt}, {1.0, 0.0, 0.02}};
    c.cables.setWinch(c.cable, w);
    c.run(0.5);
    EXPECT_NEAR(c.stored(), 0.1, 1e-9);
    c.run(0.5);
    EXPECT_NEAR(c.stored(), 0.05, 1e-9);
    c.run(0.5);
    EXPECT_NEAR(c.stored(), 0.02, 1e-9);
    EXPECT_NEAR(c.world.body(c.load).x.y(), -3.0 + 0.02, 1e-3);
    EXPECT_NEAR(c.cables.totalLength(c.cable), c.total, 1e-9 * c.total);
  }
  // Out of order, or faster than the winch: refused.
  Crane c(5.0, SolverKind::Direct, 1, 1);
  WinchDef w;
  w.max_speed = 0.3;
  w.schedule = {{1.0, 0.1, std::nullopt}, {1.0, 0.0, std::nullopt}};
  EXPECT_THROW(c.cables.setWinch(c.cable, w), std::invalid_argument);
  w.schedule = {{1.0, 0.5, std::nullopt}};
  EXPECT_THROW(c.cables.setWinch(c.cable, w), std::invalid_argument);
}

// A World at budget `b` under `gravity` (m/s^2).
World budgetWorld(const Budget& b, const Vec3& gravity) {
  World world;
  world.settings().gravity = gravity;
  world.settings().solver = b.solver;
  world.settings().substeps = b.substeps;
  world.settings().iterations = b.iterations;
  return world;
}

// Two static posts, at the origin and 2 m along x.
std::pair<BodyId, BodyId> twoPosts(World& world) {
  BodyDef post;
  post.is_static = true;
  post.shape = Shape::box(Vec3::Constant(0.05));
  const BodyId first = world.addBody(post);
  post.position = Vec3(2.0, 0.0, 0.0);
  return {first, world.addBody(post)};
}

TEST(Winch, HaulingACompliantCableBetweenTwoStaticAnchorsStretchesItToTheClosedForm) {
  // Issue 28, item 8: 2 m of cable (compliance 2e-3 m/N for the whole, so
  // 1e-3 per metre) between two static anchors, 0.3 m reeled in at 0.3
  // m/s: 1.7 m of rest length stretched 0.3 m pulls 0.3 / 1.7e-3 = 176.5 N,
  // holding 0.3^2 / (2 x 1.7e-3) = 26.5 J, which the winch put in (with the
  // strain of the cable it reeled). The direct solver left the span out of
  // its system, nothing in it moving: 0 N, and the energy from nowhere.
  for (const Budget& b : test::kFourBudgets) {
    SCOPED_TRACE(name(b));
    World world = budgetWorld(b, Vec3::Zero());
    CableSystem cables(world);
    const auto [a, c2] = twoPosts(world);
    CableDef def;
    def.links = {LinkDef::attachment(a, Vec3::Zero()), LinkDef::attachment(c2, Vec3::Zero())};
    def.compliance = 2e-3;
    const int cable = cables.addCable(def);
    WinchDef w;
    w.target_stored = 0.3;
    w.max_speed = 0.3;
    cables.setWinch(cable, w);
    for (int f = 0; f < 90; ++f) world.step(1.0 / 60.0);
    const double alpha = 1e-3 * 1.7, tension = 0.3 / alpha;
    EXPECT_NEAR(cables.restLength(cable, 0), 1.7, 1e-12);
    EXPECT_NEAR(cables.tension(cable, 0), tension, 1e-9 * tension);
    EXPECT_NEAR(cables.winchPull(cable), tension, 1e-9 * tension);
    const double elastic = 0.5 * 0.3 * 0.3 / alpha;
    EXPECT_NEAR(world.energy().elastic, elastic, 1e-9 * elastic);
    EXPECT_GE(cables.winchWork(), elastic);  // the winch put it in: nothing made
  }
}

// Hauls 1 m onto the drum at 1 m/s (a pull no start can stall), holds it
// 0.5 s, then caps the winch at `max_pull` N commanding `speed` m/s.
void haulOneMetreThenCap(Crane& c, double max_pull, double speed) {
  WinchDef w;
  w.speed = 1.0;  // max_pull unlimited: 1 m hauled whatever the load
  w.max_speed = 1.0;
  w.schedule = {{1.0, 0.0, std::nullopt}};
  c.cables.setWinch(c.cable, w);
  c.run(1.5);
  w = WinchDef{};
  w.max_pull = max_pull;
  w.speed = speed;
  c.cables.setWinch(c.cable, w);
}

TEST(Winch, AnOverloadedWinchPaysOutWhatItHoldsAndAnEmptyDrumHolds) {
  // Issue 28, item 4: 10 kg on a winch of 60 N at most. On an empty drum
  // it cannot pay out: the tied end holds the load at 98.1 N (capped, the
  // inextensible span stretched from nothing: 1.9 m in 1 s). With 1 m
  // hauled onto the drum first and then held, it stalls and pays out
  // under the load, which sinks at g - 60 / 10 = 3.81 m/s^2 until the drum
  // is empty (0.72 s). The stall is paid out at the next
  // substep's update (the solve that hit 60 N left the span longer by its
  // fall in that substep): the span is never longer than its rest length
  // by more than the load's fall in one substep, v h + a h^2. Where the
  // drum runs out the tied end stops the load dead, 1 m down: paid out at
  // the next update there too, the last substep's stretch was projected
  // out by the solve after it, launching the load up (0.2 m/s at 10 x 2,
  // 0.05 at 1 x 1 with 0.3 m to pay out). On an elastic cable (1e-3 m/N) the stall keeps the stretch
  // of its 60 N: paid out too, the tension fell to 14 N and chattered back
  // up, the ledger seeing each drop as energy made.
  for (const Budget& b : test::kFourBudgets) {
    SCOPED_TRACE(name(b));
    Crane empty(10.0, b.solver, b.substeps, b.iterations);
    WinchDef w;
    w.max_pull = 60.0;
    empty.cables.setWinch(empty.cable, w);
    empty.run(1.0);
    EXPECT_NEAR(empty.world.body(empty.load).x.y(), -3.0, 1e-9);
    EXPECT_NEAR(empty.cables.tension(empty.cable, 0), 10.0 * kG, 1e-6 * 10.0 * kG);
    EXPECT_NEAR(empty.cables.length(empty.cable, 0), empty.cables.restLength(empty.cable, 0), 1e-9);

    Crane c(10.0, b.solver, b.substeps, b.iterations);
    haulOneMetreThenCap(c, 60.0, 0.0);
    ASSERT_NEAR(c.stored(), 1.0, 1e-9);
    const double y0 = c.world.body(c.load).x.y();
    const double a = kG - 60.0 / 10.0, h = 1.0 / (60.0 * b.substeps);
    double worst_stretch = 0.0;
    for (int f = 0; f < 30; ++f) {  // 0.5 s of the 0.72 s the drum lasts
      c.world.step(1.0 / 60.0);
      worst_stretch = std::max(worst_stretch, c.cables.length(c.cable, 0) - c.cables.restLength(c.cable, 0));
    }
    const double t = 0.5;
    EXPECT_NEAR(y0 - c.world.body(c.load).x.y(), 0.5 * a * t * t, a * t * h + 1e-9);
    EXPECT_LE(worst_stretch, a * t * h + a * h * h + 1e-12);
    double fastest_up = 0.0;
    for (int f = 0; f < 60; ++f) {  // on to 1.5 s: the drum runs out at 0.72 s
      c.world.step(1.0 / 60.0);
      fastest_up = std::max(fastest_up, c.world.body(c.load).v.y());
    }
    EXPECT_EQ(c.stored(), 0.0);
    EXPECT_LT(fastest_up, 1e-9);  // stopped, never launched
    EXPECT_NEAR(c.world.body(c.load).x.y(), y0 - 1.0, 1e-9);
    EXPECT_NEAR(c.world.body(c.load).v.y(), 0.0, 1e-9);
    EXPECT_NEAR(c.cables.totalLength(c.cable), c.total, 1e-9);

    // Hanging at rest on the stretched rope (1e-3 m/N per 3 m), hauled
    // slowly (0.1 m/s for 1 s: the rope swings within 10 N of the load's
    // weight), then capped: it pays out the stretch past 60 N's at once and
    // stalls for the 0.18 s the rest of its 0.1 m lasts.
    Crane elastic(10.0, b.solver, b.substeps, b.iterations, 1e-3);
    elastic.cables.setRestLength(elastic.cable, 0, 3.0 / (1.0 + 1e-3 / 3.0 * 10.0 * kG));
    w = WinchDef{};
    w.speed = 0.1;
    elastic.cables.setWinch(elastic.cable, w);
    elastic.run(1.0);
    w.speed = 0.0;
    w.max_pull = 60.0;
    elastic.cables.setWinch(elastic.cable, w);
    for (int f = 0; f < 11; ++f) {
      elastic.world.step(1.0 / 60.0);
      const double pull = elastic.cables.winchPull(elastic.cable);
      EXPECT_LE(pull, 60.0 * (1.0 + 1e-9)) << "t = " << elastic.world.time();
      // Once the load, rising at 0.1 m/s when capped, has turned (the rope
      // just under 60 N meanwhile), it sinks with the drum stalled at 60 N.
      if (f >= 5) {
        EXPECT_NEAR(pull, 60.0, 1e-6 * 60.0) << "t = " << elastic.world.time();
      }
    }
  }
}

// Item 4 at the extremes of mass: 1 g and 10 t on a winch of 0.6 m g at
// most (10 kg is above). On an empty drum the tied end holds the load;
// with 1 m hauled on and held, it stalls, the load sinks at 0.4 g, and
// where the drum runs out (0.714 s) it stops dead 1 m down, never
// launched, as at 10 kg.
TEST(Winch, AnOverloadedWinchHoldsOrStopsItsLoadDeadAtEveryMass) {
  for (const double m : {1e-3, 1e4})
    for (const Budget& b : test::kFourBudgets) {
      SCOPED_TRACE(name(b) + ", " + std::to_string(m) + " kg");
      Crane empty(m, b.solver, b.substeps, b.iterations);
      WinchDef w;
      w.max_pull = 0.6 * m * kG;
      empty.cables.setWinch(empty.cable, w);
      empty.run(1.0);
      EXPECT_NEAR(empty.world.body(empty.load).x.y(), -3.0, 1e-9);
      EXPECT_NEAR(empty.cables.tension(empty.cable, 0), m * kG, 1e-6 * m * kG);

      Crane c(m, b.solver, b.substeps, b.iterations);
      haulOneMetreThenCap(c, 0.6 * m * kG, 0.0);
      ASSERT_NEAR(c.stored(), 1.0, 1e-9);
      const double y0 = c.world.body(c.load).x.y();
      const double a = 0.4 * kG, h = 1.0 / (60.0 * b.substeps);
      double fastest_up = 0.0;
      for (int f = 0; f < 90; ++f) {  // 1.5 s
        c.world.step(1.0 / 60.0);
        fastest_up = std::max(fastest_up, c.world.body(c.load).v.y());
        if (f == 29) {
          EXPECT_NEAR(y0 - c.world.body(c.load).x.y(), 0.5 * a * 0.25, a * 0.5 * h + 1e-9);  // 0.5 s
        }
        if (c.stored() > 0.0) {
          EXPECT_LE(c.cables.winchPull(c.cable), 0.6 * m * kG * (1.0 + 1e-9));  // then the catch
        }
      }
      EXPECT_EQ(c.stored(), 0.0);
      EXPECT_LT(fastest_up, 1e-9);  // stopped, never launched
      EXPECT_NEAR(c.world.body(c.load).x.y(), y0 - 1.0, 1e-9);
      EXPECT_NEAR(c.world.body(c.load).v.y(), 0.0, 1e-9);
      EXPECT_NEAR(c.cables.tension(c.cable, 0), m * kG, 1e-6 * m * kG);
      EXPECT_NEAR(c.cables.totalLength(c.cable), c.total, 1e-9);
    }
}

// A winch told to haul from an empty drum, outpulled (max_pull half the
// load's weight), on an elastic cable with a dashpot (m03 of the generated
// machines). Each substep's stall paid out the slip of the solve before as
// cable fed in that substep, so the dashpot read it as the cable
// shortening and cut the tension: the load, let go on the unstretched
// cable, gained energy in its first frames (0.05 to 1.3 J at 1 kg, up to
// 4 % of m g x 3 m) and, at
// 10 x 2 and 32 x 32 below twice critical damping, went on chattering
// between 0 and 8 times its weight. It must settle and hang at m g with the
// drum empty, never holding more energy than the winch put in.
TEST(Winch, AConstantPullWinchBooksTheWorkItDoes) {
  // A winch asked to haul far faster than its load can follow (1e6 m/s,
  // as an MJCF tendon motor or muscle is imported) stalls at its pull all
  // along: a constant tension, the load rising at a = pull / m - g. Its
  // work is the pull times the cable its load took in: what the load
  // gained plus implicit Euler's loss under a constant force, exactly
  // m (a h)^2 / 2 a substep (v' = v + a h, x' = x + h v': the pull does
  // m (a + g) h v', kinetic and potential energy take m a h v' - m (a h)^2 / 2).
  // At each frame the ledger's winch work is that, to 1e-9. (Booked
  // between updates as its whole reel, 1 x 10 showed 56 J for 25.6 J done
  // and the balance rising frame by frame.)
  for (const Budget& b : test::kFourBudgets)
    for (const double m : {1.0, 1e3}) {
      SCOPED_TRACE(name(b) + ", " + std::to_string(m) + " kg");
      Crane c(m, b.solver, b.substeps, b.iterations);
      WinchDef w;
      w.speed = w.max_speed = 1e6;
      w.max_pull = 2.0 * m * kG;
      c.cables.setWinch(c.cable, w);
      const WorldEnergy start = c.world.energy();
      const double h = 1.0 / (60.0 * b.substeps), a = kG;
      for (int f = 1; f <= 30; ++f) {
        c.world.step(1.0 / 60.0);
        const WorldEnergy e = c.world.energy();
        const double gained = e.kinetic + e.gravity - start.kinetic - start.gravity, work = c.cables.winchWork();
        const double lost = f * b.substeps * 0.5 * m * a * a * h * h;
        EXPECT_NEAR(work, gained + lost, 1e-9 * work) << "t = " << c.world.time();
      }
      EXPECT_NEAR(c.world.body(c.load).v.y(), kG * c.world.time(), 1e-9 * kG);
      EXPECT_NEAR(c.cables.totalLength(c.cable), c.total, 1e-9 * c.total);
    }
}

TEST(Winch, AnOutpulledWinchOnADampedElasticCableHangsItsLoadSteady) {
  for (const double m : {1e-3, 1.0, 1e4})
    for (const double zeta : {0.5, 2.0})  // the damping ratio
      for (const Budget& b : test::kFourBudgets) {
        SCOPED_TRACE(name(b) + ", " + std::to_string(m) + " kg, damping ratio " + std::to_string(zeta));
        // 0.1 mm of stretch under m g and sqrt(k / m) = 316 rad/s at every mass.
        const double compliance = 1e-5 / m;
        Crane c(m, b.solver, b.substeps, b.iterations, compliance, zeta * 2.0 * std::sqrt(m / compliance));
        WinchDef w;
        w.target_stored = 0.2;
        w.max_speed = 0.25;
        w.max_pull = 0.5 * m * kG;
        c.cables.setWinch(c.cable, w);
        const auto held = [&c] {
          const WorldEnergy e = c.world.energy();
          return e.kinetic + e.gravity + e.elastic - c.cables.winchWork();
        };
        // At one substep a frame the first catch rises 6e-4 of m g x 3 m
        // (1.8e-5 at two substeps, none from four): the budget's own error.
        const double start = held(), scale = m * kG * 3.0, rise = b.substeps == 1 ? 1e-3 : 1e-9;
        for (int f = 0; f < 60; ++f) {
          c.world.step(1.0 / 60.0);
          EXPECT_LE(held() - start, rise * scale) << "t = " << c.world.time();
          if (f >= 30) {
            EXPECT_NEAR(c.cables.tension(c.cable, 0), m * kG, 1e-6 * m * kG) << "t = " << c.world.time();
          }
        }
        const double settled = -3.0 - compliance * m * kG;
        EXPECT_EQ(c.stored(), 0.0);
        EXPECT_NEAR(c.world.body(c.load).x.y(), settled, 1e-3 * compliance * m * kG);
        EXPECT_NEAR(c.cables.totalLength(c.cable), c.total, 1e-9);
      }
}

TEST(Winch, HaulingAndPayingOutThroughAFrictionPinholeHoldTheCapstanRatio) {
  // Issue 28, item 6: 10 kg hanging 2 m below a static pinhole with mu 0.2,
  // the cable turning 90 degrees there to a winch 2 m off: hauling at 0.2
  // m/s the drum pulls m g exp(mu pi / 2) = 134.3 N and the load rises at
  // 0.2 m/s; paying out, m g exp(-mu pi / 2) = 71.65 N. The span between
  // the pinhole and the static drum cannot be solved while the pinhole
  // sticks; read as 0 N, it made the pinhole slip the wrong way and the
  // load was flung up at up to 10 m/s (+457 J in a frame at 10 x 2).
  // Paying out, reversed from hauling: the load falls free until it has
  // caught up with the cable paid out (at the winch's own displacement) and
  // then descends at 0.2 m/s. At 10 substeps and more the pinhole stuck and
  // slipped by turns there, the load falling in jerks: a slipping link stuck
  // again while its run was slack (DESIGN, item 6).
  const double g = 9.81, k = std::exp(0.2 * std::numbers::pi / 2.0);
  for (const Budget& b : test::kFourBudgets)
    for (const double speed : {0.2, -0.2}) {
      SCOPED_TRACE(name(b) + ", " + std::to_string(speed) + " m/s");
      World world = budgetWorld(b, Vec3(0.0, -g, 0.0));
      CableSystem cables(world);
      const auto [pin, drum] = twoPosts(world);
      BodyDef def;
      def.shape = Shape::box(Vec3::Constant(0.05));
      def.mass = 10.0;
      def.position = Vec3(0.0, -2.0, 0.0);
      const BodyId load = world.addBody(def);
      CableDef c;
      LinkDef hole = LinkDef::pinhole(pin, Vec3::Zero());
      hole.mu = 0.2;
      c.links = {LinkDef::attachment(load, Vec3::Zero()), hole, LinkDef::attachment(drum, Vec3::Zero())};
      const int cable = cables.addCable(c);
      if (speed < 0.0) {  // cable on the drum to pay out
        WinchDef haul;
        haul.speed = 0.2;
        cables.setWinch(cable, haul);
        for (int f = 0; f < 60; ++f) world.step(1.0 / 60.0);
      }
      WinchDef w;
      w.speed = speed;
      cables.setWinch(cable, w);
      const double y0 = world.body(load).x.y();
      const double start = world.energy().kinetic + world.energy().gravity;
      const double work0 = cables.winchWork(), friction0 = cables.frictionLoss();
      for (int f = 0; f < 30; ++f) world.step(1.0 / 60.0);
      EXPECT_NEAR(world.body(load).x.y() - y0, speed * 0.5, 1e-9);
      EXPECT_NEAR(world.body(load).v.y(), speed, 1e-9);
      EXPECT_NEAR(cables.tension(cable, 0), 10.0 * g, 1e-6 * g);
      EXPECT_NEAR(cables.tension(cable, 1), 10.0 * g * (speed > 0.0 ? k : 1.0 / k), 1e-6 * g);
      // Nothing made: what the bodies gained and friction took, the winch put in.
      const WorldEnergy e = world.energy();
      EXPECT_LE(e.kinetic + e.gravity - start + cables.frictionLoss() - friction0,
                cables.winchWork() - work0 + 1e-9 * g);
    }
}

TEST(Winch, AnOverloadedWinchPayingOutBrakesAtItsMaximumPullOnceTheLoadCatchesUp) {
  // Issue 28, item 5, turned round: 10 kg held by a 60 N winch (1 m of
  // cable on its drum), then told to pay out at 0.2 m/s. The load falls
  // freely into the slack paid out until it has fallen as far as the drum
  // gave (g t^2 / 2 = 0.2 t: t_c = 0.0408 s, 0.4 m/s), then the winch
  // cannot brake it to 0.2 m/s with 60 N and stalls: 3.81 m/s^2 on from
  // there, so 2.15 m/s at 0.5 s, pulling 60 N. (Read over the whole 0.5 s
  // as one acceleration, that is 4.3 m/s^2: the free fall, not a weak brake.)
  for (const Budget& b : test::kFourBudgets) {
    SCOPED_TRACE(name(b));
    Crane c(10.0, b.solver, b.substeps, b.iterations);
    haulOneMetreThenCap(c, 60.0, -0.2);
    c.run(0.5);
    const double t_c = 2.0 * 0.2 / kG, h = 1.0 / (60.0 * b.substeps);
    const double v = kG * t_c + (kG - 6.0) * (0.5 - t_c);
    EXPECT_NEAR(-c.world.body(c.load).v.y(), v, 2.0 * kG * h);  // the catch-up falls on a substep
    EXPECT_NEAR(c.cables.winchPull(c.cable), 60.0, 1e-6);
  }
}

}  // namespace
}  // namespace reeve::test_winch
