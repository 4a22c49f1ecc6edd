// Cable joints in 3D (paper sec. 3.4, Fig. 8-9): each wheel has its own
// cable plane; tangents between differing planes come from the Fig. 6
// iteration.
#include <gtest/gtest.h>

#include "reeve/cable/cable.h"
#include "scene_fixture.h"

namespace reeve {
namespace {

TEST(Wheels3D, PerpendicularWheelsTransmitTheAtwoodAcceleration) {
  // a = (m2 - m1) g / (m1 + m2 + sum I / r^2), I / r^2 = M / 2 per wheel.
  Scene s = test::scene("wheels_3d");
  const BodyId heavy = test::body(s, "heavy");
  const double g = 9.81, a = (2.0 - 1.0) * g / (1.0 + 2.0 + 3 * 0.5);
  const double total = s.cables->totalLength(0);
  for (int f = 0; f < 30; ++f) test::frame(s);
  EXPECT_NEAR(-s.world->body(heavy).v.y() / s.world->time(), a, 0.01 * a);
  EXPECT_NEAR(s.cables->totalLength(0), total, 1e-9 * total);
  // Every wheel turns with the cable: |omega| r = v.
  const double v = -s.world->body(heavy).v.y();
  for (const char* w : {"wheel_a", "wheel_b", "wheel_c"})
    EXPECT_NEAR(s.world->body(test::body(s, w)).omega.norm() * 0.5, v, 0.01 * v) << w;
}

TEST(Wheels3D, TangentPointsLieInTheirWheelsPlanesOnTheRims) {
  Scene s = test::scene("wheels_3d");
  for (int f = 0; f < 30; ++f) test::frame(s);
  s.cables->update();  // tangent points for the poses as they are now
  const Cable& cable = s.cables->cables()[0];
  for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
    for (const bool start : {true, false}) {
      const Link& link = cable.links[start ? j : cable.joints[j].to];
      if (!link.rolls()) continue;
      const BodyState& body = s.world->body(link.body);
      const Vec3 p = body.toLocal(start ? s.cables->startPoint(0, j) : s.cables->endPoint(0, j));
      EXPECT_NEAR(p.z(), 0.0, 1e-9) << "joint " << j;        // in the plane
      EXPECT_NEAR(p.head<2>().norm(), 0.5, 1e-9) << "joint " << j;  // on the rim
    }
  }
  // The span between the perpendicular wheels is tangent to both rims:
  // perpendicular to each radius at its end.
  const Vec3 a = s.cables->startPoint(0, 2), b = s.cables->endPoint(0, 2);
  const Vec3 span = (b - a).normalized();
  const BodyState& wb = s.world->body(cable.links[2].body);
  const BodyState& wc = s.world->body(cable.links[3].body);
  EXPECT_NEAR(span.dot((a - wb.x).normalized()), 0.0, 1e-9);
  EXPECT_NEAR(span.dot((b - wc.x).normalized()), 0.0, 1e-9);
}

}  // namespace
}  // namespace reeve
