// Where the direct solver's iterations start (DirectSolver::startPoint): a
// body the rows held up against gravity in the last substep starts the
// next held up by the same, at most its weight. The start changes where
// Newton's iterations begin, never what they converge to: a load at rest
// is met in one solve a substep, and a load its cables let go of falls
// freely from the substep they let go in.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "reeve/engine/world.h"

namespace reeve::test_start_point {
namespace {

constexpr double kG = 9.81;
constexpr double kFrame = 1.0 / 60.0;

struct Budget {
  int substeps, iterations;
};
const Budget kBudgets[] = {{1, 20}, {10, 2}, {4, 5}};

std::string name(const Budget& b, double mass) {
  char text[64];
  std::snprintf(text, sizeof text, "%d x %d, %g kg", b.substeps, b.iterations, mass);
  return text;
}

// A 0.2 m box of `mass` kg hung by two rigid spans of 3 cm from static
// points to its top corners, each 0.5 rad out from the vertical: a 2.7 mm
// fall (g h^2 at 1 x 20) turns each span by 0.04 rad.
struct VHung {
  World world;
  BodyId box = 0;
  DistanceId left = 0, right = 0;

  /// From static points, or from a kinematic bar moved along `motion`.
  VHung(const Budget& b, double mass, std::vector<MotionKeyframe> motion = {}) : world(settings(b)) {
    if (!motion.empty()) {
      BodyDef bar;  // small: the box's top is 2.6 cm below it
      bar.shape = Shape::box(Vec3::Constant(0.001));
      bar.motion = std::move(motion);
      anchor = world.addBody(bar);
    }
    BodyDef def;
    def.shape = Shape::box(Vec3::Constant(0.1));
    def.mass = mass;
    def.position = Vec3(0.0, -0.1 - kSpan * std::cos(kTilt), 0.0);
    box = world.addBody(def);
    left = world.addDistance(span(Vec3(-0.1 - kSpan * std::sin(kTilt), 0.0, 0.0), Vec3(-0.1, 0.1, 0.0)));
    right = world.addDistance(span(Vec3(0.1 + kSpan * std::sin(kTilt), 0.0, 0.0), Vec3(0.1, 0.1, 0.0)));
  }
  BodyId anchor = kWorldBody;

  /// From a static point on the right, and on the left from the tip of a
  /// 0.2 m, 1 kg lever hinged to the world at its far end and held level
  /// by its lower limit (the load presses it there), with or without a
  /// rigid velocity drive turning it down into that limit (a winch stalled
  /// on its stop, as servin.json's drums end).
  VHung(const Budget& b, double mass, bool driven) : world(settings(b)) {
    BodyDef def;
    def.shape = Shape::box(Vec3::Constant(0.1));
    def.mass = mass;
    def.position = Vec3(0.0, -0.1 - kSpan * std::cos(kTilt), 0.0);
    box = world.addBody(def);
    const Vec3 tip(-0.1 - kSpan * std::sin(kTilt), 0.0, 0.0), pivot = tip - Vec3(kLever, 0.0, 0.0);
    BodyDef bar;
    bar.shape = Shape::box(Vec3(0.5 * kLever, 0.005, 0.005));
    bar.mass = 1.0;
    bar.position = pivot + Vec3(0.5 * kLever, 0.0, 0.0);
    lever = world.addBody(bar);
    HingeDrive drive;
    if (driven) {
      drive.mode = HingeDrive::Mode::Velocity;
      drive.target = -1.0;  // rad/s about +z: the tip down
    }
    hinge = world.addHinge(HingeDef(lever, kWorldBody, pivot, Vec3::UnitZ(), 0.0, JointLimit{true, 0.0, 1.0}, drive));
    anchor = lever;
    left = world.addDistance(span(Vec3(0.5 * kLever, 0.0, 0.0), Vec3(-0.1, 0.1, 0.0)));
    anchor = kWorldBody;
    right = world.addDistance(span(Vec3(0.1 + kSpan * std::sin(kTilt), 0.0, 0.0), Vec3(0.1, 0.1, 0.0)));
  }
  BodyId lever = kWorldBody;
  HingeId hinge = 0;

  static constexpr double kLever = 0.2;  // m
  static constexpr double kSpan = 0.03;  // m
  static constexpr double kTilt = 0.5;   // rad, each span from the vertical, outwards

  static SolverSettings settings(const Budget& b) {
    SolverSettings s;
    s.substeps = b.substeps;
    s.iterations = b.iterations;
    s.gravity = Vec3(0.0, -kG, 0.0);
    return s;
  }
  DistanceConstraint span(const Vec3& top, const Vec3& corner) const {
    DistanceConstraint c;
    c.a = anchor;
    c.local_a = top;
    c.b = box;
    c.local_b = corner;
    c.rest_length = kSpan;
    return c;
  }
  double y() const { return world.body(box).x.y(); }
};

// The V held for 30 frames, then both spans lengthened by 1 m: the
// largest distance (m) over the next 20 frames between the box and
// semi-implicit Euler's free fall from where it was let go, y_n = y_0 -
// g h^2 n (n + 1) / 2 (a start lifted and not taken back is g h^2 off).
double offFreeFallWhenLetGo(VHung& v, const Budget& b) {
  for (int f = 0; f < 30; ++f) v.world.step(kFrame);
  v.world.distance(v.left).rest_length += 1.0;
  v.world.distance(v.right).rest_length += 1.0;
  const double y0 = v.y(), h = kFrame / b.substeps;
  double worst = 0.0;
  for (int f = 1; f <= 20; ++f) {
    v.world.step(kFrame);
    const double n = f * b.substeps;
    worst = std::max(worst, std::abs(v.y() - (y0 - kG * h * h * n * (n + 1.0) / 2.0)));
  }
  return worst;
}

TEST(StartPoint, ALoadAtRestIsMetInOneSolveASubstepAtAnyMass) {
  // Started at x~ each substep, the box has fallen g h^2 and its spans
  // turned: the first solve, linearized there, misses the balance by the
  // turn, and Newton's residual takes a second solve (and a third at 1 x
  // 20). Started where the last substep held it, one solve meets the rows
  // and the residual. The tension is each span's share of m g, whatever
  // the mass.
  for (const Budget& b : kBudgets)
    for (const double mass : {1e-6, 1.0, 1e6}) {
      SCOPED_TRACE(name(b, mass));
      VHung v(b, mass);
      const double y0 = v.y();
      int most = 0;
      for (int f = 0; f < 60; ++f) {
        v.world.step(kFrame);
        if (f >= 1) most = std::max(most, v.world.lastStepIterations());
      }
      std::printf("[ measured ] %s: at most %d solves a frame at rest, sag %.1e m\n", name(b, mass).c_str(), most,
                  y0 - v.y());
      EXPECT_EQ(most, b.substeps);
      EXPECT_NEAR(v.y(), y0, 1e-12);
      const double share = mass * kG / (2.0 * std::cos(VHung::kTilt));
      EXPECT_NEAR(v.world.tension(v.left), share, 1e-9 * share);
      EXPECT_NEAR(v.world.tension(v.right), share, 1e-9 * share);
    }
}

TEST(StartPoint, ALoadHungFromALeverOnItsStopIsMetInOneSolveASubstepAtAnyMass) {
  // The left span hangs from a lever that the load presses onto its stop.
  // A stop that pushed kept the whole island at x~ (a body resting on one
  // would start exactly at it, where rounding decides whether it pushes:
  // DirectSolver::startPoint): at rest 11 solves a frame at 1 x 20, 8 at
  // 4 x 5, the budget's 20 at 10 x 2 and under the 1e6 kg load. The lever
  // turns nothing, and the lift leaves its stop's angle where it was: the
  // island is lifted, one solve a substep. The first substep (not lifted)
  // leaves the V, free to swing on its spans, swinging by rounding (1e-9
  // m, 1e-7 of the tension), which the heaviest load takes 20 frames to
  // lose (up to 5 solves a frame): counted from 0.5 s on. The lever stays
  // on its stop, the load in place, each span pulls its share of m g.
  for (const bool driven : {false, true})
    for (const Budget& b : kBudgets)
      for (const double mass : {1e-6, 1.0, 1e6}) {
        SCOPED_TRACE(name(b, mass) + (driven ? ", driven into its stop" : ""));
        VHung v(b, mass, driven);
        const double y0 = v.y();
        int most = 0;
        for (int f = 0; f < 60; ++f) {
          v.world.step(kFrame);
          if (f >= 30) most = std::max(most, v.world.lastStepIterations());
        }
        std::printf("[ measured ] %s%s: at most %d solves a frame at rest\n", name(b, mass).c_str(),
                    driven ? ", driven" : "", most);
        EXPECT_EQ(most, b.substeps);
        EXPECT_NEAR(v.y(), y0, 1e-12);
        EXPECT_NEAR(v.world.hingeAngle(v.hinge), 0.0, 1e-12);
        const double share = mass * kG / (2.0 * std::cos(VHung::kTilt));
        EXPECT_NEAR(v.world.tension(v.left), share, 1e-6 * share);
        EXPECT_NEAR(v.world.tension(v.right), share, 1e-6 * share);
      }
}

TEST(StartPoint, ALoadLetGoFallsFreelyFromTheSubstepItIsLetGoIn) {
  // The box held at rest, then both spans lengthened by 1 m: the start
  // lifts it by the last substep's hold, g h^2, and the first solve must
  // take that back (Newton's residual M (x - x~), with no row to hold it):
  // from the release on the box follows semi-implicit Euler's free fall,
  // y_n = y_0 - g h^2 n (n + 1) / 2, exactly, at any mass.
  for (const Budget& b : kBudgets)
    for (const double mass : {1e-6, 1.0, 1e6}) {
      SCOPED_TRACE(name(b, mass));
      VHung v(b, mass);
      const double worst = offFreeFallWhenLetGo(v, b);
      EXPECT_LT(worst, 1e-12) << "off free fall by " << worst << " m";
      EXPECT_EQ(v.world.tension(v.left), 0.0);
    }
}

TEST(StartPoint, ALoadLetGoFromALeverOnItsStopFallsFreelyAndTheLeverStaysOnIt) {
  // Turned round: the load hung from the lever (above) let go. The island
  // starts lifted (its stop's angle does not move with the lift), and the
  // first solve must take the load's lift back: from the release on it
  // follows semi-implicit Euler's free fall, y_n = y_0 - g h^2 n (n + 1) /
  // 2, at any mass, driven or not: to 1e-11 m over its 0.55 m fall (1.8e-12
  // measured; the V swung by rounding before the release), where a lift
  // kept would be off by g h^2 (1.7e-4 to 2.7e-3 m). The lever, its own
  // weight on its stop, stays there.
  for (const bool driven : {false, true})
    for (const Budget& b : kBudgets)
      for (const double mass : {1e-6, 1.0, 1e6}) {
        SCOPED_TRACE(name(b, mass) + (driven ? ", driven into its stop" : ""));
        VHung v(b, mass, driven);
        const double worst = offFreeFallWhenLetGo(v, b);
        EXPECT_LT(worst, 1e-11) << "off free fall by " << worst << " m";
        EXPECT_EQ(v.world.tension(v.left), 0.0);
        EXPECT_NEAR(v.world.hingeAngle(v.hinge), 0.0, 1e-12);
      }
}

TEST(StartPoint, ALoadCarriedByAnAcceleratingAnchorFollowsItAtAnyMass) {
  // The V hung from a kinematic bar that accelerates from rest at a for
  // 0.5 s. Hoisted (a = +2 g) the spans hold the load up by 3 g, and the
  // start, at most g h^2 up, is short of the answer: the solve must make
  // up the rest. Lowered at a = -g / 2 the start lifts by what held the
  // load (g / 2). Lowered at a = -2 g the spans go slack at once: the load
  // falls freely (for 3 frames: the bar then reaches the box). Rigid
  // spans: a taut load keeps its place under
  // the bar to 1e-9 m, each span's tension its share of m (g + a), which
  // the start from x~ missed by 1.6e-5 m g at 4 x 5.
  constexpr double kSeconds = 0.5;
  for (const Budget& b : kBudgets)
    for (const double mass : {1e-6, 1.0, 1e6})
      for (const double a : {2.0 * kG, -0.5 * kG, -2.0 * kG}) {
        SCOPED_TRACE(name(b, mass) + ", bar at " + std::to_string(a) + " m/s^2");
        VHung v(b, mass, {{0.0, Vec3::Zero(), Vec3::Zero()}, {kSeconds, Vec3(0.0, a * kSeconds, 0.0), Vec3::Zero()}});
        const double below = v.world.body(v.anchor).x.y() - v.y();
        const double h = kFrame / b.substeps;
        const int frames = a > -kG ? 30 : 3;
        for (int f = 1; f <= frames; ++f) {
          v.world.step(kFrame);
          const double n = f * b.substeps;
          if (a > -kG) {
            ASSERT_NEAR(v.world.body(v.anchor).x.y() - v.y(), below, 1e-9) << "frame " << f;
          } else {  // from rest at the top: y_n = y_0 - g h^2 n (n + 1) / 2
            ASSERT_NEAR(v.y(), -0.1 - VHung::kSpan * std::cos(VHung::kTilt) - kG * h * h * n * (n + 1.0) / 2.0, 1e-12)
                << "frame " << f;
          }
        }
        const double share = a > -kG ? mass * (kG + a) / (2.0 * std::cos(VHung::kTilt)) : 0.0;
        // To the solve's stop (Newton's residual): 7e-6 m g at most.
        EXPECT_NEAR(v.world.tension(v.left), share, 1e-5 * mass * kG);
        EXPECT_NEAR(v.world.tension(v.right), share, 1e-5 * mass * kG);
      }
}

}  // namespace
}  // namespace reeve::test_start_point
