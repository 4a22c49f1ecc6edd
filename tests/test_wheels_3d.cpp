// Cable joints in 3D (paper sec. 3.4, Fig. 8-9): each wheel has its own
// cable plane; tangents between differing planes come from the Fig. 6
// iteration.
#include <gtest/gtest.h>

#include <string>

#include "reeve/cable/cable.h"
#include "reeve/scene/energy.h"
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

TEST(Wheels3D, RunOnPastItsDurationTheCableWrapsNoWheelItPassesBeside) {
  // Run on to 5 s, the heavy box hauls the light one over wheel_a (which
  // lets the cable go at 1.92 s, wheel_b at 2.75 s), and the light box
  // swings on the span from wheel_c. That span, seen in wheel_a's plane
  // (sec. 3.4), crossed wheel_a while passing more than a radius out of
  // the plane and beyond the wheel's thickness: it split onto wheel_a,
  // then merged and split between wheel_a and wheel_b until it ran out,
  // making 8.8e4 J in the frame at 2.77 s. No wheel the span passes beside
  // may take the cable. (At one substep a frame the swing differs, meets
  // wheel_b and runs out on it at 5.02 s: DESIGN's known run-out case.)
  for (const int substeps : {10, 32}) {
    SCOPED_TRACE(std::to_string(substeps) + " substeps");
    Scene s = test::scene("wheels_3d", substeps, substeps == 10 ? 2 : 32);
    const double total = s.cables->totalLength(0);
    EnergyWatch watch(s);
    int splits = 0;
    for (int f = 0; f < 300; ++f) {
      test::frame(s);
      ASSERT_FALSE(s.world->firstNonFinite()) << "t = " << s.world->time();
      for (const CableEvent& e : s.cables->takeEvents()) splits += e.kind == CableEvent::Kind::Split;
      const auto created = watch.check(s);
      ASSERT_FALSE(created) << created->created_J << " J at t = " << created->time_s;
    }
    EXPECT_EQ(splits, 0);
    EXPECT_NEAR(s.cables->totalLength(0), total, 1e-9 * total);
  }
}

}  // namespace
}  // namespace reeve
