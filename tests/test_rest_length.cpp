// Alg. 1 lines 4-5: a wheel turned by an angle moves exactly r x angle of
// cable between its two spans, in the sense given by its orientation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "reeve/cable/cable.h"

namespace reeve::test_rest_length {
namespace {

// A static post, a wheel (radius 0.5, axis z) and a second post: the cable
// runs post A -> over the wheel clockwise -> down to post B. Post A at
// `post_a`: far enough for span 0 to give up what a test turns the wheel
// by (rest lengths never go below zero).
struct WheelRig {
  double radius = 0.5;
  World world;
  CableSystem cables{world};
  BodyId wheel;
  int cable;
  explicit WheelRig(int orientation = -1, const Vec3& post_a = Vec3(-2.0, -1.0, 0.0)) {
    BodyDef post;
    post.is_static = true;
    post.position = post_a;
    const BodyId a = world.addBody(post);
    post.position = Vec3(1.5, -2.0, 0.0);
    const BodyId b = world.addBody(post);
    BodyDef w;
    w.is_static = true;  // turned by hand below
    w.shape = Shape::cylinder(radius, 0.1);
    wheel = world.addBody(w);
    CableDef def;
    def.links = {LinkDef::attachment(a, Vec3::Zero()),
                 LinkDef::rolling(wheel, orientation),
                 LinkDef::attachment(b, Vec3::Zero())};
    cable = cables.addCable(def);
  }
  void turn(double angle, int steps) {
    for (int i = 0; i < steps; ++i) {
      rotateExactly(world.body(wheel).q, Vec3(0, 0, angle / steps));
      cables.update();
    }
  }
};

TEST(RestLength, TurningInThePayingOutSenseLengthensTheLeavingSpanByRadiusTimesAngle) {
  // The cable leaves the wheel into span 1 travelling clockwise; turning the
  // wheel clockwise (negative about z) by 1.5 turns pays out r * 3 pi into
  // span 1 and takes the same from span 0.
  WheelRig rig(-1, Vec3(-8.0, -1.0, 0.0));
  const double d0 = rig.cables.restLength(rig.cable, 0);
  const double d1 = rig.cables.restLength(rig.cable, 1);
  const double angle = 3.0 * std::numbers::pi;
  rig.turn(-angle, 90);
  EXPECT_NEAR(rig.cables.restLength(rig.cable, 1) - d1, rig.radius * angle, 1e-12);
  EXPECT_NEAR(rig.cables.restLength(rig.cable, 0) - d0, -rig.radius * angle, 1e-12);
}

TEST(RestLength, AWheelTurningOneAndAHalfTurnsInOneSubstepPaysOutEveryTurn) {
  // The update after a substep of h in which the wheel turned -3 pi at
  // omega: geometrically the tangent point is where it was a half turn
  // ago, either way round; the wheel's own turn says which and how often.
  for (const double angle : {3.0 * std::numbers::pi, 7.9, 0.5 * std::numbers::pi}) {
    WheelRig rig(-1, Vec3(-8.0, -1.0, 0.0));
    const double d1 = rig.cables.restLength(rig.cable, 1);
    const double h = 1.0 / 600.0;
    BodyState& wheel = rig.world.body(rig.wheel);
    wheel.omega = Vec3(0.0, 0.0, -angle / h);
    rotateExactly(wheel.q, h * wheel.omega);
    rig.cables.update(0.0, h);
    EXPECT_NEAR(rig.cables.restLength(rig.cable, 1) - d1, rig.radius * angle, 1e-12) << angle;
  }
}

TEST(RestLength, TurningTheOtherWayShortensIt) {
  WheelRig rig(-1);
  const double d1 = rig.cables.restLength(rig.cable, 1);
  rig.turn(0.8, 10);
  EXPECT_NEAR(rig.cables.restLength(rig.cable, 1) - d1, -rig.radius * 0.8, 1e-12);
}

TEST(RestLength, TurningBackAndForthConservesTotalLengthAndWrapArc) {
  WheelRig rig(-1);
  const double total = rig.cables.totalLength(rig.cable);
  const double wrap = rig.cables.cables()[rig.cable].links[1].stored;
  // Tangent points seen from the centre: from post A (-2, -1) at
  // atan2(-1, -2) - acos(r / sqrt 5), towards post B (1.5, -2) at
  // atan2(-2, 1.5) + acos(r / 2.5); clockwise over the top in between.
  const double arrive = std::atan2(-1.0, -2.0) + 2 * std::numbers::pi - std::acos(0.5 / std::sqrt(5.0));
  const double depart = std::atan2(-2.0, 1.5) + std::acos(0.5 / 2.5);
  EXPECT_NEAR(wrap, rig.radius * (arrive - depart), 1e-12);
  rig.turn(2.0, 40);
  rig.turn(-5.0, 70);
  EXPECT_NEAR(rig.cables.totalLength(rig.cable), total, 1e-12 * total);
  EXPECT_NEAR(rig.cables.cables()[rig.cable].links[1].stored, wrap, 1e-12);
}

TEST(RestLength, MovingTheWheelWithoutTurningItOnlyRollsTheTangentPoint) {
  // Translating the wheel changes the spans' geometric lengths but pays out
  // only the arc the tangent point travels, so rest + stored is unchanged.
  WheelRig rig(-1);
  const double total = rig.cables.totalLength(rig.cable);
  for (int i = 0; i < 50; ++i) {
    rig.world.body(rig.wheel).x += Vec3(0.004, 0.006, 0.0);
    rig.cables.update();
  }
  EXPECT_NEAR(rig.cables.totalLength(rig.cable), total, 1e-12 * total);
}

}  // namespace
}  // namespace reeve::test_rest_length

namespace reeve::test_rest_length {
namespace {

TEST(RestLength, TheFramesOutputAgreesWithItsPosesNotASubstepLate) {
  // Issue 28, item 11: the Atwood machine (1 and 2 kg over a 2 kg wheel of
  // r = 0.3 m, no slip) stepped once at one substep of 1/600 s. The
  // bookkeeping updates at a substep's start, so after the step its rest
  // lengths are those before the solve turned the wheel; the rest lengths
  // and stored cable reported now must include that turn: each span
  // changes by r x the wheel's turn, the total is kept.
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel}) {
    SolverSettings settings;
    settings.solver = solver;
    settings.substeps = 1;
    settings.iterations = 10;
    World world(settings);
    CableSystem cables(world);
    BodyDef def;
    def.shape = Shape::cylinder(0.3, 0.05);
    def.mass = 2.0;
    const BodyId wheel = world.addBody(def);
    world.addHinge(HingeDef(wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ()));
    def.shape = Shape::box(Vec3::Constant(0.1));
    def.mass = 1.0;
    def.position = Vec3(-0.3, -2.0, 0.0);
    const BodyId light = world.addBody(def);
    def.mass = 2.0;
    def.position = Vec3(0.3, -2.0, 0.0);
    const BodyId heavy = world.addBody(def);
    CableDef rope;
    rope.links = {LinkDef::attachment(light, Vec3(0.0, 0.1, 0.0)), LinkDef::rolling(wheel, -1),
                  LinkDef::attachment(heavy, Vec3(0.0, 0.1, 0.0))};
    cables.addCable(rope);
    const double left = cables.restLength(0, 0), right = cables.restLength(0, 1), wrap = cables.cables()[0].links[1].stored;
    world.step(1.0 / 600.0);
    const double turn = world.hingeAngle(0);  // clockwise: negative, the heavy side goes down
    ASSERT_LT(turn, -1e-6);
    EXPECT_NEAR(cables.restLengthNow(0, 0), left + 0.3 * turn, 1e-12);
    EXPECT_NEAR(cables.restLengthNow(0, 1), right - 0.3 * turn, 1e-12);
    EXPECT_NEAR(cables.storedNow(0, 1), wrap, 1e-12);
    EXPECT_NE(cables.restLength(0, 0), cables.restLengthNow(0, 0));  // the bookkeeping's own lags
    // The next substep's update books what the query said.
    const double said = cables.restLengthNow(0, 0);
    cables.update(world.time(), 0.0);
    EXPECT_NEAR(cables.restLength(0, 0), said, 1e-12);
  }
}

TEST(CableSetup, ACableThatCannotBeBuiltLeavesTheWorldUntouched) {
  // The second span would have to start inside the wheel: no tangent.
  World world;
  CableSystem cables(world);
  BodyDef def;
  def.is_static = true;
  const BodyId post = world.addBody(def);
  def.shape = Shape::cylinder(0.5, 0.1);
  def.position = Vec3(0, 2, 0);
  const BodyId wheel = world.addBody(def);
  def.shape = Shape::box(Vec3(0.1, 0.1, 0.1));
  def.position = Vec3(0.1, 2.1, 0);
  const BodyId inside = world.addBody(def);
  CableDef cable;
  cable.links = {LinkDef::attachment(post, Vec3::Zero()),
                 LinkDef::rolling(wheel, 1),
                 LinkDef::attachment(inside, Vec3::Zero())};
  EXPECT_THROW(cables.addCable(cable), std::invalid_argument);
  EXPECT_EQ(world.pathCount(), 0);
  EXPECT_TRUE(cables.cables().empty());
}

}  // namespace
}  // namespace reeve::test_rest_length

namespace reeve::test_rest_length {
namespace {

TEST(CableSetup, DefaultSectionsAreTheShapesCutByTheCablePlane) {
  // A sphere of radius 0.5 cut 0.3 off its centre is a circle of radius
  // 0.4; a plane beyond a box's half height misses it.
  World world;
  CableSystem cables(world);
  BodyDef def;
  def.is_static = true;
  def.position = Vec3(-2, 0, 0.3);
  const BodyId post = world.addBody(def);
  def.position = Vec3(2, -1, 0.3);
  const BodyId end = world.addBody(def);
  def.position = Vec3::Zero();
  def.shape = Shape::sphere(0.5);
  const BodyId ball = world.addBody(def);
  CableDef cable;
  LinkDef over = LinkDef::rolling(ball, -1);
  over.plane_offset = 0.3;
  cable.links = {LinkDef::attachment(post, Vec3::Zero()), over, LinkDef::attachment(end, Vec3::Zero())};
  const int c = cables.addCable(cable);
  EXPECT_NEAR(cables.cables()[c].links[1].section.radius, 0.4, 1e-15);
  def.shape = Shape::box(Vec3(0.5, 0.5, 0.2));
  cable.links[1].body = world.addBody(def);
  EXPECT_THROW(cables.addCable(cable), std::invalid_argument);
}

}  // namespace
}  // namespace reeve::test_rest_length
