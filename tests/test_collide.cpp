// Narrow phase (collide.h): the manifold of a face on a face is the clip of
// the incident face to the reference face, with exact depths; nearly
// touching pairs within the contact margin give contacts with a gap; two
// curved surfaces touch through both axes, and their contact is measured
// again where they touch when the solve moves them; a sphere on a box,
// hull or cylinder, and a log beyond a box's edge, touch along the line
// from the centre's or axis' nearest point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "reeve/engine/collide.h"
#include "reeve/engine/contact.h"
#include "reeve/engine/shape.h"

namespace reeve::test_collide {
namespace {

using std::numbers::pi;

BodyState at(const Vec3& x, const Quat& q = Quat::Identity()) {
  BodyState s;
  s.x = s.x_prev = x;
  s.q = s.q_prev = q;
  s.inv_mass = 1.0;
  return s;
}

/// Separation (m) along the normal of a contact's two points: < 0 overlaps.
double separation(const Contact& c, const BodyState& a, const BodyState& b) {
  return (b.toWorld(c.local_b) - a.toWorld(c.local_a)).dot(c.normal);
}

std::vector<Contact> collide(const Shape& sa, const BodyState& a, const Shape& sb,
                             const BodyState& b) {
  std::vector<Contact> out;
  collideBodies(0, sa, a, 1, sb, b, ContactMaterial{}, out);
  return out;
}

TEST(Collide, SmallBoxOnBigBoxTouchesAtItsFourCornersWithTheExactDepth) {
  // A 0.5 m cube turned 30 deg about y sinks 1 mm into a 1 m cube.
  const Shape big = Shape::box(Vec3(0.5, 0.5, 0.5)), small = Shape::box(Vec3(0.25, 0.25, 0.25));
  const Quat yaw(Eigen::AngleAxisd(pi / 6.0, Vec3::UnitY()));
  const BodyState a = at(Vec3(0.0, 0.5, 0.0)), b = at(Vec3(0.1, 1.249, -0.05), yaw);
  const std::vector<Contact> contacts = collide(big, a, small, b);
  ASSERT_EQ(contacts.size(), 4u);
  for (const Contact& c : contacts) {
    EXPECT_NEAR((c.normal - Vec3::UnitY()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(separation(c, a, b), -1e-3, 1e-12);
    // At a bottom corner of the small cube.
    EXPECT_NEAR(std::abs(c.local_b.x()), 0.25, 1e-12);
    EXPECT_NEAR(c.local_b.y(), -0.25, 1e-12);
    EXPECT_NEAR(std::abs(c.local_b.z()), 0.25, 1e-12);
  }
}

TEST(Collide, BigBoxOnSmallBoxTouchesAtTheSmallTopCorners) {
  // The reference face is the small box's top; the big box's face is
  // clipped to it, so the points are above the small box's corners.
  const Shape big = Shape::box(Vec3(0.5, 0.5, 0.5)), small = Shape::box(Vec3(0.25, 0.25, 0.25));
  const BodyState a = at(Vec3(0.0, 0.25, 0.0)), b = at(Vec3(0.05, 0.998, 0.0));
  const std::vector<Contact> contacts = collide(small, a, big, b);
  ASSERT_EQ(contacts.size(), 4u);
  for (const Contact& c : contacts) {
    EXPECT_NEAR(separation(c, a, b), -2e-3, 1e-12);
    EXPECT_NEAR(std::abs(c.local_a.x()), 0.25, 1e-12);
    EXPECT_NEAR(c.local_a.y(), 0.25, 1e-12);
    EXPECT_NEAR(std::abs(c.local_a.z()), 0.25, 1e-12);
  }
}

TEST(Collide, BoxOnAnEdgeTouchesAtTheEdgeEnds) {
  // A cube rolled 45 deg about z stands on its edge, 0.5 mm deep.
  const Shape cube = Shape::box(Vec3(0.5, 0.5, 0.5));
  const Quat roll(Eigen::AngleAxisd(pi / 4.0, Vec3::UnitZ()));
  const BodyState a = at(Vec3(0.0, 0.5, 0.0)), b = at(Vec3(0.0, 1.0 + std::sqrt(0.5) - 5e-4, 0.0), roll);
  const std::vector<Contact> contacts = collide(cube, a, cube, b);
  ASSERT_EQ(contacts.size(), 2u);
  for (const Contact& c : contacts) {
    EXPECT_NEAR(separation(c, a, b), -5e-4, 1e-12);
    EXPECT_NEAR(b.toWorld(c.local_b).x(), 0.0, 1e-12);
    EXPECT_NEAR(std::abs(b.toWorld(c.local_b).z()), 0.5, 1e-12);
  }
}

TEST(Collide, CylinderOnItsSideTouchesAlongItsLowestLine) {
  // Axis along x, 0.2 mm deep: the ends of the bottom line, at x = +-0.4.
  const Shape slab = Shape::box(Vec3(1.0, 0.1, 1.0)), log = Shape::cylinder(0.3, 0.4);
  const Quat along_x(Eigen::AngleAxisd(pi / 2.0, Vec3::UnitY()));
  const BodyState a = at(Vec3(0.0, 0.0, 0.0)), b = at(Vec3(0.2, 0.4 - 2e-4, 0.1), along_x);
  const std::vector<Contact> contacts = collide(slab, a, log, b);
  ASSERT_EQ(contacts.size(), 2u);
  for (const Contact& c : contacts) {
    EXPECT_NEAR(separation(c, a, b), -2e-4, 1e-12);
    const Vec3 p = b.toWorld(c.local_b);
    EXPECT_NEAR(std::abs(p.x() - 0.2), 0.4, 1e-12);
    EXPECT_NEAR(p.z(), 0.1, 1e-12);
  }
}

TEST(Collide, NearlyTouchingBoxesGiveGapContactsWithinTheMarginOnly) {
  // 1 mm apart: inside the 2 % margin (17 mm for unit cubes), so four
  // contacts with separation +1 mm; 5 cm apart: none.
  const Shape cube = Shape::box(Vec3(0.5, 0.5, 0.5));
  EXPECT_NEAR(contactMargin(cube, cube), 0.02 * std::sqrt(0.75), 1e-15);
  const BodyState a = at(Vec3(0.0, 0.5, 0.0));
  const BodyState near = at(Vec3(0.0, 1.501, 0.0)), far = at(Vec3(0.0, 1.55, 0.0));
  const std::vector<Contact> contacts = collide(cube, a, cube, near);
  ASSERT_EQ(contacts.size(), 4u);
  for (const Contact& c : contacts) EXPECT_NEAR(separation(c, a, near), 1e-3, 1e-12);
  EXPECT_TRUE(collide(cube, a, cube, far).empty());
}

TEST(Collide, ThinRodOnAWheelTouchesOnTheRadiusThroughBothAxes) {
  // A rope segment (radius 0.01 m) lying on a wheel (radius 0.3 m, axle
  // along z), tangent to it at angle phi, up to 1.5 cm deep, shifted along
  // itself and along the axle, either body first. Two cylinders whose sides
  // touch push along the common perpendicular of their axes: the wheel's
  // radius to the rod, never along the axle, by exactly the overlap, and
  // through both axes, so that the push turns neither the rod about its
  // own axis (its inertia about it is tiny) nor the wheel about its axle.
  // (MPR's point lies up to 2 um beside the rod's axis.)
  for (const double half_length : {0.05, 0.25})
    for (int k = 0; k < 24; ++k) {
      const double phi = 2.0 * pi * k / 24.0 + 0.1;
      const double depth = 0.015 * (k % 4) / 3.0;
      const double along = 0.03 * ((k % 3) - 1), z = (half_length - 0.03) * ((k % 5) / 2.0 - 1.0);
      const Vec3 radial(std::cos(phi), std::sin(phi), 0.0), tangent(-std::sin(phi), std::cos(phi), 0.0);
      const Shape wheel = Shape::cylinder(0.3, half_length), rod = Shape::cylinder(0.01, 0.08);
      const BodyState w = at(Vec3::Zero());
      const BodyState r = at((0.31 - depth) * radial + along * tangent + Vec3(0.0, 0.0, z),
                             rotationBetween(Vec3::UnitZ(), tangent));
      for (const bool wheel_first : {true, false}) {
        SCOPED_TRACE(testing::Message() << "half length " << half_length << ", phi " << phi << ", depth "
                                        << depth << (wheel_first ? ", wheel first" : ", rod first"));
        const std::vector<Contact> contacts = wheel_first ? collide(wheel, w, rod, r) : collide(rod, r, wheel, w);
        ASSERT_EQ(contacts.size(), 1u);
        const Contact& c = contacts.front();
        const BodyState &a = wheel_first ? w : r, &b = wheel_first ? r : w;
        const Vec3 n = wheel_first ? c.normal : Vec3(-c.normal);  // out of the wheel
        EXPECT_NEAR((n - radial).norm(), 0.0, 1e-6);
        EXPECT_NEAR(separation(c, a, b), -depth, 1e-9);
        const Vec3 on_rod = (wheel_first ? b : a).toWorld(wheel_first ? c.local_b : c.local_a);
        const Vec3 on_wheel = (wheel_first ? a : b).toWorld(wheel_first ? c.local_a : c.local_b);
        // Lever of the push about the rod's axis and about the axle (m).
        EXPECT_LT(std::abs((on_rod - r.x).cross(n).dot(tangent)), 1e-12);
        EXPECT_LT(std::abs(on_wheel.cross(n).z()), 1e-12);
      }
    }
}

TEST(Collide, ARodTurnedAboutWhereItFirstTouchedIsPushedOutWhereItTouchesNow) {
  // A rope segment (radius 0.01 m, 6 cm long) lies on a fixed wheel
  // (radius 0.3 m), touching at its middle. A solve then turns it about its
  // middle by theta, as its joints do when the chain pulls one end down:
  // one half rises, the other sinks into the wheel, 0.31 - 0.31 cos(theta)
  // at the closest point of its axis or more at its end (0.4 mm at 0.05
  // rad, 4.5 mm at 0.2). The contact, measured again where the two axes are
  // now closest, pushes the rod out until its axis is 0.31 m from the
  // axle. Held at the point found first, which rose, it pushed nothing, and
  // the rod pivoted about that point from solve to solve: the segmented
  // rope's rods rocked on the wheel until the chain flew apart at 100
  // substeps of one iteration (DESIGN, "Forty-fifth session").
  const Shape wheel = Shape::cylinder(0.3, 0.05), rod = Shape::cylinder(0.01, 0.03);
  const auto overlap = [](const BodyState& r) {  // of the rod's axis into the 0.31 m circle (m)
    const Vec3 u = r.q * Vec3::UnitZ();
    const double s = std::clamp(-r.x.dot(u), -0.03, 0.03);
    return 0.31 - (r.x + s * u).norm();
  };
  for (const double theta : {0.05, 0.2, -0.3})
    for (const bool wheel_first : {true, false}) {
      SCOPED_TRACE(testing::Message() << "theta " << theta << (wheel_first ? ", wheel first" : ", rod first"));
      BodyState w = at(Vec3::Zero());
      w.inv_mass = 0.0;
      BodyState r = at(Vec3(0.0, 0.31, 0.0), rotationBetween(Vec3::UnitZ(), Vec3::UnitX()));
      r.inv_mass = 1e4;  // 0.1 g, as the shipped rope's rods
      r.inv_inertia = inertiaTensor(rod, 1e-4).inverse();
      std::vector<Contact> contacts;
      collideBodies(0, wheel_first ? wheel : rod, wheel_first ? w : r, 1, wheel_first ? rod : wheel,
                    wheel_first ? r : w, ContactMaterial{0.0, 0.0, 0.0}, contacts);
      ASSERT_EQ(contacts.size(), 1u);
      EXPECT_GE(contacts.front().core_a, 0.0);
      r.q = Quat(Eigen::AngleAxisd(theta, Vec3::UnitZ())) * r.q;
      EXPECT_GT(overlap(r), 3e-4);
      ContactManifold m;
      m.a = 0;
      m.b = 1;
      m.count = 1;
      EXPECT_TRUE(solveContactPositions(m, contacts.data(), wheel_first ? w : r, wheel_first ? r : w));
      EXPECT_LT(overlap(r), 1e-9);
      EXPECT_EQ(w.x, Vec3::Zero());
    }
}

// A sphere (0.1 m) on a turned box or on a hull of its corners, over its
// top face, beyond its top edge and beyond its corner, and on a drum over
// its cap, beyond its rim and beside its side: the normal runs from
// the centre's nearest point of the body to the centre, the separation is
// their distance less the radius, and the contact carries both cores. MPR
// gave an upright normal beyond the edge (the ball rested there, 0.8 mm
// above it) and an overlap of 0.66 mm where there was none.
TEST(Collide, ASphereOnABoxHullOrCylinderTakesItsNormalFromItsCentresNearestPoint) {
  const Vec3 half(0.5, 0.4, 0.3);
  std::vector<Vec3> corners;
  for (const double x : {-1.0, 1.0})
    for (const double y : {-1.0, 1.0})
      for (const double z : {-1.0, 1.0}) corners.push_back(half.cwiseProduct(Vec3(x, y, z)));
  const Shape ball = Shape::sphere(0.1);
  const Quat turn(Eigen::AngleAxisd(0.4, Vec3(0.2, 1.0, 0.1).normalized()));
  const BodyState table = at(Vec3(2.0, 1.0, 0.3), turn);
  struct Case {
    const char* what;
    Vec3 nearest, out;  // table-local
    double gap;         // m
  };
  for (const Shape& solid : {Shape::box(half), Shape::convexHull(corners)})
    for (const Case& c : {Case{"over the face", Vec3(0.2, 0.4, -0.1), Vec3::UnitY(), -1e-3},
                          Case{"beyond the edge", Vec3(0.5, 0.4, 0.1), Vec3(0.02, 1.0, 0.0), 0.0},
                          Case{"beyond the corner", half, Vec3(1.0, 2.0, 1.5), -2e-4},
                          Case{"off the edge", Vec3(0.5, 0.4, 0.1), Vec3(1.0, 0.3, 0.0), 1e-4}})
      for (const bool solid_first : {true, false}) {
        SCOPED_TRACE(testing::Message() << (solid.type == Shape::Type::Box ? "box, " : "hull, ") << c.what
                                        << (solid_first ? ", solid first" : ", sphere first"));
        const Vec3 out = turn * c.out.normalized();
        const BodyState sphere = at(table.toWorld(c.nearest) + (0.1 + c.gap) * out);
        const std::vector<Contact> contacts =
            solid_first ? collide(solid, table, ball, sphere) : collide(ball, sphere, solid, table);
        ASSERT_EQ(contacts.size(), 1u);
        const Contact& k = contacts.front();
        const BodyState &a = solid_first ? table : sphere, &b = solid_first ? sphere : table;
        EXPECT_NEAR((k.normal - (solid_first ? out : Vec3(-out))).norm(), 0.0, 1e-12);
        EXPECT_NEAR(separation(k, a, b), c.gap, 1e-12);
        EXPECT_NEAR((table.toWorld(solid_first ? k.local_a : k.local_b) - table.toWorld(c.nearest)).norm(), 0.0, 1e-12);
        EXPECT_GE(k.core_a, 0.0);
        EXPECT_EQ((solid_first ? k.solid_a : k.solid_b).kind,
                  solid.type == Shape::Type::Box ? ContactSolid::Kind::Box : ContactSolid::Kind::Hull);
      }
  // A drum (r 0.5 m, half length 0.4 m) standing on its cap: over the cap,
  // beyond its rim, beside its side; the side's normal passes through the
  // axis as a curved pair's did.
  const Shape drum = Shape::cylinder(0.5, 0.4);
  const BodyState stand = at(Vec3(2.0, 1.0, 0.3), turn * Quat(Eigen::AngleAxisd(-pi / 2.0, Vec3::UnitX())));
  for (const Case& c : {Case{"over the cap", Vec3(0.1, 0.2, 0.4), Vec3::UnitZ(), -1e-3},
                        Case{"beyond the rim", Vec3(0.3, 0.4, 0.4), Vec3(0.6, 0.8, 2.0), 0.0},
                        Case{"beside the side", Vec3(0.0, -0.5, -0.1), Vec3(0.0, -1.0, 0.0), 5e-4}}) {
    SCOPED_TRACE(testing::Message() << "drum, " << c.what);
    const Vec3 out = stand.q * c.out.normalized();
    const BodyState sphere = at(stand.toWorld(c.nearest) + (0.1 + c.gap) * out);
    const std::vector<Contact> contacts = collide(drum, stand, ball, sphere);
    ASSERT_EQ(contacts.size(), 1u);
    const Contact& k = contacts.front();
    EXPECT_NEAR((k.normal - out).norm(), 0.0, 1e-12);
    EXPECT_NEAR(separation(k, stand, sphere), c.gap, 1e-12);
    EXPECT_NEAR((stand.toWorld(k.local_a) - stand.toWorld(c.nearest)).norm(), 0.0, 1e-12);
    EXPECT_EQ(k.solid_a.kind, ContactSolid::Kind::Cylinder);
  }
}

// A log (r 0.1 m, half length 0.2 m) beyond a turned box's top edge, lying
// along it and skewed 0.3 rad across it (turned about the normal): the
// normal runs from the edge to the axis, at the middle of where the axis
// runs along the edge, or where the skewed axis passes nearest it. Lengthwise over the edge a cap
// touches, which stays MPR's (no solid core).
TEST(Collide, ALogBeyondABoxsEdgeTakesItsNormalFromTheEdgeToItsAxis) {
  const Vec3 half(0.5, 0.4, 0.3);
  const Shape box = Shape::box(half), log = Shape::cylinder(0.1, 0.2);
  const Quat turn(Eigen::AngleAxisd(0.4, Vec3(0.2, 1.0, 0.1).normalized()));
  const BodyState table = at(Vec3(2.0, 1.0, 0.3), turn);
  const Vec3 out = turn * Vec3(0.2, 1.0, 0.0).normalized();  // between the top's and the side's normals
  for (const double skew : {0.0, 0.3}) {
    SCOPED_TRACE(testing::Message() << "skew " << skew);
    const Vec3 on_edge = table.toWorld(Vec3(0.5, 0.4, 0.05));
    const Quat along = Quat(Eigen::AngleAxisd(skew, out)) * turn;  // the axis turned about the normal
    const BodyState body = at(on_edge + 0.1005 * out, along);  // 0.5 mm apart
    const std::vector<Contact> contacts = collide(box, table, log, body);
    ASSERT_EQ(contacts.size(), 1u);
    const Contact& k = contacts.front();
    EXPECT_NEAR((k.normal - out).norm(), 0.0, 1e-7);
    EXPECT_NEAR(separation(k, table, body), 5e-4, 1e-9);
    EXPECT_NEAR((table.toWorld(k.local_a) - on_edge).norm(), 0.0, 1e-7);
    EXPECT_EQ(k.solid_a.kind, ContactSolid::Kind::Box);
  }
  const BodyState lengthwise = at(table.toWorld(Vec3(0.5 + 0.15, 0.4 + 0.0995, 0.0)), turn * rotationBetween(Vec3::UnitZ(), Vec3::UnitX()));
  const std::vector<Contact> capped = collide(box, table, log, lengthwise);
  ASSERT_FALSE(capped.empty());
  EXPECT_EQ(capped.front().solid_a.kind, ContactSolid::Kind::None);
}

}  // namespace
}  // namespace reeve::test_collide
