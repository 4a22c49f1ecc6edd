// A circle section off its body's origin (Section::centre): a sheave on a
// block's end, a knuckle at a phalanx's end, an eccentric drum, as part of
// the body it sits on rather than a body welded to it. Its geometry is the
// centred circle's moved, its cable is conserved while its body turns it
// round an axle it is not on, and a body carrying one moves as the same
// body with a wheel welded there.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "reeve/cable/cable.h"
#include "reeve/cable/section.h"
#include "cable_machine.h"
#include "pendulum_period.h"
#include "solver_budgets.h"

namespace reeve::test_off_centre_section {
namespace {

constexpr double kG = test::kCableMachineG, kPi = std::numbers::pi;

using test::Budget;
using test::kBudgets;

TEST(OffCentreSection, IsTheCentredCircleMoved) {
  // Every section function on a circle about c equals the same function on
  // the circle about the origin, with its points moved by c.
  const Vec2 c(0.37, -1.25);
  const Section moved = Section::circle(0.2, c), centred = Section::circle(0.2);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const Vec2 p(2.0 * u(rng), 2.0 * u(rng)), q(2.0 * u(rng), 2.0 * u(rng));
    const Vec2 a = 0.2 * Vec2(u(rng), u(rng)).normalized(), b = 0.2 * Vec2(u(rng), u(rng)).normalized();
    const int o = u(rng) < 0.0 ? -1 : 1;
    for (const bool leaving : {true, false}) {
      const auto t0 = tangentFromPoint(centred, p, o, leaving), t1 = tangentFromPoint(moved, p + c, o, leaving);
      ASSERT_EQ(t0.has_value(), t1.has_value());
      if (t0) {
        EXPECT_LT((*t1 - c - *t0).norm(), 1e-14);
      }
    }
    EXPECT_NEAR(boundaryPosition(moved, a + c), boundaryPosition(centred, a), 1e-13);
    EXPECT_LT((boundaryPoint(moved, 0.7 * k) - c - boundaryPoint(centred, 0.7 * k)).norm(), 1e-14);
    const double turn = 3.0 * u(rng);
    EXPECT_NEAR(sectionSurfaceDistance(moved, a + c, b + c, o, turn), sectionSurfaceDistance(centred, a, b, o, turn),
                1e-13);
    EXPECT_NEAR(sectionWrappedArc(moved, a + c, b + c, o), sectionWrappedArc(centred, a, b, o), 1e-13);
    // Two sections, the second about (0.05, 0.02) from q: the moved circle
    // at p is the centred one at p + c.
    const Section other = Section::circle(0.1, Vec2(0.05, 0.02));
    const auto s1 = sectionTangent(moved, p, o, other, q, -o), s2 = sectionTangent(centred, p + c, o, other, q, -o);
    ASSERT_EQ(s1.has_value(), s2.has_value());
    if (s1) {
      EXPECT_LT((s1->on_from - s2->on_from).norm(), 1e-13);
      EXPECT_LT((s1->on_to - s2->on_to).norm(), 1e-13);
    }
  }
  EXPECT_THROW(Section::circle(0.2, Vec2(std::nan(""), 0.0)), std::invalid_argument);
  EXPECT_EQ(moved, Section::circle(0.2, c));
  EXPECT_FALSE(moved == centred);
}

using Machine = test::CableMachine;

LinkDef groove(BodyId body, int orientation, const Vec2& centre, double radius, std::optional<double> mu) {
  LinkDef d = LinkDef::rolling(body, orientation);
  d.section = Section::circle(radius, centre);
  d.mu = mu;
  return d;
}

TEST(OffCentreSection, AnAtwoodMachineOverTwoGroovesOfOneStaticBarMeetsTheMasslessPulleyClosedForm) {
  // One static bar, its origin at the world's, with two frictionless
  // grooves of r = 0.1 m about (-0.6, 0.2) and (0.9, -0.1): the boxes hang
  // straight below the grooves' outer sides, x = -0.7 and 1.0, and move
  // as over massless pulleys, a = g (m2 - m1) / (m1 + m2), T = 2 m1 m2 g /
  // (m1 + m2) in all three spans. Both solvers, up to 3 kN.
  constexpr double r = 0.1;
  const Vec2 left_c(-0.6, 0.2), right_c(0.9, -0.1);
  struct Case {
    double m1, m2;
  } cases[] = {{1.0, 2.0}, {1e-3, 3e-3}, {100.0, 300.0}};
  for (const Budget& b : kBudgets)
    for (const Case& c : cases) {
      SCOPED_TRACE(test::name(b) + ", m1 " + std::to_string(c.m1) + " m2 " + std::to_string(c.m2));
      Machine m(b);
      BodyDef bar;
      bar.shape = Shape::box(Vec3(1.0, 0.05, 0.05));
      bar.is_static = true;
      const BodyId fixed = m.world.addBody(bar);
      const BodyId left = m.box(c.m1, Vec3(left_c.x() - r, -2.0, 0.0));
      const BodyId right = m.box(c.m2, Vec3(right_c.x() + r, -2.0, 0.0));
      CableDef def;
      def.links = {LinkDef::attachment(left, Vec3(0.0, 0.05, 0.0)), groove(fixed, -1, left_c, r, 0.0),
                   groove(fixed, -1, right_c, r, 0.0), LinkDef::attachment(right, Vec3(0.0, 0.05, 0.0))};
      m.cable = m.cables.addCable(def);
      m.total = m.cables.totalLength(m.cable);
      // The span between the grooves: their common outer tangent.
      const double between = (right_c - left_c).norm();
      EXPECT_NEAR(m.cables.length(m.cable, 1), between, 1e-12);
      m.run(0.5);
      const double a = kG * (c.m2 - c.m1) / (c.m1 + c.m2), T = 2.0 * c.m1 * c.m2 * kG / (c.m1 + c.m2);
      const double t = m.world.time();
      EXPECT_NEAR(m.world.body(right).v.y(), -a * t, 1e-3 * a * t);
      EXPECT_NEAR(m.world.body(left).v.y(), a * t, 1e-3 * a * t);
      EXPECT_NEAR(m.world.body(left).x.x(), left_c.x() - r, 1e-9);
      EXPECT_NEAR(m.world.body(right).x.x(), right_c.x() + r, 1e-9);
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(m.cables.tension(m.cable, j), T, 1e-3 * T) << "span " << j;
      m.expectLengthKept();
    }
}

// A disc hinged at its centre of mass (the origin) carries a drum of
// radius r about (e, 0) in its frame: an eccentric. A hybrid link stores
// cable on it, which runs down its right side to a load on a vertical rail
// at x = e + r. Driven round at `omega`, the load's demanded acceleration,
// e omega^2 = 0.2 m/s^2 at most, is well below g: the cable stays taut.
// Free (no omega), the 0.5 kg load unwinds the 20 kg disc, turning it in
// every solve.
struct Eccentric {
  static constexpr double r = 0.1, e = 0.05, stored = 10.0;
  Machine m;
  BodyId disc = 0, load = 0;
  Eccentric(const Budget& b, std::optional<double> omega, double load_kg) : m(b) {
    BodyDef d;
    d.shape = Shape::cylinder(0.16, 0.02);
    d.mass = 20.0;  // free, it turns 4 rad in 1.5 s: e omega^2 stays below g
    disc = m.world.addBody(d);
    HingeDrive drive;
    drive.mode = omega ? HingeDrive::Mode::Velocity : HingeDrive::Mode::None;
    drive.target = omega.value_or(0.0);
    m.world.addHinge({disc, kWorldBody, Vec3::Zero(), Vec3::UnitZ(), 0.0, {}, drive});
    load = m.box(load_kg, Vec3(e + r, -1.0, 0.0));
    m.world.body(load).v = Vec3(0.0, drive.target * (e + r), 0.0);  // the drum's tangent point's: taut from the start
    PrismaticDef rail;
    rail.body = load;
    rail.anchor = Vec3(e + r, -1.0, 0.0);
    rail.axis = Vec3::UnitY();
    m.world.addPrismatic(rail);
    LinkDef drum = LinkDef::hybrid(disc, -1, stored);
    drum.section = Section::circle(r, Vec2(e, 0.0));
    CableDef def;
    def.links = {drum, LinkDef::attachment(load, Vec3(0.0, 0.05, 0.0))};
    m.cable = m.cables.addCable(def);
    m.total = m.cables.totalLength(m.cable);
  }
  // The tangent point (world) of the span from the load's tie point to the
  // drum, found here from the disc's pose: the cable leaves the drum with
  // the drum on its right (clockwise), so the point is the centre plus r
  // along the direction to the tie point turned by +acos(r / d).
  Vec3 tangentPoint() const {
    const BodyState& body = m.world.body(disc);
    const Vec3 centre = body.toWorld(Vec3(e, 0.0, 0.0));
    const Vec3 tie = m.world.body(load).toWorld(Vec3(0.0, 0.05, 0.0));
    const Vec3 d = tie - centre;
    const double beta = std::acos(r / d.norm());
    const Vec3 u = d.normalized();
    return centre + r * Vec3(std::cos(beta) * u.x() - std::sin(beta) * u.y(),
                             std::sin(beta) * u.x() + std::cos(beta) * u.y(), 0.0);
  }
  // The tangent point's angle about the drum's centre in the disc's frame.
  double angleOnDrum(const Vec3& tangent) const {
    const Vec3 local = m.world.body(disc).toLocal(tangent) - Vec3(e, 0.0, 0.0);
    return std::atan2(local.y(), local.x());
  }
};

TEST(OffCentreSection, AnEccentricDrumWindsAndUnwindsItsCableWithTheLengthKept) {
  // The cable between the drum's fixed end and the load: the cable stored
  // on the drum, r times the angle the tangent point moved back over it in
  // the disc's frame, plus the straight span to the load, stays what it
  // was, found from the poses alone. The drum's centre swings by +-e = 5 cm
  // round the axle: a tangent point about the disc's origin would be
  // centimetres out. Hoisting (omega > 0 winds) and lowering loads of
  // 1e-6, 1/40 and 10 times the disc's 20 kg (2 kN), and a 0.5 kg load
  // turning it free, both solvers.
  struct Case {
    std::optional<double> omega;
    double load_kg;
  };
  const Case cases[] = {{2.0, 2e-5}, {-2.0, 2e-5}, {2.0, 0.5}, {-2.0, 0.5}, {2.0, 200.0}, {-2.0, 200.0}, {{}, 0.5}};
  for (const Budget& b : kBudgets)
    for (const auto& [omega, load_kg] : cases) {
      SCOPED_TRACE(test::name(b) + (omega ? ", omega " + std::to_string(*omega) : ", free") + ", load " +
                   std::to_string(load_kg) + " kg");
      Eccentric x(b, omega, load_kg);
      const Vec3 t0 = x.tangentPoint();
      const double span0 = (x.m.world.body(x.load).toWorld(Vec3(0.0, 0.05, 0.0)) - t0).norm();
      EXPECT_NEAR(x.m.cables.length(x.m.cable, 0), span0, 1e-12);
      double angle = x.angleOnDrum(t0), moved = 0.0, worst = 0.0;
      const double y0 = x.m.world.body(x.load).x.y();
      for (int f = 0; f < 90; ++f) {  // 1.5 s: 3 rad, past the eccentric's half turn
        x.m.run(1.0 / 60.0);
        const Vec3 t = x.tangentPoint();
        const double now = x.angleOnDrum(t);
        moved += wrapAngle(now - angle);
        angle = now;
        const double span = (x.m.world.body(x.load).toWorld(Vec3(0.0, 0.05, 0.0)) - t).norm();
        worst = std::max(worst, std::abs(span - x.r * moved - span0));
      }
      // A rigid cable on a driven drum: held to the solver's tolerance.
      EXPECT_LT(worst, b.solver == SolverKind::Direct ? 1e-6 : 1e-4);
      EXPECT_NEAR(x.m.cables.length(x.m.cable, 0), x.m.cables.restLength(x.m.cable, 0), 1e-4);
      // Wound or unwound r x the arc the tangent point travelled over the
      // drum, give or take the eccentric's swing. Driven, the disc turned
      // 3 rad (the tangent point 2.85 over it), but for Gauss-Seidel's
      // drive at 1 x 10 under 10 times the disc's mass: 0.96 (its sweeps
      // pass a drive's pull on to the load one row a sweep: README, its
      // price).
      const double rise = x.m.world.body(x.load).x.y() - y0;
      EXPECT_GT(std::abs(moved), b.solver == SolverKind::GaussSeidel && load_kg > 20.0 ? 0.9 : 2.5);
      EXPECT_GT(std::abs(rise), x.r * std::abs(moved) - 2.0 * x.e);
      EXPECT_GT(rise * omega.value_or(-1.0), 0.0);
      x.m.expectLengthKept();
    }
}

TEST(OffCentreSection, APendulumMeetsAPegThatIsASectionOfABarWhereThePegIs) {
  // Galileo's pendulum (merge_split.json), its 1 cm peg 1 m below the
  // pivot now a section of a static bar whose origin is 0.5 m to the
  // peg's right: released at 45 degrees on 2 m, the string meets the peg
  // as it passes the vertical (split), swings round it on 1 m and leaves
  // it on the way back (merge), twice, at the times the two pendulums'
  // quarter periods give; the cable's length is kept across the events.
  // Split tests about the bar's origin would wrap the string 0.5 m off.
  for (const Budget& b : {Budget{SolverKind::Direct, 20, 2}, Budget{SolverKind::GaussSeidel, 20, 2}}) {
    SCOPED_TRACE(test::name(b));
    Machine m(b);
    BodyDef fixed;
    fixed.is_static = true;
    fixed.shape = Shape::box(Vec3::Constant(0.05));
    const BodyId pivot = m.world.addBody(fixed);
    fixed.shape = Shape::box(Vec3(0.6, 0.05, 0.05));
    fixed.position = Vec3(0.5, -1.0, 0.0);
    const BodyId bar = m.world.addBody(fixed);
    BodyDef ball;
    ball.shape = Shape::sphere(0.1);
    ball.mass = 1.0;
    ball.position = Vec3(-std::sqrt(2.0), -std::sqrt(2.0), 0.0);
    const BodyId bob = m.world.addBody(ball);
    LinkDef peg = groove(bar, 1, Vec2(-0.5, 0.0), 0.01, std::nullopt);
    peg.active = false;
    CableDef def;
    def.links = {LinkDef::attachment(pivot, Vec3::Zero()), peg, LinkDef::attachment(bob, Vec3::Zero())};
    m.cable = m.cables.addCable(def);
    m.total = m.cables.totalLength(m.cable);
    std::vector<CableEvent> events;
    double lowest_wrapped = 0.0;
    for (int f = 0; f < 360; ++f) {
      m.run(1.0 / 60.0);
      for (const CableEvent& e : m.cables.takeEvents()) events.push_back(e);
      if (events.size() % 2 == 1) lowest_wrapped = std::min(lowest_wrapped, m.world.body(bob).x.y());
      EXPECT_NEAR(m.cables.totalLength(m.cable), m.total, 1e-9 * m.total);
    }
    ASSERT_GE(events.size(), 4u);
    const double t_long = test::quarterPeriod(2.0, kPi / 4, kG);
    const double short_amplitude = std::acos(1.0 - 2.0 * (1.0 - std::cos(kPi / 4)));
    const double t_short = 2.0 * test::quarterPeriod(1.0, short_amplitude, kG);
    const double expected[] = {t_long, t_long + t_short, 3 * t_long + t_short, 3 * t_long + 2 * t_short};
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(events[i].kind, i % 2 == 0 ? CableEvent::Kind::Split : CableEvent::Kind::Merge) << i;
      EXPECT_NEAR(events[i].time_s, expected[i], 0.02 * expected[i]) << "event " << i;
    }
    // Round the peg on 1 m, the bob stays within 1 m of it: never below -2 m.
    EXPECT_GT(lowest_wrapped, -2.0 - 1e-3);
    EXPECT_LT(lowest_wrapped, -1.9);
  }
}

// A jib of 2 kg (1 m x 0.1 m x 0.1 m) hinged at its left end, with a 0.5 kg
// sheave of r = 0.1 m at its right end. The cable runs from a static post
// above the hinge over the sheave and down to a 1 kg load, which starts
// swinging sideways. `welded`: the sheave is a body of its own on a fixed
// joint; else it is a circle section of one body with the jib's and the
// sheave's mass, centre of mass and inertia.
struct Jib {
  static constexpr double r = 0.1;
  Machine m;
  BodyId jib = 0, load = 0;
  Jib(const Budget& b, bool welded, std::optional<double> mu) : m(b) {
    BodyDef post;
    post.is_static = true;
    post.position = Vec3(-0.5, 0.6, 0.0);
    const BodyId top = m.world.addBody(post);
    BodyDef beam;
    beam.shape = Shape::box(Vec3(0.5, 0.05, 0.05));
    beam.mass = 2.0;
    BodyDef wheel;
    wheel.shape = Shape::cylinder(r, 0.05);
    wheel.mass = 0.5;
    wheel.position = Vec3(0.5, 0.0, 0.0);
    LinkDef over;
    if (welded) {
      jib = m.world.addBody(beam);
      const BodyId sheave = m.world.addBody(wheel);
      m.world.addFixed({sheave, jib, wheel.position, 0.0});
      over = LinkDef::rolling(sheave, -1);
    } else {
      // The two bodies' mass properties about their joint centre of mass
      // (parallel axes), from the engine's own moments of each.
      World parts;
      const Mat3 I_beam = parts.body(parts.addBody(beam)).inertia;
      const Mat3 I_wheel = parts.body(parts.addBody(wheel)).inertia;
      const double M = beam.mass + wheel.mass;
      const Vec3 com = (wheel.mass * wheel.position) / M;
      const auto shifted = [](double mass, const Vec3& d) {
        return Mat3(mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose()));
      };
      const Mat3 I = I_beam + shifted(beam.mass, -com) + I_wheel + shifted(wheel.mass, wheel.position - com);
      BodyDef one = beam;
      one.mass = M;
      one.position = com;
      one.inertia = I.diagonal();
      jib = m.world.addBody(one);
      over = LinkDef::rolling(jib, -1);
      over.section = Section::circle(r, (wheel.position - com).head<2>());
    }
    over.mu = mu;
    m.world.addHinge({jib, kWorldBody, Vec3(-0.5, 0.0, 0.0), Vec3::UnitZ()});
    load = m.box(1.0, Vec3(0.5 + r, -1.0, 0.0));
    m.world.body(load).v = Vec3(0.8, 0.0, 0.0);
    CableDef def;
    def.links = {LinkDef::attachment(top, Vec3::Zero()), over, LinkDef::attachment(load, Vec3(0.0, 0.05, 0.0))};
    m.cable = m.cables.addCable(def);
    m.total = m.cables.totalLength(m.cable);
  }
};

TEST(OffCentreSection, AJibWithItsSheaveAsASectionMovesAsTheJibWithTheSheaveWelded) {
  // The same rigid body either way, so the same motion, up to the
  // integration's: a welded body's velocity is its centre's chord over the
  // substep, where the one body's is its centre's arc, so the two part by
  // O(h) while the jib turns. Rolling, the taut rope holds the jib still
  // while the load swings: the same to rounding. Frictionless, the jib
  // swings up a radian and more as the load falls: the two part by
  // micrometres at 10 substeps a frame, 8 times less at 80. A tangent point
  // taken about the body's origin, not the sheave's centre, would put the
  // span centimetres out.
  for (const std::optional<double> mu : {std::optional<double>(), std::optional<double>(0.0)}) {
    double apart[2] = {}, turned = 0.0, swing = 0.0;
    for (const int n : {0, 1}) {
      const Budget b{SolverKind::Direct, n == 0 ? 10 : 80, 4};
      SCOPED_TRACE(test::name(b) + (mu ? ", frictionless" : ", rolling"));
      Jib welded(b, true, mu), one(b, false, mu);
      const Vec3 start = one.m.world.body(one.load).x;
      for (int f = 0; f < 30; ++f) {
        welded.m.run(1.0 / 60.0);
        one.m.run(1.0 / 60.0);
        apart[n] = std::max(apart[n], (welded.m.world.body(welded.load).x - one.m.world.body(one.load).x).norm());
        swing = std::max(swing, (one.m.world.body(one.load).x - start).norm());
        turned = std::max(turned, 2.0 * std::abs(std::asin(one.m.world.body(one.jib).q.z())));
      }
      welded.m.expectLengthKept();
      one.m.expectLengthKept();
    }
    EXPECT_GT(swing, 0.2);
    if (mu) {
      EXPECT_GT(turned, 1.5);
      EXPECT_LT(apart[1], 1e-5);
      EXPECT_LT(apart[1], apart[0] / 4.0);
    } else {
      EXPECT_LT(std::max(apart[0], apart[1]), 1e-9);
    }
  }
}

}  // namespace
}  // namespace reeve::test_off_centre_section
