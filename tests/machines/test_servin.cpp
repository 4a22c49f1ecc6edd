// scenes/servin.json, the paper's Fig. 13 (after Servin et al. 2011): a
// ceiling rig lowers a plate on V-shaped cables and a heavy cube until both
// land. Checked against statics: the forces on every hanging body at the
// start and after landing, the ground's share from the contacts, and the
// cable's length through every winch turn.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "reeve/cable/cable.h"
#include "scene_fixture.h"

namespace reeve::test_servin {
namespace {

struct Budget {
  int substeps, iterations;
};
const Budget kBudgets[] = {{10, 2}, {1, 10}};  // the scene's; the paper's Table 1

Scene load(const Budget b) { return test::scene("servin", b.substeps, b.iterations); }

double gravity(const Scene& s) { return -s.world->settings().gravity.y(); }
double weight(const Scene& s, const char* body) { return s.world->bodyMass(test::body(s, body)) * gravity(s); }

// Unit vector along joint j of cable c, from its start to its end.
Vec3 along(const Scene& s, int c, int j) {
  return (s.cables->endPoint(c, j) - s.cables->startPoint(c, j)).normalized();
}
// Force (N) of joint j of cable c on the body at its start (pulled toward
// the end) and on the body at its end: tension along the straight span.
Vec3 pullOnStart(const Scene& s, int c, int j) { return s.cables->tension(c, j) * along(s, c, j); }
Vec3 pullOnEnd(const Scene& s, int c, int j) { return -pullOnStart(s, c, j); }

// A V runs front corner -> sheave -> back corner of the plate: its force on
// the plate; it pulls its sheave by the opposite.
Vec3 vOnPlate(const Scene& s, int v) { return pullOnStart(s, v, 0) + pullOnEnd(s, v, 1); }

// Hanger joint 0 leaves the pulley's block (left) or the ceiling (right);
// joint 3 arrives at the sheave's block. The hoist's joint 0 arrives at the
// pulley and joint 1 leaves it.
Vec3 hangerOnSheave(const Scene& s, int hanger) { return pullOnEnd(s, hanger, 3); }
Vec3 hoistOnPulley(const Scene& s, int hoist) { return pullOnEnd(s, hoist, 0) + pullOnStart(s, hoist, 1); }

// Radius (m), drive speed (rad/s) and limit (rad) of a winch drum's hinge.
struct Drum {
  double radius, speed, lower, upper;
  BodyId body;
  int hinge;
};
Drum drum(const Scene& s, const char* name) {
  const BodyId b = test::body(s, name);
  for (int h = 0; h < static_cast<int>(s.world->hinges().size()); ++h) {
    const HingeJoint& j = s.world->hinge(h);
    if (j.a == b) return {s.world->bodyDef(b).shape.radius, j.drive.target, j.limit.lower, j.limit.upper, b, h};
  }
  ADD_FAILURE() << "no hinge on " << name;
  return {};
}

// Ground force (N, up) on a body: its contacts' normal corrections / h^2.
double groundForce(const Scene& s, BodyId body) {
  double f = 0.0;
  for (const Contact& c : s.world->contacts())
    if (c.a == kWorldBody && c.b == body) f += contactNormalForce(c, s.world->lastSubstep()) * c.normal.y();
  return f;
}

double relative(double got, double want) { return std::abs(got / want - 1.0); }

TEST(Servin, StartsInEquilibriumWithTheWinchesPayingOutSteadily) {
  // The winches pay out at constant speed from t = 0 and every body starts
  // at the speed that implies, so nothing accelerates: the cable forces on
  // each hanging body balance its weight as in statics. The plate is level
  // with its Vs at equal arms from its centre, so each V carries half of it.
  for (const Budget b : kBudgets) {
    Scene s = load(b);
    SCOPED_TRACE(testing::Message() << b.substeps << " x " << b.iterations);
    const int hoist = test::cable(s, "hoist"), hanger_l = test::cable(s, "hanger_l"), hanger_r = test::cable(s, "hanger_r");
    const int v_l = test::cable(s, "v_l"), v_r = test::cable(s, "v_r"), cube_line = test::cable(s, "cube_line");
    for (int f = 0; f < 3; ++f) test::frame(s);

    const double plate = weight(s, "plate"), cube = weight(s, "cube");
    const Vec3 left = vOnPlate(s, v_l), right = vOnPlate(s, v_r);
    const double up_cube = pullOnEnd(s, cube_line, 1).y();
    // Each sheave and its block: the hanger holds their weight plus the V.
    const double sheave_l = weight(s, "sheave_l") + weight(s, "block_l") + left.y();
    const double sheave_r = weight(s, "sheave_r") + weight(s, "block_r") + right.y();
    // The moving pulley and its block hold the left hanger.
    const double pulley = weight(s, "pulley") + weight(s, "block_p") - pullOnStart(s, hanger_l, 0).y();
    std::printf("[ measured ] %d x %d: plate %.2e (left %.2e, right %.2e, sideways %.2e N), cube %.2e, "
                "sheaves %.2e %.2e, pulley %.2e\n",
                b.substeps, b.iterations, relative(left.y() + right.y(), plate), relative(left.y(), plate / 2),
                relative(right.y(), plate / 2), std::hypot((left + right).x(), (left + right).z()),
                relative(up_cube, cube), relative(hangerOnSheave(s, hanger_l).y(), sheave_l),
                relative(hangerOnSheave(s, hanger_r).y(), sheave_r), relative(hoistOnPulley(s, hoist).y(), pulley));
    EXPECT_NEAR(left.y() + right.y(), plate, 1e-3 * plate);
    EXPECT_NEAR(left.y(), plate / 2, 1e-3 * plate / 2);
    EXPECT_NEAR(right.y(), plate / 2, 1e-3 * plate / 2);
    EXPECT_NEAR((left + right).x(), 0.0, 1e-3 * plate);
    EXPECT_NEAR((left + right).z(), 0.0, 1e-3 * plate);
    EXPECT_NEAR(up_cube, cube, 1e-3 * cube);
    EXPECT_NEAR(hangerOnSheave(s, hanger_l).y(), sheave_l, 1e-3 * sheave_l);
    EXPECT_NEAR(hangerOnSheave(s, hanger_r).y(), sheave_r, 1e-3 * sheave_r);
    EXPECT_NEAR(hoistOnPulley(s, hoist).y(), pulley, 1e-3 * pulley);

    // Steady: the pulley hangs in a bight tied at one end, so it sinks at
    // half the hoist drum's payout R w, and the inextensible left hanger
    // lowers its sheave as fast; the cube follows its drum at R w; the
    // right side is tied to the ceiling.
    const Drum a = drum(s, "drum_a"), c = drum(s, "drum_b");
    const double sink = a.radius * a.speed / 2, cube_speed = c.radius * std::abs(c.speed);
    EXPECT_NEAR(s.world->body(test::body(s, "pulley")).v.y(), -sink, 1e-4 * sink);
    EXPECT_NEAR(s.world->body(test::body(s, "sheave_l")).v.y(), -sink, 1e-4 * sink);
    EXPECT_NEAR(s.world->body(test::body(s, "cube")).v.y(), -cube_speed, 1e-4 * cube_speed);
    EXPECT_LT(s.world->body(test::body(s, "sheave_r")).v.norm(), 1e-3 * sink);  // the plate's tilt sways it
  }
}

TEST(Servin, AfterLandingSlackSpansCarryNothingAndTheGroundTakesTheRest) {
  // By 7.5 s both drums have turned to their limits (5 s and 6 s): the cube
  // stands on the ground under a slack strand; the plate's left edge rests
  // on the ground under a slack V while its right V still holds it up.
  for (const Budget b : kBudgets) {
    Scene s = load(b);
    SCOPED_TRACE(testing::Message() << b.substeps << " x " << b.iterations);
    const int hoist = test::cable(s, "hoist"), hanger_l = test::cable(s, "hanger_l"), hanger_r = test::cable(s, "hanger_r");
    const int v_l = test::cable(s, "v_l"), v_r = test::cable(s, "v_r"), cube_line = test::cable(s, "cube_line");
    for (int f = 0; f < static_cast<int>(7.5 * s.frame_rate_hz); ++f) test::frame(s);
    const Drum a = drum(s, "drum_a"), c = drum(s, "drum_b");
    EXPECT_NEAR(s.world->hingeAngle(a.hinge), a.upper, 1e-6);
    EXPECT_NEAR(s.world->hingeAngle(c.hinge), c.lower, 1e-6);

    // Cube: on the ground, still, its strand slack and free of tension;
    // the ground carries all of it.
    const BodyId cube = test::body(s, "cube");
    const BodyState& cb = s.world->body(cube);
    const double cube_w = weight(s, "cube");
    EXPECT_NEAR(cb.x.y(), s.world->bodyDef(cube).shape.half_extents.y(), 1e-3);
    EXPECT_LT(cb.v.norm(), 1e-3);
    EXPECT_GT(s.cables->restLength(cube_line, 1) - s.cables->length(cube_line, 1), 0.1);
    EXPECT_EQ(s.cables->tension(cube_line, 0), 0.0);
    EXPECT_EQ(s.cables->tension(cube_line, 1), 0.0);
    EXPECT_NEAR(groundForce(s, cube), cube_w, 1e-3 * cube_w);

    // Plate: at rest on its bottom left edge (every contact is on it), the
    // left V slack and carrying nothing of it. Which of its spans holds the
    // slack is not a law: a plate hung by a V over a free sheave is an
    // unstable equilibrium (the ellipse the sheave rides relative to the
    // plate, foci at the corners, curves about a point 0.2 m below the
    // plate's centre of mass). A plate turned at 1e-4 rad/s about x at the
    // start has its sheave spinning at 4.6 rad/s by 2 s; here the hanger's
    // pull off the wheel's plane as the left block swings in x
    // (tangentSlide, second order in the swing) turns it to 0.06 rad/s by
    // the landing and 0.5 rad/s after it, and the spinning sheave carries
    // the slack to one span, whose other one may come taut again.
    const BodyId plate = test::body(s, "plate");
    const BodyState& p = s.world->body(plate);
    const Vec3 half = s.world->bodyDef(plate).shape.half_extents;
    const double plate_w = weight(s, "plate");
    EXPECT_LT(p.v.norm(), 1e-3);
    EXPECT_LT(p.omega.norm(), 1e-3);
    double slack = 0.0;
    for (int j = 0; j < 2; ++j) {
      slack += s.cables->restLength(v_l, j) - s.cables->length(v_l, j);
      EXPECT_LT(s.cables->tension(v_l, j), 1e-4 * plate_w) << j;
    }
    EXPECT_GT(slack, 0.1);  // its sheave sank 0.3 m after the landing
    int touching = 0;
    for (const Contact& k : s.world->contacts()) {
      if (k.b != plate || k.lambda_n <= 0.0) continue;
      ++touching;
      EXPECT_NEAR(k.local_b.x(), -half.x(), 1e-6);
      EXPECT_NEAR(k.local_b.y(), -half.y(), 1e-6);
    }
    EXPECT_GE(touching, 2);
    // Moments about that edge (ground forces act on it): the right V's
    // tension T (one tension: its sheave turns freely) balances the weight,
    // T sum_i ((c_i - e) x u_i) . a = -((x - e) x W) . a, for corners c_i
    // pulled along u_i, e on the edge, a along it.
    const Vec3 e = p.toWorld(Vec3(-half.x(), -half.y(), 0.0)), axis = p.q * Vec3::UnitZ();
    const Vec3 u0 = along(s, v_r, 0), u1 = -along(s, v_r, 1);
    const Vec3 c0 = s.cables->startPoint(v_r, 0), c1 = s.cables->endPoint(v_r, 1);
    const double arm = (c0 - e).cross(u0).dot(axis) + (c1 - e).cross(u1).dot(axis);
    const double t_right = -(p.x - e).cross(Vec3(0.0, -plate_w, 0.0)).dot(axis) / arm;
    // The ground carries what the right V does not.
    const double ground = plate_w - vOnPlate(s, v_r).y();
    std::printf("[ measured ] %d x %d: cube ground %.2e; right V %.4f N vs moments %.4f N (%.2e), plate ground "
                "%.3f N (%.1f %% of its weight) vs contacts (%.2e)\n",
                b.substeps, b.iterations, relative(groundForce(s, cube), cube_w), s.cables->tension(v_r, 0),
                t_right, relative(s.cables->tension(v_r, 0), t_right), ground, 100 * ground / plate_w,
                relative(groundForce(s, plate), ground));
    EXPECT_NEAR(s.cables->tension(v_r, 0), t_right, 1e-3 * t_right);
    EXPECT_NEAR(s.cables->tension(v_r, 1), t_right, 1e-3 * t_right);
    EXPECT_GT(ground, 0.2 * plate_w);  // a real share, not a rounding
    EXPECT_NEAR(groundForce(s, plate), ground, 1e-3 * plate_w);

    // Up the rig: the left sheave hangs by its hanger with what its V still
    // pulls (a span its spin brought taut: 0.017 N at 1 x 10), the pulley
    // holds only it; the right sheave holds its V.
    const double sheave_l = weight(s, "sheave_l") + weight(s, "block_l") + vOnPlate(s, v_l).y();
    const double sheave_r = weight(s, "sheave_r") + weight(s, "block_r") + vOnPlate(s, v_r).y();
    const double pulley = weight(s, "pulley") + weight(s, "block_p") + sheave_l;
    EXPECT_NEAR(hangerOnSheave(s, hanger_l).y(), sheave_l, 1e-3 * sheave_l);
    EXPECT_NEAR(hangerOnSheave(s, hanger_r).y(), sheave_r, 1e-3 * sheave_r);
    EXPECT_NEAR(hoistOnPulley(s, hoist).y(), pulley, 1e-3 * pulley);
  }
}

TEST(Servin, CableLengthIsConservedAndTheDrumsPayOutRTimesTheirTurn) {
  Scene s = test::scene("servin");
  const auto& cables = s.cables->cables();
  int joints = 0;
  for (const Cable& c : cables) joints += static_cast<int>(c.joints.size());
  EXPECT_EQ(joints, 16);  // Table 1
  std::vector<double> total;
  for (int c = 0; c < static_cast<int>(cables.size()); ++c) total.push_back(s.cables->totalLength(c));
  const int hoist = test::cable(s, "hoist"), cube_line = test::cable(s, "cube_line");
  const double stored_a = cables[hoist].links[2].stored, stored_b = cables[cube_line].links[0].stored;
  double drift = 0.0;
  for (int f = 0; f < s.frameCount(); ++f) {
    test::frame(s);
    for (int c = 0; c < static_cast<int>(cables.size()); ++c)
      drift = std::max(drift, std::abs(s.cables->totalLength(c) / total[c] - 1.0));
    const auto broken = s.cables->invariantViolation();
    ASSERT_FALSE(broken) << *broken;
  }
  std::printf("[ measured ] worst relative change of a cable's total length over %d frames: %.2e\n", s.frameCount(),
              drift);
  EXPECT_LT(drift, 1e-12);
  // A drum turned by theta hands r theta of its stored cable to the spans.
  const Drum a = drum(s, "drum_a"), c = drum(s, "drum_b");
  EXPECT_NEAR(stored_a - cables[hoist].links[2].stored, a.radius * s.world->hingeAngle(a.hinge), 1e-9);
  EXPECT_NEAR(stored_b - cables[cube_line].links[0].stored, -c.radius * s.world->hingeAngle(c.hinge), 1e-9);
}

TEST(Servin, AtThePapersBudgetTheRestingPlateMeetsTheStopBeforeItsLastIteration) {
  // Once the plate rests on the ground (2.9 s), its V cables and its
  // contact traded a correction each iteration, 0.17 to 0.3 times the
  // last, while the contact was swept after each direct solve: its normal
  // rows first, then its static friction's anchor: 6.74 solves a frame at
  // the paper's 1 x 10, 300 frames at the budget; 5.6 a frame with that
  // tail extrapolated (DirectSolver::extrapolation). Its contact's normal
  // and static friction rows are now in the solve with the cables
  // (DESIGN, "Forty-ninth session"): 2.6 a frame, the budget reached in
  // one frame (a landing); 1.87 since its island starts each substep
  // lifted, as one without contacts does, and a drum's stop no longer
  // keeps it at x~ (DirectSolver::startPoint; DESIGN, "Fiftieth
  // session"). The statics after landing are checked at this
  // budget by AfterLandingSlackSpansCarryNothingAndTheGroundTakesTheRest.
  // Counted until 6 s, when the drums have stopped: from then on the left
  // V's sheave, spinning since the landing (that test), may run the slack
  // out of one span and jerk it taut, an event like a landing.
  Scene s = load(kBudgets[1]);
  const int frames = static_cast<int>(6.0 * s.frame_rate_hz), budget = s.world->settings().iterations;
  long solves = 0;
  int all = 0;
  for (int f = 0; f < frames; ++f) {
    test::frame(s);
    solves += s.world->lastStepIterations();
    all += s.world->lastStepIterations() >= budget;
  }
  const double mean = static_cast<double>(solves) / frames;
  std::printf("[ measured ] 1 x %d, %d frames: %.3f solves a frame, %d frames at the budget\n", budget, frames, mean,
              all);
  EXPECT_LE(all, 3);
  EXPECT_LT(mean, 2.2);
}

}  // namespace
}  // namespace reeve::test_servin
