// What the importer reads: mass properties against their closed forms,
// frames given five ways, defaults and classes, and what it lists as not
// imported.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>

#include "mjcf_fixture.h"
#include "reeve/scene/warnings.h"

namespace reeve::test {
namespace {

constexpr double pi = std::numbers::pi;

// A capsule of radius r and cylinder length l along x, density 1000, and
// a welded box: mass and moments about their joint centre against the
// closed forms (a capsule is a cylinder and a sphere split at its ends,
// each hemisphere's centre 3 r / 8 beyond them), and a body with an
// <inertial> that the geoms do not change.
TEST(MjcfModel, MassPropertiesMeetTheirClosedForms) {
  const auto path = writeModel("mass", R"(<mujoco>
  <worldbody>
    <body name="arm">
      <joint type="hinge" axis="0 0 1"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.045"/>
      <body name="weld" pos="0.5 0 0">
        <geom type="box" size="0.1 0.2 0.3" mass="3"/>
      </body>
    </body>
    <body name="given" pos="2 0 0">
      <joint type="slide" axis="1 0 0"/>
      <inertial pos="0.1 0 0" mass="4" diaginertia="0.1 0.2 0.25"/>
      <geom type="sphere" size="1"/>
    </body>
  </worldbody>
</mujoco>)");
  Scene s = parseScene(importMjcf(path).scene_json, path.string());
  const double r = 0.045, l = 0.5;
  const double m_cyl = 1000 * pi * r * r * l, m_sph = 1000 * 4.0 / 3.0 * pi * r * r * r, m_cap = m_cyl + m_sph;
  const double cap_across = m_cyl * (3 * r * r + l * l) / 12 + m_sph * (0.4 * r * r + l * l / 4 + 3 * l * r / 8);
  const double cap_axial = m_cyl * r * r / 2 + m_sph * 0.4 * r * r;
  // The capsule's centre at x = 0.25, the box's at 0.5: their centre of mass
  // and, by parallel axes, the moments about it.
  const double m = m_cap + 3.0, cx = (m_cap * 0.25 + 3.0 * 0.5) / m;
  const double box_x = 3.0 / 3.0 * (0.2 * 0.2 + 0.3 * 0.3), box_y = 3.0 / 3.0 * (0.1 * 0.1 + 0.3 * 0.3),
               box_z = 3.0 / 3.0 * (0.1 * 0.1 + 0.2 * 0.2);
  const double d_cap = 0.25 - cx, d_box = 0.5 - cx;
  const Vec3 expected(cap_axial + box_x, cap_across + m_cap * d_cap * d_cap + box_y + 3.0 * d_box * d_box,
                      cap_across + m_cap * d_cap * d_cap + box_z + 3.0 * d_box * d_box);
  const BodyState& arm = s.world->body(bodyNamed(s, "arm"));
  EXPECT_NEAR(1.0 / arm.inv_mass, m, 1e-12 * m);
  EXPECT_NEAR((arm.x - Vec3(cx, 0, 0)).norm(), 0.0, 1e-12);
  const Mat3 world_inertia = arm.q.toRotationMatrix() * arm.inertia * arm.q.toRotationMatrix().transpose();
  EXPECT_LT((world_inertia - Mat3(expected.asDiagonal())).cwiseAbs().maxCoeff(), 1e-12) << world_inertia;
  const BodyState& given = s.world->body(bodyNamed(s, "given"));
  EXPECT_EQ(1.0 / given.inv_mass, 4.0);
  EXPECT_NEAR((given.x - Vec3(2.1, 0, 0)).norm(), 0.0, 1e-12);
  const Mat3 given_inertia = given.q.toRotationMatrix() * given.inertia * given.q.toRotationMatrix().transpose();
  EXPECT_LT((given_inertia - Mat3(Vec3(0.1, 0.2, 0.25).asDiagonal())).cwiseAbs().maxCoeff(), 1e-12);
}

// One rotation written as quat, axisangle, euler (intrinsic xyz, and
// extrinsic XYZ reversed), xyaxes and zaxis (where it turns +z alone):
// every box lands with the same orientation.
TEST(MjcfModel, FiveWaysToWriteAFrameAgree) {
  // 90 degrees about x then 90 about the new z: x -> y... the matrix
  // with columns x' = (0, 1, 0)... computed below from the axis-angle form.
  const Quat q = Quat(Eigen::AngleAxisd(pi / 2, Vec3::UnitX())) * Quat(Eigen::AngleAxisd(pi / 2, Vec3::UnitZ()));
  const Mat3 R = q.toRotationMatrix();
  const Eigen::AngleAxisd aa(q);
  char xml[4096];
  std::snprintf(xml, sizeof xml, R"(<mujoco>
  <compiler angle="radian"/>
  <worldbody>
    <body name="quat" quat="%.17g %.17g %.17g %.17g"><freejoint/><geom type="box" size="0.1 0.2 0.3"/></body>
    <body name="axisangle" axisangle="%.17g %.17g %.17g %.17g"><freejoint/><geom type="box" size="0.1 0.2 0.3"/></body>
    <body name="euler" euler="1.5707963267948966 0 1.5707963267948966"><freejoint/><geom type="box" size="0.1 0.2 0.3"/></body>
    <body name="xyaxes" xyaxes="%.17g %.17g %.17g %.17g %.17g %.17g"><freejoint/><geom type="box" size="0.1 0.2 0.3"/></body>
  </worldbody>
</mujoco>)",
                q.w(), q.x(), q.y(), q.z(), aa.axis().x(), aa.axis().y(), aa.axis().z(), aa.angle(), R(0, 0), R(1, 0),
                R(2, 0), R(0, 1), R(1, 1), R(2, 1));
  const auto path = writeModel("frames", xml);
  Scene s = parseScene(importMjcf(path).scene_json, path.string());
  for (const char* name : {"quat", "axisangle", "euler", "xyaxes"})
    EXPECT_LT(s.world->body(bodyNamed(s, name)).q.angularDistance(q), 1e-12) << name;
  // Extrinsic XYZ turns about the fixed axes: the same rotation is Z then X.
  const auto extrinsic = writeModel("extrinsic", R"(<mujoco>
  <compiler angle="radian" eulerseq="ZYX"/>
  <worldbody>
    <body name="e" euler="1.5707963267948966 0 1.5707963267948966"><freejoint/><geom type="box" size="0.1 0.2 0.3"/></body>
    <body name="z" zaxis="0 -1 0"><freejoint/><geom type="sphere" size="0.1"/></body>
  </worldbody>
</mujoco>)");
  Scene e = parseScene(importMjcf(extrinsic).scene_json, extrinsic.string());
  // Fixed axes Z (first) then X: q = X * Z, the same as intrinsic x then z.
  EXPECT_LT(e.world->body(bodyNamed(e, "e")).q.angularDistance(q), 1e-12);
  // zaxis turns +z onto -y by the shortest way: about +x by 90 degrees.
  EXPECT_LT((e.world->body(bodyNamed(e, "z")).q * Vec3::UnitZ() - Vec3(0, -1, 0)).norm(), 1e-12);
}

// Attributes come from the element, else its class, else the class's
// parents, else a body's childclass; angles in degrees by default.
TEST(MjcfModel, DefaultsAndClassesApply) {
  const auto path = writeModel("defaults", R"(<mujoco>
  <default>
    <joint type="hinge" axis="0 1 0" range="-10 20"/>
    <geom density="500"/>
    <default class="outer">
      <joint axis="1 0 0"/>
      <default class="inner">
        <geom density="2000"/>
      </default>
    </default>
  </default>
  <worldbody>
    <body name="a"><joint/><geom type="box" size="0.5 0.5 0.5"/></body>
    <body name="b" childclass="inner" pos="2 0 0"><joint/><geom type="box" size="0.5 0.5 0.5"/></body>
    <body name="c" pos="4 0 0"><joint class="outer"/><geom class="inner" type="box" size="0.5 0.5 0.5" mass="7"/></body>
  </worldbody>
</mujoco>)");
  MjcfImport model = importMjcf(path);
  Scene s = parseScene(model.scene_json, path.string());
  EXPECT_NEAR(1.0 / s.world->body(bodyNamed(s, "a")).inv_mass, 500.0, 1e-9);
  EXPECT_NEAR(1.0 / s.world->body(bodyNamed(s, "b")).inv_mass, 2000.0, 1e-9);  // childclass inner, via outer
  EXPECT_NEAR(1.0 / s.world->body(bodyNamed(s, "c")).inv_mass, 7.0, 1e-12);   // mass wins over density
  ASSERT_EQ(s.world->hinges().size(), 3u);
  const auto axis = [&](int h) {
    const HingeJoint& j = s.world->hinge(h);
    return Vec3(s.world->body(j.a).q * j.frame.axis_a);
  };
  EXPECT_LT((axis(0) - Vec3::UnitY()).norm(), 1e-12);
  EXPECT_LT((axis(1) - Vec3::UnitX()).norm(), 1e-12);  // inner's parent outer's axis
  EXPECT_LT((axis(2) - Vec3::UnitX()).norm(), 1e-12);
  // range in degrees, limited by autolimits (MuJoCo 2.3's default).
  EXPECT_TRUE(s.world->hinge(0).limit.enabled);
  EXPECT_NEAR(s.world->hinge(0).limit.lower, -10.0 * pi / 180.0, 1e-15);
  EXPECT_NEAR(s.world->hinge(0).limit.upper, 20.0 * pi / 180.0, 1e-15);
}

// Everything the scene cannot carry is listed with its line, in one warning.
TEST(MjcfModel, WhatIsNotImportedIsListedWithItsLine) {
  const auto path = writeModel("unmapped", R"(<mujoco>
  <worldbody>
    <site name="s0"/>
    <body name="arm">
      <joint name="j" type="hinge" axis="0 0 1" damping="0.1" frictionloss="0.2"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.04"/>
      <site name="s1" pos="0.3 0 0"/>
    </body>
  </worldbody>
  <tendon>
    <spatial name="measured"><site site="s0"/><site site="s1"/></spatial>
    <fixed name="coupling"><joint joint="j" coef="1"/></fixed>
  </tendon>
  <actuator>
    <muscle name="m" tendon="measured"/>
  </actuator>
  <sensor><jointpos joint="j"/></sensor>
</mujoco>)");
  MjcfImport model = importMjcf(path);
  const std::string file = path.string();
  const auto listed = [&](int line, const std::string& what) {
    for (const std::string& u : model.unmapped)
      if (u.rfind(file + ":" + std::to_string(line) + ":", 0) == 0 && u.find(what) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(listed(5, "frictionloss"));
  EXPECT_TRUE(listed(11, "no range, no stiffness and no motor"));
  EXPECT_TRUE(listed(12, "fixed tendons"));
  EXPECT_TRUE(listed(15, "an actuator on a tendon that is not imported"));
  EXPECT_TRUE(listed(17, "sensor"));
  EXPECT_EQ(model.unmapped.size(), 5u);
  Scene s = parseScene(model.scene_json, file);
  s.not_imported = model.unmapped;
  const auto warnings = sceneWarnings(s);
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings.front().message.find("5 parts of the model are not imported"), std::string::npos);
  EXPECT_TRUE(s.cables->cables().empty());  // a tendon that pulls on nothing is not a cable
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

// models/meshes.xml: mesh geoms are the solids their meshes bound. The
// cube (cube.obj, quads with normals and texture coordinates, negative
// indices) at 0.2 m: 8 kg, I = m a^2 / 6 about its centre, 0.1 m along its
// turned diagonal from the geom's frame. The corner tetrahedron (tetra.stl,
// binary) at a = 0.3 m: m = 1000 a^3 / 6 = 4.5 kg at a / 4 along each
// axis, principal moments m a^2 / 16 (twice) and m a^2 / 10 (about the
// (1, 1, 1) diagonal).
TEST(MjcfModel, MeshGeomsAreTheSolidsTheirMeshesBound) {
  Scene s = importedScene("meshes");
  const BodyState& cube = s.world->body(bodyNamed(s, "cube"));
  EXPECT_NEAR(1.0 / cube.inv_mass, 8.0, 1e-12);
  const double c30 = std::cos(std::numbers::pi / 6.0), s30 = 0.5;
  EXPECT_LT((cube.x - Vec3(0.5 + 0.1 * c30 - 0.1 * s30, 0.1 * s30 + 0.1 * c30, 1.1)).norm(), 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(cube.inertia(i, i), 8.0 * 0.04 / 6.0, 1e-12);
  const BodyState& corner = s.world->body(bodyNamed(s, "corner"));
  const double m = 4.5, a = 0.3;
  EXPECT_NEAR(1.0 / corner.inv_mass, m, 1e-12);
  EXPECT_LT((corner.x - Vec3(1.0, 0.0, 1.0) - Vec3::Constant(a / 4.0)).norm(), 1e-12);
  Vec3 moments = corner.inertia.diagonal();
  std::sort(moments.data(), moments.data() + 3);
  EXPECT_LT((moments - Vec3(m * a * a / 16.0, m * a * a / 16.0, m * a * a / 10.0)).norm(), 1e-12);
  // Drawn and collided as the hull of the mesh: the cube's 8 corners.
  const Shape& shape = s.world->bodyDef(bodyNamed(s, "cube")).shape;
  ASSERT_EQ(shape.type, Shape::Type::Hull);
  EXPECT_EQ(shape.hull->vertices.size(), 8u);
  EXPECT_NEAR(shape.hull->bounding_radius, 0.1 * std::sqrt(3.0), 1e-12);
}

// An ASCII STL ("solid", "vertex" lines), named by a path the compiler's
// meshdir leads to: the same tetrahedron as models/tetra.stl (binary), the
// same solid.
TEST(MjcfModel, AsciiSTLReadsAsItsBinaryTwin) {
  const std::filesystem::path dir = writeModel("ascii_stl", "").parent_path() / "ascii_meshes";
  std::filesystem::create_directories(dir);
  std::ofstream stl(dir / "tetra.stl");
  stl << "solid tetra\n";
  for (const char* facet : {"0 0 0  0 1 0  1 0 0", "0 0 0  1 0 0  0 0 1", "0 0 0  0 0 1  0 1 0", "1 0 0  0 1 0  0 0 1"}) {
    std::istringstream corners(facet);
    stl << "  facet normal 0 0 0\n    outer loop\n";
    for (int k = 0; k < 3; ++k) {
      double x, y, z;
      corners >> x >> y >> z;
      stl << "      vertex " << x << " " << y << " " << z << "\n";
    }
    stl << "    endloop\n  endfacet\n";
  }
  stl << "endsolid tetra\n";
  stl.close();
  const auto path = writeModel("ascii_stl", R"(<mujoco>
  <compiler meshdir="ascii_meshes"/>
  <asset><mesh file="tetra.stl" scale="0.3 0.3 0.3"/></asset>
  <worldbody><body name="corner"><freejoint/><geom type="mesh" mesh="tetra" density="2000"/></body></worldbody>
</mujoco>)");
  Scene s = parseScene(importMjcf(path).scene_json, path.string());
  const BodyState& corner = s.world->body(bodyNamed(s, "corner"));
  EXPECT_NEAR(1.0 / corner.inv_mass, 9.0, 1e-12);
  EXPECT_LT((corner.x - Vec3::Constant(0.075)).norm(), 1e-12);
}

// A mesh that is not closed (a unit cube without its top) bounds no solid;
// the import takes it as MuJoCo's compiler does. Its centre: the five
// faces' pyramids from their area-weighted centre (0.5, 0.5, 0.4), the
// bottom's of height 0.4 and the sides' of 0.5, V = 0.8 m^3, each pyramid's
// centre 3/4 of the way to its face: z = (0.4 / 3 x 0.1 + 4 x 0.5 / 3 x
// 0.475) / 0.8 = 0.4125. Its volume: the pyramids again from that centre,
// (0.4125 + 4 x 0.5) / 3 m^3, 804.17 kg at 1000 kg/m^3.
TEST(MjcfModel, AnOpenMeshWeighsAsMuJoCosCompilerTakesIt) {
  const std::filesystem::path dir = writeModel("open_box", "").parent_path();
  std::ofstream(dir / "open_box.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                        "f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  const auto path = writeModel("open_box", R"(<mujoco>
  <asset><mesh file="open_box.obj"/></asset>
  <worldbody><body name="box"><freejoint/><geom type="mesh" mesh="open_box"/></body></worldbody>
</mujoco>)");
  Scene s = parseScene(importMjcf(path).scene_json, path.string());
  const BodyState& box = s.world->body(bodyNamed(s, "box"));
  EXPECT_NEAR(1.0 / box.inv_mass, 1000.0 * (0.4125 + 2.0) / 3.0, 1e-9);
  EXPECT_LT((box.x - Vec3(0.5, 0.5, 0.4125)).norm(), 1e-12);
}

}  // namespace
}  // namespace reeve::test
