#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "atwood_rig.h"
#include "reeve/render/cable_path.h"
#include "reeve/render/slack_curve.h"
#include "rigs.h"

namespace reeve::test_cable_path {
namespace {

using test::AtwoodRig;

constexpr double kStep = 2.0 * std::numbers::pi / 96.0;

double maxY(const std::vector<Vec3>& path) {
  double y = -INFINITY;
  for (const Vec3& p : path) y = std::max(y, p.y());
  return y;
}

// The Atwood cable runs from the light box up its span, clockwise over the
// top of the wheel (orientation -1) and down to the heavy box.
void expectOverTheTop(const AtwoodRig& rig) {
  const auto path = test::onePath(rig.cables, rig.cable, kStep);
  const World& w = rig.world;
  EXPECT_TRUE(path.front().isApprox(w.body(rig.light_box).toWorld(Vec3(0, 0.12, 0)), 1e-12));
  EXPECT_TRUE(path.back().isApprox(w.body(rig.heavy_box).toWorld(Vec3(0, 0.15, 0)), 1e-12));
  // path: span 0 start, span 0 end (arrival), arc..., span 1 start (departure), span 1 end.
  ASSERT_GT(path.size(), 4u);
  const double r = AtwoodRig::kRadius;
  const Vec3 centre = w.body(rig.wheel).x;
  double arc_length = 0.0;
  for (std::size_t i = 1; i + 2 < path.size(); ++i) {
    const Vec3 a = path[i] - centre, b = path[i + 1] - centre;
    EXPECT_NEAR(b.norm(), r, 1e-9) << "arc point " << i + 1;
    EXPECT_NEAR(b.z(), 0.0, 1e-9);
    const double turn = std::atan2(a.cross(b).z(), a.dot(b));
    EXPECT_LT(turn, 0.0) << "clockwise, point " << i;
    EXPECT_GE(turn, -kStep - 1e-9);
    arc_length += (b - a).norm();
  }
  EXPECT_GT(maxY(path), r * std::cos(kStep));
  EXPECT_LT(maxY(path), r + 1e-9);
  EXPECT_NEAR(arc_length, rig.cables.cables()[rig.cable].links[1].stored, 1e-3 * r);
}

TEST(CablePath, AtwoodCableWrapsClockwiseOverTheTopOfTheWheel) {
  AtwoodRig rig;
  expectOverTheTop(rig);
}

TEST(CablePath, ArcFollowsTheTangentPointsAfterTheWheelTurned) {
  AtwoodRig rig;
  rig.run(30);
  ASSERT_GT(std::abs(rig.world.body(rig.wheel).omega.z()), 0.5);  // it did turn
  expectOverTheTop(rig);
}

TEST(CablePath, CounterClockwiseLinkWrapsUnderTheWheel) {
  // A sling: from an anchor up-left, counter-clockwise under the wheel, to
  // an anchor up-right.
  World world;
  CableSystem cables(world);
  BodyDef anchor;
  anchor.shape = Shape::box(Vec3(1.2, 0.05, 0.05));
  anchor.is_static = true;
  anchor.position = Vec3(0.0, 1.0, 0.0);
  const BodyId top = world.addBody(anchor);
  BodyDef wheel_def;
  wheel_def.shape = Shape::cylinder(0.3, 0.05);
  wheel_def.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3::UnitZ()));  // local != world
  const BodyId wheel = world.addBody(wheel_def);
  CableDef def;
  def.links = {test::attachment(top, Vec3(-1.0, 0.0, 0.0)), test::rolling(wheel, 1),
               test::attachment(top, Vec3(1.0, 0.0, 0.0))};
  const int c = cables.addCable(def);
  const auto path = test::onePath(cables, c, kStep);
  double min_y = INFINITY;
  for (const Vec3& p : path) min_y = std::min(min_y, p.y());
  EXPECT_LT(min_y, -0.3 * std::cos(kStep));
  EXPECT_GT(min_y, -0.3 - 1e-9);
  // Counter-clockwise: each arc point is ahead of the last by a positive angle.
  for (std::size_t i = 1; i + 2 < path.size(); ++i) {
    const double turn = std::atan2(path[i].cross(path[i + 1]).z(), path[i].dot(path[i + 1]));
    EXPECT_GT(turn, 0.0);
    EXPECT_LE(turn, kStep + 1e-9);
  }
}

double polylineLength(const std::vector<Vec3>& path, std::size_t from, std::size_t to) {
  double length = 0.0;
  for (std::size_t i = from; i < to; ++i) length += (path[i + 1] - path[i]).norm();
  return length;
}

TEST(CablePath, WrapOnASquareRunsAlongItsHullVerticesInTheOrientationSense) {
  // Clockwise (orientation -1) over the top of a square turned by 0.3 rad,
  // its cable plane 0.02 m in front of the body's middle.
  constexpr double kOffset = 0.02;
  test::SquareWheelRig rig(0.3, kOffset);
  const BodyState& wheel = rig.world.body(rig.wheel);
  const auto path = test::onePath(rig.cables, rig.cable, kStep);
  // path: light box, arrival vertex, passed vertices..., departure vertex, heavy box.
  ASSERT_GE(path.size(), 5u);
  const double h = test::SquareWheelRig::kHalf;
  double previous_angle = 0.0;
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    const Vec3 local = wheel.toLocal(path[i]);
    EXPECT_NEAR(std::abs(local.x()), h, 1e-12) << "point " << i << " is a corner";
    EXPECT_NEAR(std::abs(local.y()), h, 1e-12) << "point " << i << " is a corner";
    EXPECT_NEAR(local.z(), kOffset, 1e-12) << "in the cable plane";
    const double angle = std::atan2(local.y(), local.x());
    if (i > 1) {
      // Clockwise by a quarter turn from one corner to the next.
      double turn = angle - previous_angle;
      turn -= 2.0 * std::numbers::pi * std::round(turn / (2.0 * std::numbers::pi));
      EXPECT_NEAR(turn, -0.5 * std::numbers::pi, 1e-9) << "point " << i;
    }
    previous_angle = angle;
  }
  // The cable on the square is what the link stores.
  EXPECT_NEAR(polylineLength(path, 1, path.size() - 2),
              rig.cables.cables()[rig.cable].links[1].stored, 1e-9);
  // Tangent points still are the joints' ends.
  EXPECT_TRUE(path[1].isApprox(rig.cables.endPoint(rig.cable, 0), 1e-12));
  EXPECT_TRUE(path[path.size() - 2].isApprox(rig.cables.startPoint(rig.cable, 1), 1e-12));
}

TEST(CablePath, WrapPathOfASquareGoesTheOtherWayForTheOtherOrientation) {
  const Section square = boxSection(0.5, 0.5);
  Link link;
  link.type = LinkType::Rolling;
  link.section = square;
  BodyState body;
  const Vec3 arrival(0.5, -0.5, 0.0), departure(-0.5, 0.5, 0.0);
  link.orientation = 1;
  const auto ccw = wrapPath(link, body, arrival, departure, 0, kStep);
  ASSERT_EQ(ccw.size(), 3u);
  EXPECT_TRUE(ccw[1].isApprox(Vec3(0.5, 0.5, 0.0)));
  link.orientation = -1;
  const auto cw = wrapPath(link, body, arrival, departure, 0, kStep);
  ASSERT_EQ(cw.size(), 3u);
  EXPECT_TRUE(cw[1].isApprox(Vec3(-0.5, -0.5, 0.0)));
  // Whole extra turns pass every corner again and end at the departure.
  const auto twice = wrapPath(link, body, arrival, departure, 2, kStep);
  EXPECT_NEAR(polylineLength(twice, 0, twice.size() - 1), 2.0 + 2 * 4.0, 1e-12);
  EXPECT_TRUE(twice.back().isApprox(departure));
}

TEST(CablePath, StoredCableBeyondTheWrapDrawsWholeExtraTurns) {
  const auto build = [](test::Rig& rig, std::optional<double> stored) {
    const BodyId top = rig.addStatic(Shape::box(Vec3(1.2, 0.05, 0.05)), Vec3(0.0, 1.0, 0.0));
    const BodyId wheel = rig.addStatic(Shape::cylinder(0.3, 0.05), Vec3::Zero());
    CableDef def;
    LinkDef roll = test::rolling(wheel, 1);
    roll.stored = stored;
    def.links = {test::attachment(top, Vec3(-1.0, 0.0, 0.0)), roll,
                 test::attachment(top, Vec3(1.0, 0.0, 0.0))};
    rig.cable = rig.cables.addCable(def);
  };
  test::Rig plain;
  build(plain, std::nullopt);
  const double wrap = plain.cables.cables()[0].links[1].stored;
  const double perimeter = 2.0 * std::numbers::pi * 0.3;
  test::Rig wound;
  build(wound, wrap + 2.0 * perimeter);
  const auto path = test::onePath(wound.cables, 0, kStep);
  const double drawn = polylineLength(path, 1, path.size() - 2);
  EXPECT_NEAR(drawn, wrap + 2.0 * perimeter, 2e-3 * drawn);  // chords of a 3.75 degree step
  for (std::size_t i = 1; i + 1 < path.size(); ++i) EXPECT_NEAR(path[i].norm(), 0.3, 1e-9);
}

TEST(CablePath, DisabledJointsAreLeftOut) {
  test::InactiveLinkRig rig;
  ASSERT_FALSE(rig.cables.jointEnabled(rig.cable, 1));
  const auto path = test::onePath(rig.cables, rig.cable, kStep);
  ASSERT_EQ(path.size(), 2u);
  EXPECT_EQ(path[0], rig.world.body(rig.left).x);
  EXPECT_EQ(path[1], rig.world.body(rig.right).x);
  EXPECT_EQ(arrivingJoint(rig.cables, rig.cable, 2), 0);
  EXPECT_EQ(arrivingJoint(rig.cables, rig.cable, 1), -1);
  EXPECT_EQ(arrivingJoint(rig.cables, rig.cable, 0), -1);
}

TEST(CablePath, ClosedBeltWrapsBothWheelsAndCloses) {
  test::BeltRig rig;
  const auto path = test::onePath(rig.cables, rig.cable, kStep);
  ASSERT_GT(path.size(), 10u);
  EXPECT_LT((path.front() - path.back()).norm(), 1e-12);
  const double r = test::BeltRig::kRadius;
  // Two spans of 1.2 m and half of each wheel, as chords of kStep.
  const double expected = 2.0 * 1.2 + 2.0 * std::numbers::pi * r;
  EXPECT_NEAR(polylineLength(path, 0, path.size() - 1), expected, 2e-3 * expected);
  int on_left = 0, on_right = 0;
  for (const Vec3& p : path) {
    on_left += std::abs((p - rig.world.body(rig.left).x).norm() - r) < 1e-9;
    on_right += std::abs((p - rig.world.body(rig.right).x).norm() - r) < 1e-9;
  }
  EXPECT_GT(on_left, 40);  // half a turn at 96 steps a turn
  EXPECT_GT(on_right, 40);
  EXPECT_EQ(on_left + on_right, static_cast<int>(path.size()));
}

TEST(CablePath, ClosedBeltWhoseFirstLinkIsInactiveStartsAtTheNextAndCloses) {
  test::Rig rig;
  const BodyId idle = rig.addStatic(Shape::cylinder(0.1, 0.05), Vec3(0.0, -1.0, 0.0), "idle");
  const BodyId left = rig.addStatic(Shape::cylinder(0.25, 0.05), Vec3(-0.6, 0.0, 0.0), "left");
  const BodyId right = rig.addStatic(Shape::cylinder(0.25, 0.05), Vec3(0.6, 0.0, 0.0), "right");
  CableDef def;
  def.closed = true;
  LinkDef first = test::rolling(idle, 1);
  first.active = false;
  def.links = {first, test::rolling(left, 1), test::rolling(right, 1)};
  rig.cable = rig.cables.addCable(def);
  ASSERT_FALSE(rig.cables.jointEnabled(rig.cable, 0));
  const auto path = test::onePath(rig.cables, rig.cable, kStep);
  EXPECT_LT((path.front() - path.back()).norm(), 1e-12);
  EXPECT_TRUE(path.front().isApprox(rig.cables.endPoint(rig.cable, 2), 1e-12));  // arrives at link 1
  for (const Vec3& p : path) EXPECT_GT(p.y(), -0.26);  // nowhere near the idle wheel
  const double expected = 2.0 * 1.2 + 2.0 * std::numbers::pi * 0.25;
  EXPECT_NEAR(polylineLength(path, 0, path.size() - 1), expected, 2e-3 * expected);
}

TEST(CablePath, LooseSpanHangsWithItsRestLength) {
  test::SlackRig rig(1.3);
  const auto path = test::onePath(rig.cables, rig.cable, kStep);
  ASSERT_EQ(path.size(), std::size_t(kSlackSegments + 1));
  EXPECT_EQ(path.front(), rig.a);
  EXPECT_EQ(path.back(), rig.b);
  const double rest = rig.cables.restLength(rig.cable, 0);
  EXPECT_NEAR(polylineLength(path, 0, path.size() - 1), rest, 1e-9 * rest);
  double lowest = INFINITY;
  for (const Vec3& p : path) lowest = std::min(lowest, p.y());
  EXPECT_LT(lowest, rig.b.y() - 0.2);
  // Taut again: straight.
  rig.cables.setRestLength(rig.cable, 0, (rig.b - rig.a).norm());
  EXPECT_EQ(test::onePath(rig.cables, rig.cable, kStep).size(), 2u);
}

TEST(CablePath, LooseSpanSagsAlongTheWorldsGravity) {
  test::SlackRig rig(1.3);
  rig.world.settings().gravity = Vec3(9.81, 0.0, 0.0);  // "down" is +x
  const auto path = test::onePath(rig.cables, rig.cable, kStep);
  double furthest = -INFINITY;
  for (const Vec3& p : path) furthest = std::max(furthest, p.x());
  EXPECT_GT(furthest, rig.b.x() + 0.1);
}

// Angle turned (rad, signed, about the local z axis) along `points`, local.
double turned(const std::vector<Vec3>& points, const BodyState& body) {
  double total = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const Vec3 a = body.toLocal(points[i - 1]), b = body.toLocal(points[i]);
    total += std::atan2(a.x() * b.y() - a.y() * b.x(), a.x() * b.x() + a.y() * b.y());
  }
  return total;
}

TEST(SpoolCoil, WindsTheStoredTurnsOutwardFromTheTangentPoint) {
  constexpr double kStored = 3.0, kPitch = 0.01;
  test::SpoolRig rig(kStored, LinkType::Rolling, false);
  const BodyState& drum = rig.world.body(rig.drum);
  const auto coil = spoolCoil(rig.cables, rig.cable, 0, kPitch, kStep);
  ASSERT_GT(coil.size(), 10u);
  EXPECT_EQ(coil.front(), rig.cables.startPoint(rig.cable, 0));
  const double r = test::SpoolRig::kRadius;
  const double turns = kStored / (2.0 * std::numbers::pi * r);
  // The cable leaves clockwise (orientation -1): the coil winds back
  // counter-clockwise, a pitch further out each turn.
  EXPECT_NEAR(turned(coil, drum), 2.0 * std::numbers::pi * turns, 1e-9);
  double last = r - 1e-12;
  for (const Vec3& p : coil) {
    const Vec3 local = drum.toLocal(p);
    EXPECT_NEAR(local.z(), 0.0, 1e-12);
    EXPECT_GE(local.norm(), last - 1e-12);
    last = local.norm();
  }
  EXPECT_NEAR(last, r + turns * kPitch, 1e-9);
  // Nothing on the other end (an attachment), nothing once empty.
  EXPECT_TRUE(spoolCoil(rig.cables, rig.cable, 1, kPitch, kStep).empty());
  test::SpoolRig empty(0.0, LinkType::Rolling, false);
  EXPECT_TRUE(spoolCoil(empty.cables, empty.cable, 0, kPitch, kStep).empty());
}

TEST(SpoolCoil, OnTheLastLinkWindsOnFromTheArrival) {
  // A cable from a post to a drum that ends it, arriving counter-clockwise
  // (orientation +1): the coil carries on counter-clockwise.
  test::Rig rig;
  const BodyId post = rig.addStatic(Shape::box(Vec3(0.05, 0.05, 0.05)), Vec3(-1.0, 1.0, 0.0));
  const BodyId drum = rig.addStatic(Shape::cylinder(0.2, 0.05), Vec3::Zero());
  CableDef def;
  LinkDef end = test::rolling(drum, 1);
  end.stored = 2.0;
  def.links = {test::attachment(post), end};
  rig.cable = rig.cables.addCable(def);
  const auto coil = spoolCoil(rig.cables, rig.cable, 1, 0.005, kStep);
  ASSERT_GT(coil.size(), 10u);
  EXPECT_EQ(coil.front(), rig.cables.endPoint(rig.cable, 0));
  const double turns = 2.0 / (2.0 * std::numbers::pi * 0.2);
  EXPECT_NEAR(turned(coil, rig.world.body(drum)), 2.0 * std::numbers::pi * turns, 1e-9);
  EXPECT_NEAR(coil.back().norm(), 0.2 + turns * 0.005, 1e-9);
  EXPECT_TRUE(spoolCoil(rig.cables, rig.cable, 0, 0.005, kStep).empty());  // the post
}

TEST(SpoolCoil, CapsTheTurnsAndTheThicknessOfAFullCoil) {
  // 40 m on a 0.3 m drum: 21 turns, 20 drawn; a full coil at most as thick
  // as the radius, or as `min_full_band` on a spool smaller than that.
  test::SpoolRig rig(40.0, LinkType::Rolling, false);
  const BodyState& drum = rig.world.body(rig.drum);
  const auto wide = spoolCoil(rig.cables, rig.cable, 0, 1.0, kStep);
  EXPECT_NEAR(turned(wide, drum), 2.0 * std::numbers::pi * kMaxCoilTurns, 1e-9);
  EXPECT_NEAR(drum.toLocal(wide.back()).norm(), 0.3 + 0.3, 1e-9);
  const auto banded = spoolCoil(rig.cables, rig.cable, 0, 1.0, kStep, 0.5);
  EXPECT_NEAR(drum.toLocal(banded.back()).norm(), 0.3 + 0.5, 1e-9);
  const auto fine = spoolCoil(rig.cables, rig.cable, 0, 0.01, kStep, 0.5);
  EXPECT_NEAR(drum.toLocal(fine.back()).norm(), 0.3 + 0.2, 1e-9);
}

TEST(CablePath, APartedCableIsDrawnAsItsPiecesWithLooseEndsHanging) {
  // 1 kg and 2 kg over a hinged 2 kg wheel; the cable breaks at once (at
  // 5 N, under both loads' pulls), the heavy box's span first; the free
  // end then unwinds the wheel. Drawn: the light box's piece up over the
  // wheel, and the parted span's two ends hanging straight down, half its
  // cable each.
  test::Rig rig;
  constexpr double r = 0.3;
  const BodyId wheel = rig.addDynamic(Shape::cylinder(r, 0.06), 2.0, Vec3::Zero());
  rig.world.addHinge({wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ(), 0.0});
  const BodyId light = rig.addDynamic(Shape::box(Vec3::Constant(0.1)), 1.0, Vec3(-r, -1.2, 0.0));
  const BodyId heavy = rig.addDynamic(Shape::box(Vec3::Constant(0.1)), 2.0, Vec3(r, -1.2, 0.0));
  CableDef def;
  def.links = {test::attachment(light, Vec3(0.0, 0.1, 0.0)), test::rolling(wheel, -1),
               test::attachment(heavy, Vec3(0.0, 0.1, 0.0))};
  def.breaking_tension = 5.0;
  rig.cable = rig.cables.addCable(def);
  const double rest = rig.cables.restLength(rig.cable, 1);
  const Vec3 start = rig.cables.startPoint(rig.cable, 1), end = rig.cables.endPoint(rig.cable, 1);
  rig.world.settings().substeps = 1;
  rig.world.step(1.0 / 600.0);  // the solve overloads it; the next update parts it
  rig.world.step(1.0 / 600.0);
  ASSERT_TRUE(rig.cables.cables()[rig.cable].joints[1].parted);
  const auto paths = cablePaths(rig.cables, rig.cable, kStep);
  ASSERT_EQ(paths.size(), 3u);
  // The piece: from the light box up over the wheel.
  EXPECT_NEAR((paths[0].front() - rig.cables.startPoint(rig.cable, 0)).norm(), 0.0, 1e-12);
  EXPECT_GT(maxY(paths[0]), 0.9 * r);
  // The loose ends: straight down from where the span left and arrived
  // (the wheel and the box moved a little in the two substeps).
  for (int i : {1, 2}) {
    SCOPED_TRACE(i);
    ASSERT_EQ(paths[i].size(), 2u);
    const Vec3 hang = paths[i][1] - paths[i][0];
    EXPECT_NEAR(hang.norm(), 0.5 * rest, 1e-9);
    EXPECT_NEAR(hang.normalized().dot(-Vec3::UnitY()), 1.0, 1e-12);
    EXPECT_LT((paths[i][0] - (i == 1 ? start : end)).norm(), 1e-2);
  }
}

TEST(SpoolCoil, ShrinksAsTheSpoolPaysOutAndStopsWhenTheHybridIsTied) {
  test::SpoolRig rig(1.0);  // a hinged drum, a hybrid end
  const BodyState& drum = rig.world.body(rig.drum);
  const double before = turned(spoolCoil(rig.cables, rig.cable, 0, 0.01, kStep), drum);
  rig.run(20);
  const double after = turned(spoolCoil(rig.cables, rig.cable, 0, 0.01, kStep), drum);
  EXPECT_LT(after, before - 0.5);
  EXPECT_GT(after, 0.0);
  // Runs out (it may roll again, a yo-yo, and run out again later).
  for (int i = 0; i < 300 && !rig.cables.cables()[rig.cable].links[0].attached; ++i) rig.run(1);
  ASSERT_TRUE(rig.cables.cables()[rig.cable].links[0].attached);
  EXPECT_TRUE(spoolCoil(rig.cables, rig.cable, 0, 0.01, kStep).empty());
}

TEST(SpoolCoil, OnASquareRunsOutsideTheSquareRoundingItsCorners) {
  test::SpoolRig rig(2.0, LinkType::Hybrid, false, boxSection(0.2, 0.2));
  const BodyState& drum = rig.world.body(rig.drum);
  const auto coil = spoolCoil(rig.cables, rig.cable, 0, 0.01, kStep);
  ASSERT_GT(coil.size(), 10u);
  const Vec3 start = drum.toLocal(coil.front());
  EXPECT_NEAR(std::abs(start.x()), 0.2, 1e-12);  // a corner
  EXPECT_NEAR(std::abs(start.y()), 0.2, 1e-12);
  // 1.25 turns, counter-clockwise (the cable leaves clockwise). About the
  // centre it turns less: round a corner the coil turns on the spot.
  const double turns = 2.0 / 1.6;
  EXPECT_GT(turned(coil, drum), 2.0 * std::numbers::pi * turns - std::numbers::pi);
  EXPECT_LE(turned(coil, drum), 2.0 * std::numbers::pi * turns + 1e-9);
  double last_gap = -1e-12;
  for (const Vec3& p : coil) {
    const Vec3 local = drum.toLocal(p);
    // Distance outside the square: grows, never negative.
    const double dx = std::max(0.0, std::abs(local.x()) - 0.2);
    const double dy = std::max(0.0, std::abs(local.y()) - 0.2);
    const double gap = std::hypot(dx, dy);
    EXPECT_GE(gap, last_gap - 1e-12);
    last_gap = gap;
  }
  EXPECT_NEAR(last_gap, turns * 0.01, 1e-9);
}

TEST(SectionOutline, MatchesTheShapeOnlyWhereTheBodyShowsTheSection) {
  Link link;
  link.type = LinkType::Rolling;
  link.section = Section::circle(0.3);
  EXPECT_TRUE(sectionMatchesShape(link, Shape::cylinder(0.3, 0.1)));
  EXPECT_FALSE(sectionMatchesShape(link, Shape::cylinder(0.35, 0.1)));  // a groove
  link.plane_offset = 0.2;
  EXPECT_FALSE(sectionMatchesShape(link, Shape::cylinder(0.3, 0.1)));  // off the end
  link.plane_offset = 0.0;
  EXPECT_TRUE(sectionMatchesShape(link, Shape::sphere(0.3)));
  link.section = Section::circle(0.4);
  link.plane_offset = 0.3;
  EXPECT_TRUE(sectionMatchesShape(link, Shape::sphere(0.5)));  // cut off-centre
  link.plane_offset = 0.0;
  link.section = boxSection(0.2, 0.3);
  EXPECT_TRUE(sectionMatchesShape(link, Shape::box(Vec3(0.2, 0.3, 0.1))));
  EXPECT_FALSE(sectionMatchesShape(link, Shape::box(Vec3(0.3, 0.2, 0.1))));
  EXPECT_FALSE(sectionMatchesShape(link, Shape::cylinder(0.3, 0.1)));
  // A hull: a square pyramid (base half side 1 at z = 0, apex at z = 3;
  // centre of mass at z = 3/4) shows the square of half side 1 - z/3 that
  // its cut at z makes.
  const Shape pyramid = Shape::convexHull(
      {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0), Vec3(0, 0, 3)});
  link.plane_offset = 1.5 - 0.75;
  link.section = boxSection(0.5, 0.5);
  EXPECT_TRUE(sectionMatchesShape(link, pyramid));
  link.section = boxSection(0.6, 0.6);  // a groove
  EXPECT_FALSE(sectionMatchesShape(link, pyramid));
  link.plane_offset = 0.0;
  link.section = boxSection(0.2, 0.3);
  link.type = LinkType::Attachment;
  EXPECT_FALSE(sectionMatchesShape(link, Shape::box(Vec3(0.2, 0.3, 0.1))));

  // The outline is closed and in the cable plane.
  link.type = LinkType::Rolling;
  link.plane_offset = 0.05;
  BodyState body;
  body.x = Vec3(1, 2, 3);
  const auto outline = sectionOutline(link, body, kStep);
  ASSERT_EQ(outline.size(), 5u);
  EXPECT_EQ(outline.front(), outline.back());
  for (const Vec3& p : outline) EXPECT_NEAR(p.z(), 3.05, 1e-12);
}

}  // namespace
}  // namespace reeve::test_cable_path
