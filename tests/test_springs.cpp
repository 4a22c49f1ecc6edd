// Springs on joint drives: an angle drive with a stiffness is a torsional
// spring, a position drive with one a linear spring (HingeDrive,
// PrismaticDrive), each one compliant XPBD row with XPBD damping (Macklin,
// Müller, Chentanez, MIG 2016, eq. 26). Checked against closed forms with
// both solvers: statics of a bob on a spring (k theta = m g L cos theta),
// the period 2 pi sqrt(I / k) and a bounded energy, critical damping
// without overshoot and the damping ratio from the log decrement, a very
// stiff spring at one substep per frame, a cantilever of five spring
// hinges (a bow limb) under a tip load, a mass on a prismatic spring; the
// trapezoidal rule (Integration::Trapezoidal) keeping an undamped spring's
// energy and period over 100 periods, and its statics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "reeve/engine/world.h"

#include "run_frames.h"

namespace reeve::test_springs {
namespace {

using std::numbers::pi;
constexpr double kG = 9.81;

const char* solverName(SolverKind solver) { return solver == SolverKind::Direct ? "direct" : "gauss-seidel"; }

World makeWorld(SolverKind solver, int substeps, int iterations, double gravity) {
  SolverSettings s;
  s.gravity = Vec3(0.0, -gravity, 0.0);
  s.substeps = substeps;
  s.iterations = iterations;
  s.solver = solver;
  return World(s);
}

BodyId addBody(World& world, const Shape& shape, double mass, const Vec3& position) {
  BodyDef def;
  def.shape = shape;
  def.mass = mass;
  def.position = position;
  return world.addBody(def);
}

using test::run;

// A root of f (derivative df) by Newton's method from x.
template <class F, class DF>
double newton(F f, DF df, double x) {
  for (int i = 0; i < 50; ++i) {
    const double step = f(x) / df(x);
    x -= step;
    if (std::abs(step) < 1e-15) break;
  }
  return x;
}

// Times (s) at which a sampled signal crosses zero upward, linearly
// interpolated between samples (exact to third order: a sine is straight
// at its zeros).
struct UpwardCrossings {
  std::vector<double> times;
  double previous = 0.0, t_previous = 0.0;
  bool started = false;
  void add(double t, double x) {
    if (started && previous < 0.0 && x >= 0.0)
      times.push_back(t_previous + (t - t_previous) * -previous / (x - previous));
    previous = x;
    t_previous = t;
    started = true;
  }
  double period() const { return (times.back() - times.front()) / static_cast<double>(times.size() - 1); }
};

// An angle drive toward `target` rad as a spring of stiffness k and damping c.
HingeDrive spring(double target, double k, double c, double max_torque = 0.0) {
  HingeDrive d;
  d.mode = HingeDrive::Mode::Angle;
  d.target = target;
  d.max_torque = max_torque;
  d.stiffness = k;
  d.damping = c;
  return d;
}

class Springs : public ::testing::TestWithParam<SolverKind> {};

// ------------------------------------------------------------- statics --

// A bob (a sphere of mass m whose centre is L from the hinge: a rigid arm)
// on a torsional spring of stiffness k aimed at the horizontal, under
// gravity. At rest the spring holds the weight's torque,
//   k theta = -m g L cos(theta)   (theta < 0: below the horizontal),
// solved here by Newton; damped critically to come to rest.
struct Bob {
  static constexpr double m = 2.0, L = 0.8, r = 0.05, k = 40.0;
  static constexpr double inertia = m * L * L + 0.4 * m * r * r;  // about the hinge
  World world;
  BodyId body;
  HingeId hinge;
  Bob(SolverKind solver, const HingeDrive& drive, const JointLimit& limit = {}) : world(makeWorld(solver, 10, 2, kG)) {
    body = addBody(world, Shape::sphere(r), m, Vec3(L, 0, 0));
    HingeDef def{body, kWorldBody, Vec3::Zero(), Vec3::UnitZ()};
    def.drive = drive;
    def.limit = limit;
    hinge = world.addHinge(def);
  }
  static double criticalDamping() { return 2.0 * std::sqrt(k * inertia); }
  static double weightTorque(double theta) { return -m * kG * L * std::cos(theta); }  // about +z
};

TEST_P(Springs, BobSettlesWhereStiffnessTimesAngleIsTheWeightsTorque) {
  Bob bob(GetParam(), spring(0.0, Bob::k, Bob::criticalDamping()));
  run(bob.world, 6.0, 1.0 / 60.0, [](double) {});
  const double k = Bob::k, mgL = Bob::m * kG * Bob::L;
  const double expected = newton([&](double t) { return k * t + mgL * std::cos(t); },
                                 [&](double t) { return k - mgL * std::sin(t); }, 0.0);
  const double angle = bob.world.hingeAngle(bob.hinge);
  const double torque = bob.world.hingeDriveTorque(bob.hinge);
  std::printf("[ measured ] %s: bob on a spring rests at %.9f rad vs %.9f (error %.2e rad); drive "
              "torque %.9f vs -k theta %.9f N m (%+.2e relative)\n",
              solverName(GetParam()), angle, expected, angle - expected, torque, -k * expected,
              (torque + k * expected) / (k * expected));
  EXPECT_NEAR(angle, expected, 1e-4);
  EXPECT_NEAR(torque, -k * expected, 1e-4 * k * std::abs(expected));
  // The drive is the only row about the axis: the hinge's torque is its own.
  EXPECT_NEAR(bob.world.hingeWrench(bob.hinge).torque.z(), torque, 1e-6 * std::abs(torque));
}

// max_torque still bounds a spring: asked for k |theta| >> max_torque, the
// drive gives max_torque, and the bob hangs where m g L cos(theta) is that:
// cos(theta) = 1/2 for max_torque = m g L / 2 (linear damping on the bob
// lets it come to rest).
TEST_P(Springs, MaxTorqueBoundsTheSpring) {
  const double tau = 0.5 * Bob::m * kG * Bob::L;
  Bob bob(GetParam(), spring(0.0, Bob::k, 0.0, tau));
  bob.world.body(bob.body).linear_damping = 5.0;
  run(bob.world, 8.0, 1.0 / 60.0, [](double) {});
  const double angle = bob.world.hingeAngle(bob.hinge);
  std::printf("[ measured ] %s: spring at max torque: %.9f rad vs -pi/3, torque %.9f vs %.9f N m\n",
              solverName(GetParam()), angle, bob.world.hingeDriveTorque(bob.hinge), tau);
  EXPECT_NEAR(angle, -pi / 3.0, 1e-4);
  EXPECT_NEAR(bob.world.hingeDriveTorque(bob.hinge), tau, 1e-9 * tau);
}

// A spring too weak for the load (its free rest angle is -0.37 rad) on a
// hinge limited to [-0.2, 0.5] rad: the bob rests on the lower limit, the
// spring pushes with k x 0.2 and the limit with the rest of m g L cos(0.2).
// The direct solver splits the two exactly (the spring's row is compliant,
// so not dependent on the limit's). Gauss-Seidel solves the spring and
// then the limit, each with the hinge's block; the spring's share
// converges by w / (w + alpha~) per sweep (w = 1 / I the row's inverse
// mass, alpha~ = 1 / ((k + c / h) h^2) its compliance): fast here
// (alpha~ = 53 w), slowly where k + c / h >> I / h^2. The bob's rest and
// the hinge's total torque are right either way.
TEST_P(Springs, SpringPressedAgainstALimitRestsOnIt) {
  Bob bob(GetParam(), spring(0.0, Bob::k, Bob::criticalDamping()), JointLimit{true, -0.2, 0.5});
  run(bob.world, 4.0, 1.0 / 60.0, [](double) {});
  const double angle = bob.world.hingeAngle(bob.hinge);
  const double total = bob.world.hingeWrench(bob.hinge).torque.z();
  const double drive = bob.world.hingeDriveTorque(bob.hinge);
  std::printf("[ measured ] %s: spring on a limit: %.9f rad, hinge torque %.6f vs %.6f N m, drive "
              "torque %.6f vs k x 0.2 = %.6f N m\n",
              solverName(GetParam()), angle, total, -Bob::weightTorque(-0.2), drive, 0.2 * Bob::k);
  EXPECT_NEAR(angle, -0.2, 1e-6);
  EXPECT_NEAR(total, -Bob::weightTorque(-0.2), 1e-4 * std::abs(Bob::weightTorque(-0.2)));
  EXPECT_NEAR(drive, 0.2 * Bob::k, (GetParam() == SolverKind::Direct ? 1e-6 : 1e-3) * 0.2 * Bob::k);
}

// ------------------------------------------------------------ dynamics --

// A disc (I about its axle) on a torsional spring of stiffness k, no
// gravity, released at rest theta0 from the spring's target: theta(t) =
// theta0 cos(sqrt(k / I) t) undamped. On a hinge through its centre the
// direct solver makes it a rotor.
struct Disc {
  static constexpr double m = 3.0, r = 0.2, inertia = 0.5 * m * r * r, theta0 = 0.5;
  World world;
  BodyId body;
  HingeId hinge;
  Disc(SolverKind solver, double k, double c, HingeDrive::Integration integration = HingeDrive::Integration::Implicit,
       int substeps = 10)
      : world(makeWorld(solver, substeps, 2, 0.0)) {
    body = addBody(world, Shape::cylinder(r, 0.05), m, Vec3::Zero());
    HingeDrive drive = spring(-theta0, k, c);
    drive.integration = integration;
    hinge = world.addHinge(HingeDef(body, kWorldBody, Vec3::Zero(), Vec3::UnitZ(), 0.0, {}, drive));
  }
  double displacement() const { return world.hingeAngle(hinge) + theta0; }  // from the target
  double omega() const { return world.body(body).omega.z(); }
};

TEST_P(Springs, UndampedSpringSwingsWithPeriodTwoPiSqrtIOverKAndLosesEnergyOnly) {
  const double period = 1.0;
  const double k = Disc::inertia * std::pow(2.0 * pi / period, 2);
  Disc disc(GetParam(), k, 0.0);
  const auto energy = [&] {
    return 0.5 * disc.inertia * disc.omega() * disc.omega() + 0.5 * k * std::pow(disc.displacement(), 2);
  };
  const double e0 = energy();
  double highest = e0;
  UpwardCrossings crossings;
  const double dt = 1.0 / 60.0;
  run(disc.world, 10.0 * period, dt, [&](double t) {
    crossings.add(t, disc.displacement());
    highest = std::max(highest, energy());
  });
  ASSERT_GE(crossings.times.size(), 9u);
  const double measured = crossings.period();
  const double error = (measured - period) / period;
  // Implicit Euler keeps 1 / (1 + (w h)^2) of the energy per substep.
  const double h = dt / 10.0, wh = 2.0 * pi / period * h;
  const double lost = 1.0 - energy() / e0, expected_lost = 1.0 - std::pow(1.0 + wh * wh, -disc.world.time() / h);
  std::printf("[ measured ] %s: spring period %.6f s vs 2 pi sqrt(I/k) = %.6f s (%+.4f %%); energy "
              "at most %+.2e of E0, %.2f %% lost over 10 periods (implicit Euler: %.2f %%)\n",
              solverName(GetParam()), measured, period, 100.0 * error, highest / e0 - 1.0, 100.0 * lost,
              100.0 * expected_lost);
  EXPECT_LT(std::abs(error), 0.005);
  EXPECT_LE(highest, e0 * (1.0 + 1e-3));
  EXPECT_GT(lost, 0.0);
}

// The trapezoidal rule (HingeDrive::Integration::Trapezoidal) on the same
// undamped disc for 100 periods: no drift. The energy at the end of each
// substep ripples by about w h / 2 (0.26 % at 20 substeps of 1/60 s, w = 2
// pi rad/s); counted with the spring's energy at the mid-substep angle,
// 1/2 k ((theta_0 + theta_+) / 2 - target)^2 with the mean velocity over
// the substep, it is what the rule keeps exactly. The period is 2 pi
// sqrt(I / k) slowed by (w h)^2 / 12 (3e-6 here). Implicit Euler on the
// same disc keeps 4 % of its energy.
TEST_P(Springs, TrapezoidalSpringKeepsItsEnergyAndPeriodOver100Periods) {
  const double period = 1.0, dt = 1.0 / 60.0;
  const int substeps = 20;
  const double k = Disc::inertia * std::pow(2.0 * pi / period, 2);
  Disc disc(GetParam(), k, 0.0, HingeDrive::Integration::Trapezoidal, substeps);
  const auto kinetic = [&] { return 0.5 * disc.inertia * disc.omega() * disc.omega(); };
  const auto energy = [&] { return kinetic() + 0.5 * k * std::pow(disc.displacement(), 2); };
  const auto mid_energy = [&] {
    const HingeJoint& j = disc.world.hinge(disc.hinge);
    const double before = hingeAngle(j, disc.world.body(j.a).q_prev, disc.world.body(j.b).q_prev) + disc.theta0;
    return kinetic() + 0.5 * k * std::pow(0.5 * (before + disc.displacement()), 2);
  };
  const double e0 = energy();
  double worst = 0.0, worst_mid = 0.0, mid0 = 0.0;
  UpwardCrossings crossings;
  run(disc.world, 100.0 * period, dt, [&](double t) {
    crossings.add(t, disc.displacement());
    worst = std::max(worst, std::abs(energy() / e0 - 1.0));
    if (mid0 == 0.0) mid0 = mid_energy();
    worst_mid = std::max(worst_mid, std::abs(mid_energy() / mid0 - 1.0));
  });
  ASSERT_GE(crossings.times.size(), 99u);
  const double measured = crossings.period();
  Disc implicit(GetParam(), k, 0.0, HingeDrive::Integration::Implicit, substeps);
  const double implicit_e0 = 0.5 * k * std::pow(implicit.displacement(), 2);
  run(implicit.world, 100.0 * period, dt, [](double) {});
  const double implicit_kept = (0.5 * implicit.inertia * implicit.omega() * implicit.omega() +
                                0.5 * k * std::pow(implicit.displacement(), 2)) /
                               implicit_e0;
  std::printf("[ measured ] %s: trapezoidal spring over 100 periods: energy within %.2e (mid-substep: %.2e), "
              "%+.2e at the end; period %.6f s vs %.6f s (%+.4f %%); implicit Euler keeps %.2e of its energy\n",
              solverName(GetParam()), worst, worst_mid, energy() / e0 - 1.0, measured, period,
              100.0 * (measured - period) / period, implicit_kept);
  EXPECT_LT(worst, 0.005);
  EXPECT_LT(worst_mid, 1e-6);
  EXPECT_NEAR(measured, period, 0.005 * period);
  EXPECT_LT(implicit_kept, 0.1);
}

// A stiff spring at one substep per frame (w h = 6.8): with the direct
// solver the trapezoidal rule stays bounded and keeps the mid-substep
// energy; it runs slow, each substep turning the phase by 2 atan(w h / 2)
// instead of w h, and the angle at a substep's end may swing out to
// sqrt(1 + (w h / 2)^2) of the amplitude (only the mid-substep angle is
// bounded by it). Gauss-Seidel turns bodies by first-order corrections,
// which its two sweeps do not converge on at w h = 6.8 (the disc gains
// 60 times its energy; at w h = 2.3, 13 times): it is held to w h = 0.68
// (ten substeps) here, where its first-order turns leave the energy within
// 0.2 % over 650 periods, no drift.
TEST_P(Springs, TrapezoidalStiffSpringKeepsItsEnergyAtLargeOmegaH) {
  const bool direct = GetParam() == SolverKind::Direct;
  const int substeps = direct ? 1 : 10;
  const double k = 1e4, w = std::sqrt(k / Disc::inertia), h = 1.0 / 60.0 / substeps;
  Disc disc(GetParam(), k, 0.0, HingeDrive::Integration::Trapezoidal, substeps);
  const auto mid_energy = [&] {
    const HingeJoint& j = disc.world.hinge(disc.hinge);
    const double before = hingeAngle(j, disc.world.body(j.a).q_prev, disc.world.body(j.b).q_prev) + disc.theta0;
    return 0.5 * disc.inertia * disc.omega() * disc.omega() + 0.5 * k * std::pow(0.5 * (before + disc.displacement()), 2);
  };
  double first = 0.0, worst = 0.0, largest = 0.0;
  run(disc.world, 10.0, 1.0 / 60.0, [&](double) {
    if (first == 0.0) first = mid_energy();
    worst = std::max(worst, std::abs(mid_energy() / first - 1.0));
    largest = std::max(largest, std::abs(disc.displacement()));
  });
  const double bound = std::sqrt(1.0 + 0.25 * w * h * w * h);
  std::printf("[ measured ] %s: trapezoidal, w h = %.2f, 10 s: mid-substep energy within %.2e, largest swing %.3f "
              "of the start (bound %.3f)\n",
              solverName(GetParam()), w * h, worst, largest / disc.theta0, bound);
  EXPECT_LT(worst, direct ? 1e-6 : 5e-3);
  EXPECT_LT(largest, bound * disc.theta0 * (1.0 + 1e-6));
}

// Statics do not depend on the integration: the bob rests where k theta =
// -m g L cos(theta) with a damped trapezoidal spring too.
TEST_P(Springs, TrapezoidalSpringRestsWhereTheImplicitOneDoes) {
  HingeDrive drive = spring(0.0, Bob::k, Bob::criticalDamping());
  drive.integration = HingeDrive::Integration::Trapezoidal;
  Bob bob(GetParam(), drive);
  run(bob.world, 6.0, 1.0 / 60.0, [](double) {});
  const double k = Bob::k, mgL = Bob::m * kG * Bob::L;
  const double expected = newton([&](double t) { return k * t + mgL * std::cos(t); },
                                 [&](double t) { return k - mgL * std::sin(t); }, 0.0);
  std::printf("[ measured ] %s: trapezoidal bob rests at %.9f rad vs %.9f, torque %.6f vs %.6f N m\n",
              solverName(GetParam()), bob.world.hingeAngle(bob.hinge), expected, bob.world.hingeDriveTorque(bob.hinge),
              -k * expected);
  EXPECT_NEAR(bob.world.hingeAngle(bob.hinge), expected, 1e-4);
  EXPECT_NEAR(bob.world.hingeDriveTorque(bob.hinge), -k * expected, 1e-4 * k * std::abs(expected));
}

// Critical damping c = 2 sqrt(k I): theta0 (1 + w t) e^(-w t), back to the
// target without crossing it.
TEST_P(Springs, CriticallyDampedSpringReturnsWithoutOvershoot) {
  const double k = 4.0 * Disc::inertia;  // w = 2 rad/s
  Disc disc(GetParam(), k, 2.0 * std::sqrt(k * Disc::inertia));
  double lowest = disc.theta0;
  run(disc.world, 6.0, 1.0 / 60.0, [&](double) { lowest = std::min(lowest, disc.displacement()); });
  std::printf("[ measured ] %s: critical damping: lowest %+.3e theta0, after 6 s %.3e theta0 (closed "
              "form %.3e)\n",
              solverName(GetParam()), lowest / disc.theta0, disc.displacement() / disc.theta0, 13.0 * std::exp(-12.0));
  EXPECT_GT(lowest, -1e-3 * disc.theta0);
  EXPECT_LT(std::abs(disc.displacement()), 1e-3 * disc.theta0);
}

// Underdamped, damping ratio zeta = c / (2 sqrt(k I)) = 0.2: released at
// rest, the maxima come every damped period T_d = 2 pi / (w sqrt(1 -
// zeta^2)) and shrink by e^delta, delta = 2 pi zeta / sqrt(1 - zeta^2) (the
// log decrement), so zeta = delta / sqrt(4 pi^2 + delta^2). Implicit Euler
// adds about pi w h of decrement (0.8 % here, w = 2 rad/s, h = 1/600 s).
TEST_P(Springs, UnderdampedSpringsLogDecrementGivesItsDampingRatio) {
  const double k = 4.0 * Disc::inertia, zeta = 0.2;  // w = 2 rad/s
  Disc disc(GetParam(), k, 2.0 * zeta * std::sqrt(k * Disc::inertia));
  const double dt = 1.0 / 60.0;
  std::vector<double> x = {disc.theta0};
  std::vector<double> peaks, peak_times;
  run(disc.world, 10.0, dt, [&](double t) {
    x.push_back(disc.displacement());
    const std::size_t n = x.size();
    if (n >= 3 && x[n - 2] > x[n - 3] && x[n - 2] >= x[n - 1] && x[n - 2] > 0.0) {
      // The parabola through the last three samples, at its vertex.
      const double a = 0.5 * (x[n - 1] - 2.0 * x[n - 2] + x[n - 3]), b = 0.5 * (x[n - 1] - x[n - 3]);
      const double s = -b / (2.0 * a);
      peaks.push_back(x[n - 2] + b * s + a * s * s);
      peak_times.push_back(t - dt + s * dt);
    }
  });
  ASSERT_GE(peaks.size(), 3u);
  const double delta = std::log(disc.theta0 / peaks[2]) / 3.0;
  const double measured = delta / std::sqrt(4.0 * pi * pi + delta * delta);
  const double damped_period = 2.0 * pi / (2.0 * std::sqrt(1.0 - zeta * zeta));
  const double period = (peak_times[2] - peak_times[0]) / 2.0;
  std::printf("[ measured ] %s: log decrement %.6f, damping ratio %.6f vs c / (2 sqrt(k I)) = %.2f "
              "(%+.3f %%); damped period %.6f vs %.6f s (%+.4f %%)\n",
              solverName(GetParam()), delta, measured, zeta, 100.0 * (measured - zeta) / zeta, period,
              damped_period, 100.0 * (period - damped_period) / damped_period);
  EXPECT_NEAR(measured, zeta, 0.02 * zeta);
  EXPECT_NEAR(period, damped_period, 0.005 * damped_period);
}

// ------------------------------------------------------------ extremes --

// A light segment (1e-3 kg m^2 about its hinge at one end) on a spring of
// 1e4 and 1e6 N m/rad, released 0.3 rad from its target at one substep of
// 1/60 s (w h = 53 and 527): implicit, it neither explodes nor rings, and
// rests where the spring holds its weight, k (theta - target) = -m g d
// cos(theta).
TEST_P(Springs, VeryStiffSpringOnALightSegmentAtOneSubstepSettlesAtItsTarget) {
  const double length = 0.1, thickness = 0.02, inertia = 1e-3, target = -0.3;
  const double m = inertia / (length * length / 3.0 + thickness * thickness / 12.0);
  for (const double k : {1e4, 1e6}) {
    World world = makeWorld(GetParam(), 1, 2, kG);
    const BodyId segment = addBody(world, Shape::box(Vec3(0.5 * length, 0.5 * thickness, 0.5 * thickness)), m,
                                   Vec3(0.5 * length, 0, 0));
    const HingeId hinge =
        world.addHinge(HingeDef(segment, kWorldBody, Vec3::Zero(), Vec3::UnitZ(), 0.0, {}, spring(target, k, 0.0)));
    double fastest = 0.0;
    bool finite = true;
    run(world, 2.0, 1.0 / 60.0, [&](double) {
      finite = finite && !world.firstNonFiniteBody();
      fastest = std::max(fastest, world.body(segment).omega.norm());
    });
    ASSERT_TRUE(finite) << "k = " << k;
    const double mgd = m * kG * 0.5 * length;
    const double expected = newton([&](double t) { return k * (t - target) + mgd * std::cos(t); },
                                   [&](double t) { return k - mgd * std::sin(t); }, target);
    const double angle = world.hingeAngle(hinge);
    std::printf("[ measured ] %s: k = %.0e N m/rad, I = 1e-3 kg m^2, 1 substep: rests at %+.3e rad from the "
                "static angle (sag %.2e rad), fastest %.1f rad/s, torque %+.3e relative\n",
                solverName(GetParam()), k, angle - expected, expected - target, fastest,
                (world.hingeDriveTorque(hinge) + k * (expected - target)) / (k * (expected - target)));
    EXPECT_NEAR(angle, expected, 1e-6) << "k = " << k;
    // Released at rest 0.3 rad out, it can reach at most sqrt(k / I) 0.3 rad/s.
    EXPECT_LT(fastest, 0.3 * std::sqrt(k / inertia)) << "k = " << k;
    EXPECT_NEAR(world.hingeDriveTorque(hinge), -k * (expected - target), 1e-4 * k * std::abs(expected - target));
  }
}

// A cantilever like a bow limb: five segments of length l in a row along
// +x from a wall, each hinged to the previous one (the first to the world)
// on a torsional spring of stiffness k aimed straight, a load M welded at
// the tip. For small angles each hinge bends by its moment over k,
//   theta_i = -g (M (x_tip - x_i) + sum_{j >= i} m (x_j - x_i)) / k,
// x_i the hinge and x_j the segments' centres, and the tip drops by
// sum_i theta_i (x_tip - x_i).
// Light segments under a heavy load are what Gauss-Seidel converges on
// slowly (DESIGN.md): at 10 x 2 it drops the tip 12 times as far (0.14 m),
// about as far as rigid drives, which should hold it level, let it drop
// (0.13 m). It needs 100 x 5 here, and XPBD damping makes each spring row
// stiffer by c / h within a substep, which it converges on slower still
// (c = 1 N m s/rad: 10 % too far at 100 x 10), so with Gauss-Seidel the
// bodies' own velocity damping brings the limb to rest instead.
TEST_P(Springs, CantileverOfSpringHingesBendsByMomentOverStiffness) {
  const bool direct = GetParam() == SolverKind::Direct;
  const int n = 5;
  const double l = 0.1, m = 0.05, load = 1.0, k = 500.0, c = direct ? 30.0 : 0.0;
  World world = makeWorld(GetParam(), direct ? 10 : 100, direct ? 2 : 5, kG);
  std::vector<BodyId> segments;
  std::vector<HingeId> hinges;
  for (int i = 0; i < n; ++i) {
    segments.push_back(addBody(world, Shape::box(Vec3(0.5 * l, 0.01, 0.01)), m, Vec3((i + 0.5) * l, 0, 0)));
    if (!direct) world.body(segments[i]).angular_damping = 20.0;
    const BodyId previous = i == 0 ? kWorldBody : segments[i - 1];
    hinges.push_back(world.addHinge(
        HingeDef(segments[i], previous, Vec3(i * l, 0, 0), Vec3::UnitZ(), 0.0, {}, spring(0.0, k, c))));
  }
  const double tip = n * l;
  const BodyId weight = addBody(world, Shape::sphere(0.02), load, Vec3(tip, 0, 0));
  if (!direct) world.body(weight).linear_damping = 20.0;
  FixedDef weld;
  weld.body = weight;
  weld.other = segments.back();
  weld.anchor = Vec3(tip, 0, 0);
  world.addFixed(weld);
  run(world, 1.5, 1.0 / 60.0, [](double) {});

  double expected_drop = 0.0, worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x_i = i * l;
    double moment = -kG * load * (tip - x_i);
    for (int j = i; j < n; ++j) moment -= kG * m * ((j + 0.5) * l - x_i);
    const double expected = moment / k, angle = world.hingeAngle(hinges[i]);
    worst = std::max(worst, std::abs(angle - expected) / std::abs(expected));
    EXPECT_NEAR(angle, expected, 0.005 * std::abs(expected)) << "hinge " << i;
    expected_drop += expected * (tip - x_i);
  }
  const double drop = world.body(weight).x.y();
  std::printf("[ measured ] %s: cantilever of 5 spring hinges: tip at %.7f m vs %.7f m small-angle "
              "(%+.3f %%), worst hinge angle %.3f %% off moment / k\n",
              solverName(GetParam()), drop, expected_drop, 100.0 * (drop - expected_drop) / expected_drop,
              100.0 * worst);
  EXPECT_NEAR(drop, expected_drop, 0.005 * std::abs(expected_drop));
}

// ------------------------------------------------------------ prismatic --

// A mass m on a vertical rail on a linear spring of stiffness k aimed at
// slide 0: at rest at -m g / k, and, undamped, released at rest from 0,
// it oscillates about there at w = sqrt(k / m).
struct Slider {
  static constexpr double m = 2.0, k = 500.0;
  World world;
  BodyId body;
  PrismaticId joint;
  Slider(SolverKind solver, double c) : world(makeWorld(solver, 10, 2, kG)) {
    body = addBody(world, Shape::box(Vec3(0.1, 0.1, 0.1)), m, Vec3::Zero());
    PrismaticDef def;
    def.body = body;
    def.axis = Vec3::UnitY();
    def.drive.mode = PrismaticDrive::Mode::Position;
    def.drive.stiffness = k;
    def.drive.damping = c;
    joint = world.addPrismatic(def);
  }
  static constexpr double rest = -m * kG / k;
};

TEST_P(Springs, MassOnAPrismaticSpringSettlesAtWeightOverStiffness) {
  Slider slider(GetParam(), 2.0 * std::sqrt(Slider::k * Slider::m));
  run(slider.world, 3.0, 1.0 / 60.0, [](double) {});
  const double slide = slider.world.prismaticSlide(slider.joint);
  const double force = slider.world.prismaticDriveForce(slider.joint);
  std::printf("[ measured ] %s: prismatic spring rests at %.9f m vs -m g / k = %.9f m (%+.2e m), force "
              "%.6f vs m g %.6f N\n",
              solverName(GetParam()), slide, Slider::rest, slide - Slider::rest, force, slider.m * kG);
  EXPECT_NEAR(slide, Slider::rest, 1e-6);
  EXPECT_NEAR(force, slider.m * kG, 1e-4 * slider.m * kG);
}

// The same as a trapezoidal spring: no drift over 100 periods. The ripple
// at the substep's end is w h / 2 = 1.3 % at 10 substeps (w = 15.8
// rad/s); with the spring's energy at the mid-substep slide the energy is
// exact. The period within (w h)^2 / 12.
TEST_P(Springs, TrapezoidalPrismaticSpringKeepsItsEnergyAndPeriod) {
  Slider slider(GetParam(), 0.0);
  slider.world.prismatic(slider.joint).drive.integration = PrismaticDrive::Integration::Trapezoidal;
  const double period = 2.0 * pi * std::sqrt(slider.m / slider.k);
  // About the rest point, gravity included: 1/2 m v^2 + 1/2 k (s - rest)^2 + const.
  const auto energy = [&](double slide) {
    const double v = slider.world.body(slider.body).v.y();
    return 0.5 * slider.m * v * v + 0.5 * slider.k * std::pow(slide - Slider::rest, 2);
  };
  const auto end = [&] { return energy(slider.world.prismaticSlide(slider.joint)); };
  const auto mid = [&] {
    const BodyState& b = slider.world.body(slider.body);
    const PrismaticJoint& j = slider.world.prismatic(slider.joint);
    const BodyState& w = slider.world.body(kWorldBody);
    return energy(0.5 * (prismaticSlide(j, b.x_prev, b.q_prev, w.x, w.q) + slider.world.prismaticSlide(slider.joint)));
  };
  const double e0 = end();
  double worst = 0.0, worst_mid = 0.0, mid0 = 0.0;
  UpwardCrossings crossings;
  run(slider.world, 100.0 * period, 1.0 / 60.0, [&](double t) {
    crossings.add(t, slider.world.prismaticSlide(slider.joint) - Slider::rest);
    worst = std::max(worst, std::abs(end() / e0 - 1.0));
    if (mid0 == 0.0) mid0 = mid();
    worst_mid = std::max(worst_mid, std::abs(mid() / mid0 - 1.0));
  });
  const double measured = crossings.period();
  std::printf("[ measured ] %s: trapezoidal prismatic spring over 100 periods: energy within %.2e (mid-substep: "
              "%.2e), %+.2e at the end; period %.6f s vs %.6f s (%+.4f %%)\n",
              solverName(GetParam()), worst, worst_mid, end() / e0 - 1.0, measured, period,
              100.0 * (measured - period) / period);
  EXPECT_LT(worst, 0.015);
  EXPECT_LT(worst_mid, 1e-6);
  EXPECT_NEAR(measured, period, 0.005 * period);
}

TEST_P(Springs, MassOnAPrismaticSpringOscillatesAtSqrtKOverM) {
  Slider slider(GetParam(), 0.0);
  const double period = 2.0 * pi * std::sqrt(slider.m / slider.k);
  UpwardCrossings crossings;
  run(slider.world, 10.0 * period, 1.0 / 60.0,
      [&](double t) { crossings.add(t, slider.world.prismaticSlide(slider.joint) - Slider::rest); });
  ASSERT_GE(crossings.times.size(), 9u);
  const double measured = crossings.period();
  std::printf("[ measured ] %s: prismatic spring period %.6f s vs 2 pi sqrt(m/k) = %.6f s (%+.4f %%)\n",
              solverName(GetParam()), measured, period, 100.0 * (measured - period) / period);
  EXPECT_NEAR(measured, period, 0.005 * period);
}

// ----------------------------------------------------------- definitions --

TEST(SpringDefinitions, AddHingeAndAddPrismaticRejectBadSprings) {
  World world;
  const BodyId b = addBody(world, Shape::box(Vec3(0.1, 0.1, 0.1)), 1.0, Vec3::Zero());
  HingeDef hinge{b, kWorldBody, Vec3::Zero(), Vec3::UnitZ()};
  const double inf = HUGE_VAL;
  const std::vector<std::pair<double, double>> bad = {{-1.0, 0.0}, {std::nan(""), 0.0}, {inf, 0.0},
                                                      {10.0, -1.0}, {10.0, inf},        {0.0, 1.0}};
  for (const auto& [k, c] : bad) {
    hinge.drive = spring(0.1, k, c);
    EXPECT_THROW(world.addHinge(hinge), std::invalid_argument) << k << " " << c;
  }
  hinge.drive = spring(0.1, 10.0, 1.0);
  hinge.drive.mode = HingeDrive::Mode::Velocity;  // a spring needs an angle drive
  EXPECT_THROW(world.addHinge(hinge), std::invalid_argument);
  hinge.drive.stiffness = 0.0;  // a velocity drive's damping alone is a damper
  EXPECT_NO_THROW(world.addHinge(hinge));
  hinge.drive = spring(0.1, 10.0, 1.0);
  EXPECT_NO_THROW(world.addHinge(hinge));

  PrismaticDef rail;
  rail.body = b;
  rail.drive.mode = PrismaticDrive::Mode::Velocity;
  rail.drive.stiffness = 10.0;
  EXPECT_THROW(world.addPrismatic(rail), std::invalid_argument);
  rail.drive.mode = PrismaticDrive::Mode::Position;
  rail.drive.damping = -1.0;
  EXPECT_THROW(world.addPrismatic(rail), std::invalid_argument);
  rail.drive.damping = 1.0;
  EXPECT_NO_THROW(world.addPrismatic(rail));

  // The trapezoidal rule is for springs; a drive's end time is > 0 s.
  hinge.drive = spring(0.1, 0.0, 0.0);
  hinge.drive.integration = HingeDrive::Integration::Trapezoidal;
  EXPECT_THROW(world.addHinge(hinge), std::invalid_argument);
  hinge.drive.stiffness = 10.0;
  EXPECT_NO_THROW(world.addHinge(hinge));
  for (const double until : {0.0, -1.0, std::nan("")}) {
    hinge.drive.until = until;
    EXPECT_THROW(world.addHinge(hinge), std::invalid_argument) << until;
    rail.drive.until = until;
    EXPECT_THROW(world.addPrismatic(rail), std::invalid_argument) << until;
  }
  rail.drive.until = 1.0;
  rail.drive.stiffness = 0.0;
  rail.drive.damping = 0.0;
  rail.drive.integration = PrismaticDrive::Integration::Trapezoidal;
  EXPECT_THROW(world.addPrismatic(rail), std::invalid_argument);
}

// ------------------------------------------------------------- dampers --

// A velocity drive with a damping c is a damper toward its target speed:
// torque c (w_t - w) on a disc of inertia I (a rotor: its hinge through its
// centre), implicit, so each substep h keeps 1 / (1 + c h / I) of the
// difference: w_n = w_t + (w_0 - w_t) (1 + c h / I)^-n, to rounding, with
// both solvers; a carriage on a rail with a damper (force c (v_t - v))
// alike with its mass. Target 0 is MuJoCo's joint damping.
TEST_P(Springs, AVelocityDriveWithDampingIsAnImplicitDamperTowardItsTarget) {
  constexpr double m = 3.0, r = 0.2, c = 0.4, h = 1.0 / 600.0;
  for (const double target : {0.0, 2.0}) {
    World world = makeWorld(GetParam(), 10, 2, 0.0);
    const BodyId disc = addBody(world, Shape::cylinder(r, 0.05), m, Vec3::Zero());
    world.body(disc).omega = Vec3(0, 0, 10.0);
    HingeDef hinge{disc, kWorldBody, Vec3::Zero(), Vec3::UnitZ()};
    hinge.drive.mode = HingeDrive::Mode::Velocity;
    hinge.drive.target = target;
    hinge.drive.damping = c;
    world.addHinge(hinge);
    const BodyId cart = addBody(world, Shape::box(Vec3(0.1, 0.1, 0.1)), m, Vec3(0, -1, 0));
    world.body(cart).v = Vec3(10.0, 0, 0);
    PrismaticDef rail;
    rail.body = cart;
    rail.anchor = Vec3(0, -1, 0);
    rail.axis = Vec3::UnitX();
    rail.drive.mode = PrismaticDrive::Mode::Velocity;
    rail.drive.target = target;
    rail.drive.damping = c;
    world.addPrismatic(rail);
    const int frames = 60;
    for (int f = 0; f < frames; ++f) world.step(10 * h);
    const int n = 10 * frames;
    const double I = 0.5 * m * r * r;
    const double w = target + (10.0 - target) * std::pow(1.0 + c * h / I, -n);
    const double v = target + (10.0 - target) * std::pow(1.0 + c * h / m, -n);
    // Rounding over 600 substeps: 2e-12 of the speed here.
    EXPECT_NEAR(world.body(disc).omega.z(), w, 1e-10 * 10.0) << solverName(GetParam()) << " target " << target;
    EXPECT_NEAR(world.body(cart).v.x(), v, 1e-10 * 10.0) << solverName(GetParam()) << " target " << target;
    // The closed form of the continuous damper, for scale: 1 % away here.
    EXPECT_GT(std::abs(w - (target + (10.0 - target) * std::exp(-c * n * h / I))), 1e-4);
  }
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, Springs, ::testing::Values(SolverKind::Direct, SolverKind::GaussSeidel),
                         [](const ::testing::TestParamInfo<SolverKind>& info) {
                           return std::string(info.param == SolverKind::Direct ? "Direct" : "GaussSeidel");
                         });

}  // namespace
}  // namespace reeve::test_springs
