// Hull shapes in scene files: body-local coordinates are those of the
// vertices (the body's origin moves to the centre of mass), circle sections
// are placed in that frame, degenerate hulls are errors, and
// scenes/hulls.json behaves as its description claims.
#include <cmath>
#include <numbers>

#include "scene_test_util.h"

namespace reeve::test {
namespace {

// A static triangular prism, legs 1.2 (x) and 0.9 (y), 0.5 deep (z from 0):
// centre of mass (0.4, 0.3, 0.25) in its vertex frame, turned 90 deg about
// z and placed at (1, 2, 0). A cable runs from a crate over it (in its
// mid-plane, z = 0.25) to the top face of a hull cube whose vertex frame
// has its origin at a corner: centre of mass (0.1, 0.1, 0.1).
constexpr const char* kPrism = R"({
  "name": "prism",
  "solver": {},
  "bodies": [
    {"name": "cam", "static": true, "position_m": [1, 2, 0],
     "orientation": {"axis": [0, 0, 1], "angle_rad": 1.5707963267948966},
     "shape": {"type": "hull", "vertices_m": [[0, 0, 0], [1.2, 0, 0], [0, 0.9, 0],
                                               [0, 0, 0.5], [1.2, 0, 0.5], [0, 0.9, 0.5]]}},
    {"name": "crate", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]},
     "mass_kg": 1, "position_m": [2.5, 0, 0.25]},
    {"name": "weight", "mass_kg": 1, "position_m": [-0.6, 0, 0.15],
     "shape": {"type": "hull", "vertices_m": [[0, 0, 0], [0.2, 0, 0], [0, 0.2, 0], [0.2, 0.2, 0],
                                               [0, 0, 0.2], [0.2, 0, 0.2], [0, 0.2, 0.2], [0.2, 0.2, 0.2]]}}
  ],
  "cables": [{"name": "rope", "links": [
    {"body": "crate", "type": "attachment", "point_m": [0, 0.1, 0]},
    {"body": "cam", "type": "rolling", "orientation": "ccw", "plane_offset_m": 0.25},
    {"body": "weight", "type": "attachment", "point_m": [0.1, 0.2, 0.1]}]}]
})";

TEST(HullScenes, BodyLocalCoordinatesAreThoseOfTheVertices) {
  const Scene s = parseScene(kPrism, "prism.json");
  const World& w = *s.world;
  const BodyId cam = *w.findBody("cam");
  const Quat q(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()));
  const Vec3 centre(0.4, 0.3, 0.25);
  // The body sits at its centre of mass; its vertices are where the file
  // put them: position + q vertex.
  EXPECT_TRUE(w.body(cam).x.isApprox(Vec3(1, 2, 0) + q * centre, 1e-12)) << w.body(cam).x;
  const ConvexHull& hull = *w.bodyDef(cam).shape.hull;
  for (const Vec3& v : {Vec3(1.2, 0, 0), Vec3(0, 0.9, 0.5)}) {
    double nearest = 1e9;
    for (const Vec3& h : hull.vertices)
      nearest = std::min(nearest, (w.body(cam).toWorld(h) - (Vec3(1, 2, 0) + q * v)).norm());
    EXPECT_LT(nearest, 1e-12);
  }
  // Cable inputs move with the origin: the tie point (the middle of the
  // cube's top face), the cable plane (z = 0.25 of the prism's vertices is
  // its centre of mass's z = 0) and the default section, the triangle about
  // the centre of mass.
  const Cable& rope = s.cables->cables().at(0);
  EXPECT_TRUE(rope.links[2].point.isApprox(Vec3(0.0, 0.1, 0.0), 1e-12)) << rope.links[2].point;
  EXPECT_NEAR(rope.links[1].plane_offset, 0.0, 1e-12);
  const Section expected = Section::polygon({Vec2(-0.4, -0.3), Vec2(0.8, -0.3), Vec2(-0.4, 0.6)});
  ASSERT_EQ(rope.links[1].section.vertices.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_TRUE(rope.links[1].section.vertices[i].isApprox(expected.vertices[i], 1e-12));
}

TEST(HullScenes, DegenerateHullsAreErrors) {
  const std::string prism = R"([[0, 0, 0], [1.2, 0, 0], [0, 0.9, 0],
                                               [0, 0, 0.5], [1.2, 0, 0.5], [0, 0.9, 0.5]])";
  expectError(with(kPrism, prism, "[[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [2, 3, 0]]"),
              "/bodies/0/shape/vertices_m", "points spanning a volume", "5 points");
  const std::optional<SceneError> few =
      errorOf(with(kPrism, prism, "[[0, 0, 0], [1, 0, 0], [0, 1, 0]]"));
  ASSERT_TRUE(few.has_value());
  EXPECT_EQ(few->jsonPath(), "/bodies/0/shape/vertices_m");
}

TEST(HullScenes, ACircleSectionIsPlacedInTheVerticesFrame) {
  // Its centre_m, like every body-local input, is in the vertices' frame:
  // omitted, the circle lies about their origin, (-0.4, -0.3) from the
  // centre of mass; at [0.4, 0.3] it lies about the centre of mass.
  const auto centre = [](const std::string& section) {
    const Scene s = parseScene(with(kPrism, R"("plane_offset_m": 0.25})", R"("plane_offset_m": 0.25, "section": )" +
                                                                              section + "}"),
                               "prism.json");
    const Section& given = s.cables->cables().at(0).links[1].section;
    EXPECT_EQ(given.kind, Section::Kind::Circle);
    EXPECT_EQ(given.radius, 0.2);
    return given.centre;
  };
  EXPECT_TRUE(centre(R"({"radius_m": 0.2})").isApprox(Vec2(-0.4, -0.3), 1e-12));
  EXPECT_LT(centre(R"({"radius_m": 0.2, "centre_m": [0.4, 0.3]})").norm(), 1e-12);
  EXPECT_TRUE(centre(R"({"radius_m": 0.2, "centre_m": [1.4, 0.3]})").isApprox(Vec2(1.0, 0.0), 1e-12));
}

TEST(HullScenes, HullsSceneBehavesAsDescribed) {
  Scene s = loadScene(kScenesDir / "hulls.json");
  World& w = *s.world;
  const BodyId block = *w.findBody("block"), tetra = *w.findBody("tetrahedron"),
               octa = *w.findBody("octahedron");
  const double dt = 1.0 / s.frame_rate_hz;
  // Block: from rest on the 30 deg hull ramp, mu_d 0.3 (both surfaces):
  // a = g (sin 30 - 0.3 cos 30) along the ramp, within 2 %.
  const double tilt = std::numbers::pi / 6;
  const Vec3 downhill(std::cos(tilt), -std::sin(tilt), 0.0);
  const double a_expected = 9.81 * (std::sin(tilt) - 0.3 * std::cos(tilt));
  double v1 = 0.0, v2 = 0.0;
  for (int f = 1; f <= s.frameCount(); ++f) {
    w.step(dt);
    if (f == 12) v1 = w.body(block).v.dot(downhill);
    if (f == 72) v2 = w.body(block).v.dot(downhill);
  }
  const double a = (v2 - v1) / (60 * dt);
  // Resting on a face: the tetrahedron (edge 0.6) at its inradius, the
  // octahedron at the distance of its face plane x/0.3 + y/0.4 + z/0.3 = 1
  // from its centre.
  const double inradius = 0.6 / std::sqrt(24.0);
  const double octa_face = 1.0 / std::sqrt(2.0 / (0.3 * 0.3) + 1.0 / (0.4 * 0.4));
  std::printf("  block a = %.4f m/s^2 (%.4f); tetrahedron at %.5f m (%.5f), octahedron at %.5f m (%.5f)\n",
              a, a_expected, w.body(tetra).x.y(), inradius, w.body(octa).x.y(), octa_face);
  EXPECT_NEAR(a, a_expected, 0.02 * a_expected);
  EXPECT_NEAR(w.body(tetra).x.y(), inradius, 1e-3);
  EXPECT_NEAR(w.body(octa).x.y(), octa_face, 1e-3);
  for (BodyId id : {block, tetra, octa}) EXPECT_LT(w.body(id).v.norm(), 1e-2) << id;
}

}  // namespace
}  // namespace reeve::test
