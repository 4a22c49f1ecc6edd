// The cable, link and body keys load into the right CableDef, LinkDef and
// BodyDef values (read back from the CableSystem's links and the World).
#include <cmath>
#include <numbers>

#include "scene_test_util.h"

namespace reeve::test {
namespace {

using std::numbers::pi;

void expectVertices(const Section& section, const std::vector<Vec2>& expected) {
  ASSERT_EQ(section.kind, Section::Kind::Polygon);
  ASSERT_EQ(section.vertices.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_LE((section.vertices[i] - expected[i]).norm(), 1e-15)
        << i << ": " << section.vertices[i].transpose() << " vs " << expected[i].transpose();
}

// A belt around two equal wheels, both links counter-clockwise: the lower
// span runs left to right, the upper one back.
constexpr const char* kBelt = R"({
  "name": "belt", "solver": {},
  "bodies": [
    {"name": "a", "shape": {"type": "cylinder", "radius_m": 0.3, "half_length_m": 0.1},
     "static": true, "position_m": [-1, 0, 0]},
    {"name": "b", "shape": {"type": "cylinder", "radius_m": 0.3, "half_length_m": 0.1},
     "mass_kg": 1, "position_m": [1, 0, 0]}],
  "hinges": [{"body": "b", "anchor_m": [1, 0, 0], "axis": [0, 0, 1]}],
  "cables": [{"name": "belt", "closed": true, "compliance_m_per_N": 0.01,
              "rest_length_m": [2.5, 2], "links": [
    {"body": "a", "type": "rolling", "orientation": "ccw"},
    {"body": "b", "type": "rolling", "orientation": "ccw"}]}]
})";

TEST(LoadedValues, ClosedCable) {
  const Scene s = parseScene(kBelt, "belt.json");
  ASSERT_EQ(s.cables->cables().size(), 1u);
  const Cable& belt = s.cables->cables()[0];
  EXPECT_TRUE(belt.closed);
  ASSERT_EQ(belt.links.size(), 2u);
  EXPECT_EQ(belt.joints.size(), 2u);  // one per link: the last joins back to the first
  EXPECT_EQ(belt.joints[1].to, 0);
  EXPECT_DOUBLE_EQ(s.cables->restLength(0, 0), 2.5);
  EXPECT_DOUBLE_EQ(s.cables->restLength(0, 1), 2.0);
  for (const Link& link : belt.links) {
    EXPECT_EQ(link.type, LinkType::Rolling);
    EXPECT_EQ(link.orientation, 1);
    EXPECT_EQ(link.section.kind, Section::Kind::Circle);
    EXPECT_DOUBLE_EQ(link.section.radius, 0.3);
    EXPECT_NEAR(link.stored, pi * 0.3, 1e-12);  // half of each wheel: the wrapped arc
  }
}

TEST(LoadedValues, ComplianceIsOfTheWholeCable) {
  const Scene s = parseScene(kBelt, "belt.json");
  const double total = 2.5 + 2.0 + 2.0 * pi * 0.3;  // spans plus stored cable
  EXPECT_NEAR(s.cables->totalLength(0), total, 1e-12);
  EXPECT_NEAR(s.cables->cables()[0].compliance_per_m, 0.01 / total, 1e-15);
}

TEST(LoadedValues, DampingIsOfTheWholeCableAndSharedInSeries) {
  // Dashpots in series: a span of rest length L of a cable of total length
  // L0 gets damping x L0 / L (N s/m), so compliance x damping is the same
  // in every span.
  const Scene s = parseScene(with(kBelt, R"("compliance_m_per_N": 0.01,)",
                                  R"("compliance_m_per_N": 0.01, "damping_N_s_per_m": 3,)"),
                             "belt.json");
  const double total = 2.5 + 2.0 + 2.0 * pi * 0.3;
  const Cable& belt = s.cables->cables()[0];
  EXPECT_NEAR(s.world->path(belt.joints[0].path).damping, 3.0 * total / 2.5, 1e-12);
  EXPECT_NEAR(s.world->path(belt.joints[1].path).damping, 3.0 * total / 2.0, 1e-12);
  for (const CableJoint& span : belt.joints) {
    const PathConstraint& p = s.world->path(span.path);
    EXPECT_NEAR(p.compliance * p.damping, 0.01 * 3.0, 1e-15);
  }
}

TEST(LoadedValues, OpenCableIsNotClosed) {
  const Scene s = parseScene(baseWith(R"({"name": "rope",)", R"({"name": "rope", "closed": false,)"),
                             "open.json");
  EXPECT_FALSE(s.cables->cables()[0].closed);
  EXPECT_EQ(s.cables->cables()[0].joints.size(), 2u);
}

// A spool (hybrid, hub section, stored cable, plane offset) pays out through
// a pinhole, over a triangular block (polygon section, plane offset) past an
// idler the cable does not touch yet, to a hanging load.
constexpr const char* kHoist = R"({
  "name": "hoist", "solver": {},
  "bodies": [
    {"name": "spool", "shape": {"type": "cylinder", "radius_m": 0.3, "half_length_m": 0.1},
     "static": true, "position_m": [0, 2, 0]},
    {"name": "guide", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]},
     "static": true, "position_m": [2, 2, 0]},
    {"name": "block", "shape": {"type": "box", "half_extents_m": [0.3, 0.3, 0.3]},
     "mass_kg": 3, "position_m": [4, 1, 0]},
    {"name": "idler", "shape": {"type": "cylinder", "radius_m": 0.2, "half_length_m": 0.05},
     "static": true, "position_m": [6, 3, 0]},
    {"name": "load", "shape": {"type": "sphere", "radius_m": 0.2},
     "mass_kg": 1, "position_m": [4.3, -1.5, 0]}],
  "cables": [{"name": "hoist", "links": [
    {"body": "spool", "type": "hybrid", "orientation": "cw", "stored_m": 5,
     "section": {"radius_m": 0.1}, "plane_offset_m": -0.05},
    {"body": "guide", "type": "pinhole", "point_m": [0, -0.1, 0]},
    {"body": "block", "type": "rolling", "orientation": "cw", "plane_offset_m": 0.1,
     "section": {"polygon_m": [[-0.2, -0.2], [0.2, -0.2], [0, 0.3], [0, 0]]}},
    {"body": "idler", "type": "rolling", "orientation": "ccw", "active": false},
    {"body": "load", "type": "attachment", "point_m": [0, 0.2, 0]}]}]
})";

TEST(LoadedValues, HybridSpoolEnd) {
  const Scene s = parseScene(kHoist, "hoist.json");
  const Link& spool = s.cables->cables()[0].links[0];
  EXPECT_EQ(spool.type, LinkType::Hybrid);
  EXPECT_FALSE(spool.attached);
  EXPECT_EQ(spool.orientation, -1);
  EXPECT_EQ(spool.section.kind, Section::Kind::Circle);
  EXPECT_DOUBLE_EQ(spool.section.radius, 0.1);  // the hub, not the body's 0.3
  EXPECT_DOUBLE_EQ(spool.plane_offset, -0.05);
  EXPECT_DOUBLE_EQ(spool.stored, 5.0);
  EXPECT_TRUE(spool.active);
}

TEST(LoadedValues, PinholeLink) {
  const Scene s = parseScene(kHoist, "hoist.json");
  const Link& guide = s.cables->cables()[0].links[1];
  EXPECT_EQ(guide.type, LinkType::Pinhole);
  EXPECT_EQ(guide.body, *s.world->findBody("guide"));
  EXPECT_EQ(guide.point, Vec3(0, -0.1, 0));
  EXPECT_EQ(guide.stored, 0.0);
}

TEST(LoadedValues, RollingLinkOnAPolygonSection) {
  const Scene s = parseScene(kHoist, "hoist.json");
  const Link& block = s.cables->cables()[0].links[2];
  EXPECT_EQ(block.type, LinkType::Rolling);
  EXPECT_EQ(block.orientation, -1);
  EXPECT_DOUBLE_EQ(block.plane_offset, 0.1);
  EXPECT_TRUE(block.active);
  // The convex hull, counter-clockwise from the lowest x: [0, 0] is inside.
  expectVertices(block.section, {Vec2(-0.2, -0.2), Vec2(0.2, -0.2), Vec2(0, 0.3)});
  // Default for an interior link: the wrapped arc, here from the apex (where
  // the span from the pinhole arrives) down the right edge to the corner
  // [0.2, -0.2] (where the span to the load leaves).
  EXPECT_NEAR(block.stored, std::sqrt(0.2 * 0.2 + 0.5 * 0.5), 1e-12);
}

TEST(LoadedValues, InactiveRollingLink) {
  const Scene s = parseScene(kHoist, "hoist.json");
  const Cable& cable = s.cables->cables()[0];
  const Link& idler = cable.links[3];
  EXPECT_EQ(idler.type, LinkType::Rolling);
  EXPECT_FALSE(idler.active);
  EXPECT_EQ(idler.orientation, 1);
  EXPECT_EQ(idler.section.kind, Section::Kind::Circle);
  EXPECT_DOUBLE_EQ(idler.section.radius, 0.2);  // the cylinder's own
  EXPECT_EQ(idler.stored, 0.0);
  EXPECT_EQ(cable.joints[2].to, 4);  // the block's span runs past the idler to the load
  EXPECT_FALSE(s.cables->jointEnabled(0, 3));
}

TEST(LoadedValues, HoistSteps) {
  Scene s = parseScene(kHoist, "hoist.json");
  const double total = s.cables->totalLength(0);
  for (int f = 0; f < 30; ++f) s.world->step(1.0 / s.frame_rate_hz);
  for (BodyId b = 0; b < s.world->bodyCount(); ++b) EXPECT_TRUE(s.world->body(b).x.allFinite());
  EXPECT_NEAR(s.cables->totalLength(0), total, 1e-9 * total);
}

// kBase with the wheel a box and the cable's ends just outside its sides, so
// the spans touch its top corners.
std::string boxPulley() {
  std::string text =
      baseWith(R"({"type": "cylinder", "radius_m": 0.5, "half_length_m": 0.1})",
               R"({"type": "box", "half_extents_m": [0.5, 0.4, 0.1]})");
  text = with(text, R"({"body": "crate", "type": "attachment", "point_m": [0, 0.2, 0]})",
              R"({"body": "crate", "type": "attachment", "point_m": [-0.1, 0.2, 0]})");
  return with(text, R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]})",
              R"({"body": "ball", "type": "attachment", "point_m": [0.1, 0.2, 0]})");
}

TEST(LoadedValues, RollingLinkOnABoxWrapsItsRectangle) {
  const Scene s = parseScene(boxPulley(), "box.json");
  const Link& pulley = s.cables->cables()[0].links[1];
  EXPECT_EQ(pulley.type, LinkType::Rolling);
  expectVertices(pulley.section,
                 {Vec2(-0.5, -0.4), Vec2(0.5, -0.4), Vec2(0.5, 0.4), Vec2(-0.5, 0.4)});
  EXPECT_EQ(pulley.plane_offset, 0.0);
  EXPECT_NEAR(pulley.stored, 1.0, 1e-12);  // over the top edge, corner to corner
}

TEST(LoadedValues, RollingEndsOnASphereAndWithStoredCable) {
  // The rope now ends wound on the ball (default: no stored cable) and
  // starts on a crate with 2 m stored.
  std::string text =
      baseWith(R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]})",
               R"({"body": "ball", "type": "rolling", "orientation": "ccw"})");
  text = with(text, R"({"body": "crate", "type": "attachment", "point_m": [0, 0.2, 0]})",
              R"({"body": "crate", "type": "rolling", "orientation": "cw", "stored_m": 2})");
  const Scene s = parseScene(text, "ends.json");
  const Cable& cable = s.cables->cables()[0];
  const Link& crate = cable.links[0];
  EXPECT_EQ(crate.type, LinkType::Rolling);
  EXPECT_DOUBLE_EQ(crate.stored, 2.0);
  expectVertices(crate.section,
                 {Vec2(-0.2, -0.2), Vec2(0.2, -0.2), Vec2(0.2, 0.2), Vec2(-0.2, 0.2)});
  const Link& ball = cable.links[2];
  EXPECT_EQ(ball.type, LinkType::Rolling);
  EXPECT_EQ(ball.orientation, 1);
  EXPECT_EQ(ball.section.kind, Section::Kind::Circle);
  EXPECT_DOUBLE_EQ(ball.section.radius, 0.2);
  EXPECT_EQ(ball.stored, 0.0);
}

TEST(LoadedValues, BodyDamping) {
  const Scene s = parseScene(
      baseWith(R"("mass_kg": 2,)",
               R"("mass_kg": 2, "linear_damping_per_s": 0.5, "angular_damping_per_s": 0.25,)"),
      "damped.json");
  EXPECT_EQ(s.world->bodyDef(1).linear_damping, 0.5);
  EXPECT_EQ(s.world->bodyDef(1).angular_damping, 0.25);
  EXPECT_EQ(s.world->body(1).linear_damping, 0.5);
  EXPECT_EQ(s.world->body(1).angular_damping, 0.25);
  EXPECT_EQ(s.world->body(2).linear_damping, 0.0);
  EXPECT_EQ(s.world->body(2).angular_damping, 0.0);
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

TEST(LoadedValues, SpeedGuards) {
  const Scene none = parseScene(kBase, "test.json");
  EXPECT_TRUE(std::isinf(none.world->settings().max_linear_speed));
  const Scene s = parseScene(
      baseWith(R"("solver": {})", R"("solver": {"max_linear_speed_m_per_s": 12.5, "max_angular_speed_rad_per_s": 300})"),
      "test.json");
  EXPECT_EQ(s.world->settings().max_linear_speed, 12.5);
  EXPECT_EQ(s.world->settings().max_angular_speed, 300.0);
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

// inertia_kg_m2 replaces the shape's moments: a box of 2 kg spinning at
// (1, 2, 0) rad/s about its axes with moments (2, 3, 4) kg m^2 carries
// (2 x 1 + 3 x 4) / 2 = 7 J, whatever its half extents say (they would give
// 1/3 x 2 x (0.5^2 + 0.5^2) = 0.33 kg m^2 about each axis).
TEST(LoadedValues, GivenMomentsOfInertiaReplaceTheShapes) {
  const Scene s = parseScene(R"({"name": "spin", "solver": {}, "bodies": [
    {"name": "box", "shape": {"type": "box", "half_extents_m": [0.5, 0.5, 0.5]}, "mass_kg": 2,
     "inertia_kg_m2": [2, 3, 4], "position_m": [0, 0, 0], "angular_velocity_rad_per_s": [1, 2, 0]}]})",
                             "spin.json");
  EXPECT_EQ(s.world->body(0).inertia, Mat3(Vec3(2, 3, 4).asDiagonal()));
  EXPECT_DOUBLE_EQ(s.world->energy().kinetic, 7.0);
}

// A hull with given moments stays about position_m, its centre of mass
// then (the hull's own centre, (0.5, 0.5, 0.5) of this unit cube, is not):
// without them the body moves to the hull's centre, as always.
TEST(LoadedValues, AHullWithGivenMomentsStaysAboutItsPosition) {
  const std::string cube = R"({"name": "cube", "solver": {}, "bodies": [
    {"name": "c", "shape": {"type": "hull", "vertices_m": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1]]},
     "mass_kg": 1, INERTIA "position_m": [0, 0, 0]}]})";
  const auto with = [&](const std::string& inertia) {
    std::string text = cube;
    text.replace(text.find("INERTIA"), 7, inertia);
    return parseScene(text, "cube.json");
  };
  const Scene given = with(R"("inertia_kg_m2": [1, 1, 1],)");
  EXPECT_EQ(given.world->body(0).x, Vec3::Zero());
  EXPECT_NEAR(given.world->bodyDef(0).shape.hull->bounding_radius, std::sqrt(3.0), 1e-15);
  const Scene own = with("");
  EXPECT_LT((own.world->body(0).x - Vec3::Constant(0.5)).norm(), 1e-15);
  EXPECT_NEAR(own.world->bodyDef(0).shape.hull->bounding_radius, std::sqrt(0.75), 1e-15);
}

}  // namespace
}  // namespace reeve::test
