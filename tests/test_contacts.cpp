// Contacts (SCA 2020 sec. 3.5): non-penetration, static friction as a
// positional row, dynamic friction and restitution in the velocity pass.
// Each test checks a closed form: a box at rest stays put, a box on an
// incline sticks below the friction angle and slides at
// a = g (sin t - mu_d cos t) above it, a ball dropped with restitution e
// rises to e^2 of its height, a sphere rolls down an incline at 5/7 g sin t,
// two spheres meet with relative speed ratio e and conserve momentum,
// stacks of boxes stand still at every split of the solver budget, and a
// ball or a roller leaves a log at cos theta = 2/3 sliding and 10/17
// or 4/7 rolling, and a ball or a log a table's edge (a box's, a hull's,
// a drum's) at the same angles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
#include <numbers>

#include "contact_fixture.h"

namespace reeve::test_contacts {
namespace {

using namespace test;

using std::numbers::pi;
constexpr double kDeg = pi / 180.0;

TEST(Contacts, NoCollisionWorkWithoutGroundOrTwoCollidingBodies) {
  World world = makeWorld(10, 1);
  add(world, Shape::box(Vec3(0.5, 0.5, 0.5)), 1.0, Vec3(0, 0.5, 0), ContactMaterial{}, true);
  EXPECT_FALSE(world.hasContacts());  // one colliding body has nothing to touch
  for (int i = 0; i < 60; ++i) world.step(kFrame);
  EXPECT_TRUE(world.contacts().empty());
  // Free fall, untouched: y = y0 - g t^2 / 2 up to the O(h) of symplectic Euler.
  EXPECT_NEAR(world.body(0).x.y(), 0.5 - 0.5 * kG, kG * 1.0 * kFrame / 10.0);
}

TEST(Contacts, InvalidGroundAndMaterialsAreRejected) {
  World world;
  EXPECT_THROW(world.setGround(ground(Vec3::Zero(), ContactMaterial{})), std::invalid_argument);
  EXPECT_THROW(world.setGround(ground(Vec3::UnitY(), material(-0.1, 0.3, 0.0))),
               std::invalid_argument);
  EXPECT_THROW(world.setGround(ground(Vec3::UnitY(), material(0.5, 0.3, 1.5))),
               std::invalid_argument);
  EXPECT_THROW(add(world, Shape::sphere(1.0), 1.0, Vec3::Zero(), material(0.5, -1.0, 0.0)),
               std::invalid_argument);
  world.setGround(ground(Vec3(0.0, 2.0, 0.0), ContactMaterial{}));
  EXPECT_EQ(world.ground()->normal, Vec3::UnitY());  // normalized
}

// A box, sphere or cylinder set exactly on the ground stays within 0.1 mm
// of where it was put over 10 s; the contact forces carry its weight.
void expectRestsOnGround(const Shape& shape, const Vec3& position, const Quat& orientation) {
  // One substep per step() call (10 per 1/60 s frame, 2 iterations), so
  // that the force can be averaged over every substep.
  World world = makeWorld(1, 2);
  const double h = kFrame / 10.0;
  world.setGround(ground(Vec3::UnitY(), material(0.5, 0.3, 0.0)));
  const double mass = 3.0;
  const BodyId id = add(world, shape, mass, position, material(0.5, 0.3, 0.0), false, orientation);
  double drift = 0.0, tilt = 0.0, force = 0.0;  // force: mean over the last second
  for (int i = 0; i < 6000; ++i) {
    world.step(h);
    drift = std::max(drift, (world.body(id).x - position).norm());
    tilt = std::max(tilt, world.body(id).q.angularDistance(orientation));
    if (i >= 5400)
      for (const Contact& c : world.contacts()) force += contactNormalForce(c, h) / 600.0;
  }
  std::printf("  rest: drift %.3g m, tilt %.3g rad, normal force %.6g N (m g = %.6g N)\n", drift,
              tilt, force, mass * kG);
  EXPECT_LT(drift, 1e-4);
  EXPECT_LT(tilt, 1e-4);
  // The normal rows carry the weight as far as a visit's sweeps converge;
  // the rest is carried by the velocity pass. Measured: box and sphere
  // exact, upright cylinder (32 rim points) 1.1 % short.
  EXPECT_NEAR(force, mass * kG, 0.02 * mass * kG);
}

TEST(Contacts, BoxRestsOnGround) {
  expectRestsOnGround(Shape::box(Vec3(0.4, 0.25, 0.3)), Vec3(1.0, 0.25, -2.0), Quat::Identity());
}

TEST(Contacts, SphereRestsOnGround) {
  expectRestsOnGround(Shape::sphere(0.3), Vec3(0.0, 0.3, 0.0), Quat::Identity());
}

TEST(Contacts, UprightCylinderRestsOnGround) {
  // Axis along local z, turned to world y: it stands on a cap.
  expectRestsOnGround(Shape::cylinder(0.2, 0.5), Vec3(0.0, 0.5, 0.0),
                      Quat(Eigen::AngleAxisd(-pi / 2, Vec3::UnitX())));
}

// A box on a plane tilted by `tilt` about z (the ground normal is tilted;
// gravity stays -y), from rest, over `seconds`.
Slide slideOnIncline(double tilt, const ContactMaterial& m, double seconds) {
  World world = makeWorld(20, 1);
  const Vec3 n(-std::sin(tilt), std::cos(tilt), 0.0);
  const Vec3 downhill(-std::cos(tilt), -std::sin(tilt), 0.0);
  world.setGround(ground(n, m));
  const Vec3 half(0.3, 0.1, 0.2);  // low and wide: it slides rather than tips
  const Vec3 start = half.y() * n;
  const BodyId id = add(world, Shape::box(half), 2.0, start, m, false,
                        Quat(Eigen::AngleAxisd(tilt, Vec3::UnitZ())));
  return measureSlide(world, id, start, downhill, seconds);
}

TEST(Contacts, BoxOnInclineSticksBelowFrictionAngle) {
  const ContactMaterial m = material(0.5, 0.3, 0.0);  // friction angle atan(0.5) = 26.6 deg
  for (double deg : {10.0, 20.0, 25.0}) {
    const Slide s = slideOnIncline(deg * kDeg, m, 3.0);
    std::printf("  %g deg: moved %.3g m downhill in 3 s\n", deg, s.displacement_m);
    EXPECT_LT(std::abs(s.displacement_m), 1e-4) << deg << " deg";
  }
}

TEST(Contacts, BoxOnInclineSlidesWithDynamicFriction) {
  const ContactMaterial m = material(0.5, 0.3, 0.0);
  for (double deg : {30.0, 35.0, 45.0}) {
    const double t = deg * kDeg;
    const double expected = kG * (std::sin(t) - 0.3 * std::cos(t));
    const Slide s = slideOnIncline(t, m, 2.0);
    std::printf("  %g deg: a = %.5f m/s^2, closed form %.5f (%.3f %%)\n", deg,
                s.acceleration_m_per_s2, expected,
                100.0 * (s.acceleration_m_per_s2 - expected) / expected);
    EXPECT_NEAR(s.acceleration_m_per_s2, expected, 0.02 * expected) << deg << " deg";
  }
}

// A ball dropped from rest with its lowest point `height` above the ground,
// ground and ball of restitution e: it rises to e^2 height after the first
// bounce (v_out = e v_in).
double bounceHeight(double e, double height) {
  World world = makeWorld(20, 1);
  world.setGround(ground(Vec3::UnitY(), material(0.5, 0.3, e)));
  const double r = 0.1;
  const BodyId id = add(world, Shape::sphere(r), 0.5, Vec3(0.0, r + height, 0.0),
                        material(0.5, 0.3, e));
  bool bounced = false;
  double peak = 0.0;
  for (int i = 0; i < 600; ++i) {
    world.step(kFrame);
    const BodyState& b = world.body(id);
    if (!bounced) {
      bounced = b.v.y() > 0.0;
    } else {
      if (b.v.y() < 0.0) break;
      peak = b.x.y() - r;
    }
  }
  // Refine the sampled peak with the ballistic rest of the last frame.
  return peak;
}

TEST(Contacts, BallBouncesToRestitutionSquaredOfItsHeight) {
  for (double e : {0.3, 0.5, 0.8, 1.0}) {
    const double h0 = 1.0;
    const double rise = bounceHeight(e, h0);
    std::printf("  e = %.2f: rises to %.5f m, e^2 h = %.5f m (%.3f %%)\n", e, rise, e * e * h0,
                100.0 * (rise - e * e * h0) / (e * e * h0));
    EXPECT_NEAR(rise, e * e * h0, 0.03 * e * e * h0) << "e = " << e;
  }
}

TEST(Contacts, SphereRollsDownInclineAtFiveSeventhsGSinTilt) {
  // Rolling without slipping (static friction holds: tan t < 7/2 mu_s):
  // a = g sin t / (1 + I / (m r^2)) = 5/7 g sin t.
  World world = makeWorld(20, 1);
  const double t = 20.0 * kDeg;
  const Vec3 n(-std::sin(t), std::cos(t), 0.0);
  const Vec3 downhill(-std::cos(t), -std::sin(t), 0.0);
  const ContactMaterial m = material(0.8, 0.6, 0.0);
  world.setGround(ground(n, m));
  const double r = 0.2;
  const BodyId id = add(world, Shape::sphere(r), 1.0, r * n, m);
  double v1 = 0.0;
  for (int i = 1; i <= 120; ++i) {
    world.step(kFrame);
    if (i == 30) v1 = world.body(id).v.dot(downhill);
  }
  const double a = (world.body(id).v.dot(downhill) - v1) / 1.5;
  const double expected = 5.0 / 7.0 * kG * std::sin(t);
  std::printf("  rolling sphere: a = %.5f, closed form %.5f (%.3f %%); spin/v = %.5f (1/r = %.5f)\n",
              a, expected, 100 * (a - expected) / expected, world.body(id).omega.norm() /
              world.body(id).v.norm(), 1.0 / r);
  EXPECT_NEAR(a, expected, 0.02 * expected);
  EXPECT_NEAR(world.body(id).omega.norm() * r, world.body(id).v.norm(),
              0.01 * world.body(id).v.norm());
}

/// A 10 kg body resting on a flat face at `height`, spun at omega0 about
/// the ground normal: its angular deceleration (rad/s^2) between 0.05 s and
/// 0.2 s, and the time it stops (s).
std::pair<double, double> spinDown(const Shape& shape, const Quat& orientation, double height,
                                   double omega0, double mu_d) {
  World world = makeWorld(20, 1);
  const ContactMaterial m = material(mu_d + 0.2, mu_d, 0.0);
  world.setGround(ground(Vec3::UnitY(), m));
  const BodyId body = add(world, shape, 10.0, Vec3(0.0, height, 0.0), m, false, orientation);
  world.body(body).omega = Vec3(0.0, omega0, 0.0);
  double w1 = 0.0, w2 = 0.0, stop = -1.0;
  for (int f = 1; f <= 120; ++f) {
    world.step(kFrame);
    const double w = world.body(body).omega.y();
    if (f == 3) w1 = w;
    if (f == 12) w2 = w;
    if (stop < 0.0 && std::abs(w) < 1e-6) stop = f * kFrame;
  }
  return {(w1 - w2) / (9 * kFrame), stop};
}

TEST(Contacts, SpinningBoxAndCylinderStopWithTwistingFriction) {
  // A face spinning on the ground is braked by a torque mu_d m g r with r
  // the mean distance of its (uniform) pressure from the centre: for a
  // square of half-side s, s (sqrt 2 + asinh 1) / 3 = 0.7652 s; for a disc
  // of radius R, 2R/3. Deceleration alpha = mu_d m g r / I, stopping at
  // omega0 / alpha; within 3 % (the patch's lever arm is that of a disc of
  // equal area: 1.7 % short for the square, 1.3 % for the 16-gon cap).
  // Before patches had a twist row, nothing but the corners' tangential
  // rows braked a spin: 48 % too fast for the box.
  const double mu = 0.4, s = 0.5, R = 0.4, omega0 = 3.0;
  const double r_box = s * (std::sqrt(2.0) + std::asinh(1.0)) / 3.0;
  const double alpha_box = mu * 10.0 * kG * r_box / (10.0 * 2.0 * (2 * s) * (2 * s) / 12.0);
  const double alpha_cyl = mu * 10.0 * kG * (2.0 * R / 3.0) / (0.5 * 10.0 * R * R);
  const Quat upright(Eigen::AngleAxisd(pi / 2.0, Vec3::UnitX()));
  const auto [box_alpha, box_stop] = spinDown(Shape::box(Vec3(s, s, s)), Quat::Identity(), s, omega0, mu);
  const auto [cyl_alpha, cyl_stop] = spinDown(Shape::cylinder(R, 0.2), upright, 0.2, omega0, mu);
  std::printf("  spin-down: box alpha %.4f (%.4f, %+.2f %%), stops at %.3f s (%.3f); "
              "cylinder alpha %.4f (%.4f, %+.2f %%), stops at %.3f s (%.3f)\n",
              box_alpha, alpha_box, 100.0 * (box_alpha / alpha_box - 1.0), box_stop, omega0 / alpha_box,
              cyl_alpha, alpha_cyl, 100.0 * (cyl_alpha / alpha_cyl - 1.0), cyl_stop, omega0 / alpha_cyl);
  EXPECT_NEAR(box_alpha, alpha_box, 0.03 * alpha_box);
  EXPECT_NEAR(cyl_alpha, alpha_cyl, 0.03 * alpha_cyl);
  // The stop is seen at the end of a frame.
  EXPECT_NEAR(box_stop, omega0 / alpha_box, 0.03 * omega0 / alpha_box + kFrame);
  EXPECT_NEAR(cyl_stop, omega0 / alpha_cyl, 0.03 * omega0 / alpha_cyl + kFrame);
}

TEST(Contacts, HeadOnSpheresKeepMomentumAndRestitution) {
  // No gravity; two colliding spheres of 1 kg and 3 kg approach at 2 and
  // -1 m/s: afterwards the relative speed is e times what it was and the
  // momentum is unchanged.
  World world = makeWorld(20, 1, Vec3::Zero());
  const double e = 0.6;
  const ContactMaterial m = material(0.0, 0.0, e);
  const BodyId a = add(world, Shape::sphere(0.25), 1.0, Vec3(-1.0, 0.0, 0.0), m, true);
  const BodyId b = add(world, Shape::sphere(0.5), 3.0, Vec3(1.0, 0.0, 0.0), m, true);
  world.body(a).v = Vec3(2.0, 0.0, 0.0);
  world.body(b).v = Vec3(-1.0, 0.0, 0.0);
  for (int i = 0; i < 60; ++i) world.step(kFrame);
  const Vec3 va = world.body(a).v, vb = world.body(b).v;
  std::printf("  spheres: va %.5f vb %.5f; relative %.5f (e x 3 = %.5f)\n", va.x(), vb.x(),
              vb.x() - va.x(), e * 3.0);
  EXPECT_NEAR((1.0 * va + 3.0 * vb).x(), 2.0 - 3.0, 1e-9);
  EXPECT_NEAR(vb.x() - va.x(), e * 3.0, 0.03 * e * 3.0);
  EXPECT_LT(std::max(va.tail<2>().norm(), vb.tail<2>().norm()), 1e-9);
}

struct StackRun {
  double drift = 0.0;  // m, largest distance of any box from where it started
  double tilt = 0.0;   // rad, largest rotation of any box
  double top = 0.0;    // m, height of the top box at the end
};

/// n unit cubes of 10 kg stacked on the ground, run for `seconds`.
StackRun runStack(int n, int substeps, int iterations, double seconds) {
  World world = makeWorld(substeps, iterations);
  const ContactMaterial m = material(0.6, 0.4, 0.0);
  world.setGround(ground(Vec3::UnitY(), m));
  std::vector<BodyId> boxes;
  for (int i = 0; i < n; ++i)
    boxes.push_back(add(world, Shape::box(Vec3(0.5, 0.5, 0.5)), 10.0, Vec3(0.0, 0.5 + i, 0.0), m, true));
  StackRun run;
  for (int f = 0; f < std::lround(seconds / kFrame); ++f) {
    world.step(kFrame);
    for (int i = 0; i < n; ++i) {
      run.drift = std::max(run.drift, (world.body(boxes[i]).x - Vec3(0.0, 0.5 + i, 0.0)).norm());
      run.tilt = std::max(run.tilt, world.body(boxes[i]).q.angularDistance(Quat::Identity()));
    }
  }
  run.top = world.body(boxes.back()).x.y();
  std::printf("  %d boxes at %d x %d: largest drift %.3g m, tilt %.3g rad over %.0f s; top at %.5f m (%.1f)\n",
              n, substeps, iterations, run.drift, run.tilt, seconds, run.top, n - 0.5);
  return run;
}

TEST(Contacts, StackOfFiveBoxesStandsStillForTenSeconds) {
  // A perfectly placed stack has nothing to move it: every box stays within
  // 2 mm of where it was put, turns less than 1 mrad, and the top sinks less
  // than 1 mm (penetration of four contacts). Measured: 0.07 mm, 0.012 mrad,
  // 0.06 mm (0.7 mm and 0.08 mrad before static friction kept its anchor).
  // (Before contacts had a margin, a box pushed into its neighbour after
  // detection found no contact until the next substep; the stack bounced
  // every other substep and walked 6 cm.)
  const StackRun run = runStack(5, 20, 1, 10.0);
  EXPECT_NEAR(run.top, 4.5, 1e-3);
  EXPECT_LT(run.drift, 2e-3);
  EXPECT_LT(run.tilt, 1e-3);
}

TEST(Contacts, TallStackStandsWithIterations) {
  // Ten boxes at 10 substeps x 10 iterations: within 1 cm and 3 mrad
  // (measured 0.18 mm, 0.025 mrad; 2.3 mm, 1.4 mrad before static friction
  // kept its anchor).
  const StackRun run = runStack(10, 10, 10, 10.0);
  EXPECT_NEAR(run.top, 9.5, 1e-3);
  EXPECT_LT(run.drift, 1e-2);
  EXPECT_LT(run.tilt, 3e-3);
}

TEST(Contacts, StackStandsAtEverySplitOfTheSolverBudget) {
  // The same budget of 20 as all substeps, all iterations, or 5 x 4: the
  // stack stands in each (with more iterations it used to topple), the top
  // box within 3 cm of where it started, no box turned by 3 mrad. Measured:
  // 0.07 mm, 0.66 mm, 0.29 mm; 0.012, 0.20, 0.045 mrad (0.7 mm, 9 mm,
  // 2.3 mm before static friction kept its anchor).
  for (const auto& [substeps, iterations] : {std::pair{20, 1}, {1, 20}, {5, 4}}) {
    const StackRun run = runStack(5, substeps, iterations, 10.0);
    EXPECT_NEAR(run.top, 4.5, 2e-3) << substeps << " x " << iterations;
    EXPECT_LT(run.drift, 0.03) << substeps << " x " << iterations;
    EXPECT_LT(run.tilt, 3e-3) << substeps << " x " << iterations;
  }
}

// A thin rod (radius 0.01 m, 0.2 m long, 0.5 g) laid on a wheel of radius
// 0.3 m whose axle is world z, tangent to it `degrees` from the top: it
// rests there (friction 0.5 holds it up to 26.6 deg), pushed out along the
// wheel's radius, never along the axle, and nothing turns it about its own
// axis, whose inertia is tiny (2.5e-8 kg m^2).
TEST(Contacts, ThinRodRestsOnAWheelWithoutSpinningOrSlidingAlongTheAxle) {
  for (const double half_length : {0.05, 0.25})
    for (const bool hinged : {false, true})
      for (const double degrees : {0.0, 10.0, 20.0}) {
        World world = makeWorld(10, 2);
        BodyDef wheel;
        wheel.shape = Shape::cylinder(0.3, half_length);
        wheel.mass = 2.0;
        wheel.is_static = !hinged;
        wheel.collides = true;
        const BodyId wheel_id = world.addBody(wheel);
        if (hinged) world.addHinge(HingeDef(wheel_id, kWorldBody, Vec3::Zero(), Vec3::UnitZ()));
        const double a = degrees * kDeg;
        const Vec3 radial(std::sin(a), std::cos(a), 0.0), tangent(std::cos(a), -std::sin(a), 0.0);
        const Vec3 start = 0.3099 * radial;  // 0.1 mm into the wheel
        const BodyId rod = add(world, Shape::cylinder(0.01, 0.1), 5e-4, start, ContactMaterial{}, true,
                               rotationBetween(Vec3::UnitZ(), tangent));
        double spin = 0.0, off_axle = 0.0;
        for (int f = 0; f < 120; ++f) {
          world.step(kFrame);
          const BodyState& b = world.body(rod);
          spin = std::max(spin, std::abs(b.omega.dot(b.q * Vec3::UnitZ())));
          off_axle = std::max(off_axle, std::abs(b.x.z()));
        }
        SCOPED_TRACE(testing::Message() << "half length " << half_length << (hinged ? ", hinged" : ", static")
                                        << ", " << degrees << " deg");
        // Before contact points were put on the rod's surface under the
        // normal (collide.cpp), MPR's point 2 um beside the rod's axis spun
        // it at up to 0.1 rad/s and it rolled 0.7 mm along the axle in 2 s.
        EXPECT_LT(spin, 1e-3);
        EXPECT_LT(off_axle, 1e-5);
        // On the static wheel it stays where it was laid, but for rocking
        // about its balance point (test_friction_bounds.cpp): at 20 deg its
        // centre swings up to 0.3 mm from where it started.
        if (!hinged) {
          EXPECT_LT((world.body(rod).x - 0.31 * radial).norm(), 2e-4);
        }
      }
}

// A ball, or a roller lying along the log (radius 0.1 m, 1 kg), set on
// top of a fixed log (radius 1 m, axle along z), 0.02 rad off its crest,
// runs down its side and leaves it where its weight's normal part, g cos
// theta, no longer gives the centripetal v^2 / (R + r). Frictionless, v^2 =
// 2 g (R + r) (1 - cos theta): it leaves at cos theta = 2/3. Rolling
// (friction holding to the end: mu 50), v^2 = 2 g (R + r) (1 - cos theta)
// / (1 + k), k = I / (m r^2): the ball (k = 2/5) at 10/17, the roller (k =
// 1/2) at 4/7. Before its contact was measured against the normal midway
// through each substep, the velocity pass took the outward lean of the
// body's chord round the log for an approach and it clung on to half the
// centripetal speed (the ball rolling: cos theta 5/12, 1.14 rad for
// 0.94); before the points were measured again in the solve, the ball
// left at 1.06 to 1.2 rad frictionless and 1.11 to 1.30 rolling, depending
// on the budget, and until a line contact was measured too, the roller at
// 0.93 and 1.06 rad for 0.84 and 0.96.
TEST(Contacts, ABallOrARollerLeavesALogWhereItsWeightNoLongerHoldsItOn) {
  struct Case {
    const char* what;
    Shape shape;
    double mu, cos_theta;
  };
  const Shape ball = Shape::sphere(0.1), roller = Shape::cylinder(0.1, 0.2);
  for (const Case& c : {Case{"ball sliding", ball, 0.0, 2.0 / 3.0}, Case{"ball rolling", ball, 50.0, 10.0 / 17.0},
                        Case{"roller sliding", roller, 0.0, 2.0 / 3.0}, Case{"roller rolling", roller, 50.0, 4.0 / 7.0}})
    for (const auto& [substeps, iterations] : {std::pair{2, 4}, std::pair{10, 2}, std::pair{50, 1}})
      for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel}) {
        if (solver == SolverKind::GaussSeidel && substeps != 10) continue;  // contacts are solved alike
        SCOPED_TRACE(testing::Message() << c.what << ", " << substeps << " x " << iterations
                                        << (solver == SolverKind::Direct ? ", direct" : ", Gauss-Seidel"));
        World world = makeWorld(substeps, iterations);
        world.settings().solver = solver;
        BodyDef log;
        log.shape = Shape::cylinder(1.0, 0.5);
        log.is_static = true;
        log.collides = true;
        log.material = material(c.mu, c.mu, 0.0);
        log.position = Vec3(2.0, 1.0, 0.3);  // off the origin: its start pose is its placed one
        world.addBody(log);
        const double start = 0.02;
        const BodyId body = add(world, c.shape, 1.0, log.position + 1.1 * Vec3(std::sin(start), std::cos(start), 0.0),
                                material(c.mu, c.mu, 0.0), true);
        double left = 0.0;
        for (int step = 0; step < 1800 && left == 0.0; ++step) {  // up to 3 s
          world.step(1.0 / 600.0);
          const Vec3 x = world.body(body).x - log.position;
          const double theta = std::atan2(x.x(), x.y());
          double pressed = 0.0;
          for (const Contact& contact : world.contacts()) pressed += contact.lambda_n;
          if (theta > 0.3 && pressed <= 0.0) left = theta;
        }
        // 1/600 s steps move the body by up to 0.004 rad; 0.1 to 0.3 rad late before.
        EXPECT_NEAR(left, std::acos(c.cos_theta), 0.01);
      }
}

// A ball rolls over a box's edge as it does over a log of radius 0: its
// centre turns about the edge at R, and it leaves where gravity's part
// along the radius no longer holds it there, g cos theta = v^2 / R. With
// k = I / (m R^2) (2/5 a ball, 1/2 a log lying along the edge, 0 sliding)
// and v0 its speed as it reaches the edge, energy gives v^2 (1 + k) / 2 =
// g R (1 - cos theta) + v0^2 (1 + k) / 2, so cos theta = (2 + (1 + k) v0^2
// / (g R)) / (3 + k): from rest 2/3 sliding, 10/17 a ball rolling, 4/7 a
// log. Over a corner, along the diagonal, the same. The table is a box, a
// hull of the box's corners and (for the ball) a drum standing on its cap,
// turned and off the origin, so the edge is measured in its frame. Before
// a sphere's or a cylinder's side's contact with a box, hull or cylinder
// was measured exactly (the normal from its centre's or axis' nearest
// point of the body), MPR's upright normal held the ball or log at rest 2
// mm beyond the edge, 0.8 mm above it, for good, and a ball rolling off at
// 0.5 m/s was thrown up, its energy rising by 236 J (240 J off the drum)
// in a frame.
TEST(Contacts, ABallOrALogRollsOverATablesEdgeOrCornerAndLeavesWhereItsWeightNoLongerHoldsItOn) {
  struct Case {
    const char* what;
    double mu, v0;
    bool corner;
  };
  constexpr double R = 0.1, m = 1.0;
  const double v0 = 0.5;
  const Vec3 half(0.5, 0.4, 0.3);
  std::vector<Vec3> corners;
  for (const double x : {-1.0, 1.0})
    for (const double y : {-1.0, 1.0})
      for (const double z : {-1.0, 1.0}) corners.push_back(half.cwiseProduct(Vec3(x, y, z)));
  // The drum stands on its cap, its axis along the table's y, its rim
  // through the box's edge pivot; the log lies along the edge (z).
  const Quat upright(Eigen::AngleAxisd(-pi / 2.0, Vec3::UnitX()));
  for (const Shape& solid : {Shape::box(half), Shape::convexHull(corners), Shape::cylinder(half.x(), half.y())})
    for (const Shape& body : {Shape::sphere(R), Shape::cylinder(R, 0.2)})
      for (const Case& c : {Case{"sliding from rest", 0.0, 0.0, false}, Case{"rolling from rest", 50.0, 0.0, false},
                            Case{"rolling up at 0.5 m/s", 50.0, v0, false}, Case{"sliding over a corner", 0.0, 0.0, true},
                            Case{"rolling over a corner", 50.0, 0.0, true}})
        for (const auto& [substeps, iterations] : {std::pair{1, 4}, std::pair{2, 2}, std::pair{10, 1}})
          for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel}) {
            if (solver == SolverKind::GaussSeidel && substeps != 2) continue;  // contacts are solved alike
            const bool drum = solid.type == Shape::Type::Cylinder, log = body.type == Shape::Type::Cylinder;
            if ((drum && (c.corner || log)) || (log && c.corner)) continue;
            SCOPED_TRACE(testing::Message() << (drum ? "drum, " : solid.type == Shape::Type::Box ? "box, " : "hull, ")
                                            << (log ? "log " : "ball ") << c.what << ", " << substeps << " x "
                                            << iterations << (solver == SolverKind::Direct ? ", direct" : ", Gauss-Seidel"));
            const double k = c.mu == 0.0 ? 0.0 : log ? 0.5 : 0.4;
            const double cos_theta = (2.0 + (1.0 + k) * c.v0 * c.v0 / (kG * R)) / (3.0 + k);
            World world = makeWorld(substeps, iterations);
            world.settings().solver = solver;
            BodyDef table;
            table.shape = solid;
            table.is_static = true;
            table.collides = true;
            table.material = material(c.mu, c.mu, 0.0);
            table.position = Vec3(2.0, 1.0, 0.3);
            const Quat turn(Eigen::AngleAxisd(0.4, Vec3::UnitY()));
            table.orientation = drum ? Quat(turn * upright) : turn;
            world.addBody(table);
            // In the table's frame: the body rolls along `out` (+x, or the
            // diagonal over the corner) across the top to the pivot.
            const auto inTable = [&](const Vec3& local) { return Vec3(table.position + turn * local); };
            const Vec3 pivot = c.corner ? half : Vec3(half.x(), half.y(), 0.0);
            const Vec3 out = c.corner ? Vec3(Vec3(1.0, 0.0, 1.0).normalized()) : Vec3::UnitX();
            const Vec3 start = c.v0 > 0.0 ? Vec3(pivot + Vec3(-0.1, R, 0.0))
                                          : Vec3(pivot + R * (std::sin(0.02) * out + std::cos(0.02) * Vec3::UnitY()));
            const BodyId id = add(world, body, m, inTable(start), material(c.mu, c.mu, 0.0), true, turn);
            world.body(id).v = turn * (c.v0 * out);
            world.body(id).omega = turn * Vec3::UnitY().cross(out) * (c.v0 / R);  // rolling
            const Mat3 inertia = inertiaTensor(body, m);
            const auto energy = [&] {
              const BodyState& b = world.body(id);
              const Vec3 w = b.q.conjugate() * b.omega;
              return 0.5 * m * b.v.squaredNorm() + 0.5 * w.dot(inertia * w) + m * kG * b.x.y();
            };
            const double e0 = energy();
            double left = 0.0, most_gained = 0.0;
            for (int step = 0; step < 6000 && left == 0.0; ++step) {  // up to 2 s
              world.step(1.0 / 3000.0);
              most_gained = std::max(most_gained, energy() - e0);
              const Vec3 x = turn.conjugate() * (world.body(id).x - table.position) - pivot;
              const double theta = std::atan2(x.dot(out), x.y());
              double pressed = 0.0;
              for (const Contact& contact : world.contacts()) pressed += contact.lambda_n;
              if (theta > 0.3 && pressed <= 0.0) left = theta;
            }
            // 1/3000 s steps move the body by up to 0.003 rad there.
            EXPECT_NEAR(left, std::acos(cos_theta), 0.005);
            // Read from the step's velocities, the energy is O(h) off (9.5e-5
            // m g R at 1 x 4 over the edge, 9.4e-6 at 10 x 1); before, the
            // ball at rest was pushed up 0.8 mm (8e-3 m g R) and the rolling
            // one thrown up.
            EXPECT_LE(most_gained, 2e-4 * m * kG * R);
          }
}

}  // namespace
}  // namespace reeve::test_contacts

namespace reeve::test_contacts {
namespace {

using namespace test;

// Which colliding bodies touch (MuJoCo's contype and conaffinity, and
// excluded pairs): a 0.2 m box dropped 0.05 m onto another resting on the
// ground comes to rest on it, its centre 0.3 m up, where the pair's bits
// meet; where they do not, or the pair is excluded, it falls through onto
// the ground, its centre at 0.1 m. One side is enough: the top's type
// against the bottom's affinity.
TEST(Contacts, ContactBitsAndExcludedPairsChooseWhichBodiesTouch) {
  struct Case {
    const char* what;
    std::uint32_t top_type, top_affinity, bottom_type, bottom_affinity;
    bool excluded;
    double rest_height;
  };
  for (const Case& c : {Case{"default bits", 1, 1, 1, 1, false, 0.3}, Case{"bits apart", 1, 1, 2, 2, false, 0.1},
                        Case{"one side", 2, 0, 0, 2, false, 0.3}, Case{"neither side", 2, 0, 2, 0, false, 0.1},
                        Case{"excluded", 1, 1, 1, 1, true, 0.1}})
    for (const auto& [substeps, iterations] : {std::pair{10, 2}, std::pair{1, 10}}) {
      SCOPED_TRACE(std::string(c.what) + ", " + std::to_string(substeps) + " x " + std::to_string(iterations));
      World world = makeWorld(substeps, iterations);
      world.setGround(ground(Vec3::UnitY(), ContactMaterial{}));
      const auto box = [&](double y, std::uint32_t type, std::uint32_t affinity) {
        BodyDef def;
        def.shape = Shape::box(Vec3::Constant(0.1));
        def.mass = 1.0;
        def.position = Vec3(0.0, y, 0.0);
        def.collides = true;
        def.contact_type = type;
        def.contact_affinity = affinity;
        return world.addBody(def);
      };
      const BodyId bottom = box(0.1, c.bottom_type, c.bottom_affinity), top = box(0.35, c.top_type, c.top_affinity);
      if (c.excluded) world.excludeContact(top, bottom);
      EXPECT_EQ(world.contactAllowed(top, bottom), c.rest_height > 0.2);
      EXPECT_EQ(world.contactAllowed(bottom, top), c.rest_height > 0.2);
      for (int f = 0; f < 120; ++f) world.step(kFrame);
      EXPECT_NEAR(world.body(top).x.y(), c.rest_height, 2e-3);
      EXPECT_NEAR(world.body(bottom).x.y(), 0.1, 2e-3);
    }
  World world = makeWorld(10, 2);
  const BodyId a = add(world, Shape::box(Vec3::Constant(0.1)), 1.0, Vec3::Zero(), ContactMaterial{}, true);
  EXPECT_THROW(world.excludeContact(a, a), std::invalid_argument);
  EXPECT_THROW(world.excludeContact(a, 7), std::invalid_argument);
}

}  // namespace
}  // namespace reeve::test_contacts
