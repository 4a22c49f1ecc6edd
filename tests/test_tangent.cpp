// Appendix A: common tangents of points and discs for every orientation
// combination, checked against geometry rather than against a copy of the
// formula.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "reeve/cable/section.h"

namespace reeve::test_tangent {
namespace {

Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }

// A span leaving `from` at p with unit direction t travels around `from` in
// its orientation sense: t = o * perp(outward normal). Same on arrival.
void expectValidTangent(const CableCircle& from, const CableCircle& to, const TangentPoints& tp) {
  const Vec2 span = tp.on_to - tp.on_from;
  ASSERT_GT(span.norm(), 1e-9);
  const Vec2 t = span.normalized();
  for (const auto& [circle, p] : {std::pair{from, tp.on_from}, std::pair{to, tp.on_to}}) {
    const Vec2 radial = p - circle.center;
    EXPECT_NEAR(radial.norm(), circle.radius, 1e-9);  // on the circle
    if (circle.radius == 0.0) continue;
    const Vec2 m = radial / circle.radius;
    EXPECT_NEAR(m.dot(t), 0.0, 1e-9);  // perpendicular to the radius
    EXPECT_NEAR((circle.orientation * perp(m) - t).norm(), 0.0, 1e-9)  // winding sense
        << "orientation " << circle.orientation;
  }
}

TEST(Tangent, DiscDiscAllFourOrientationsOnRandomConfigurations) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-5.0, 5.0), rad(0.05, 2.0);
  int checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec2 c1(pos(rng), pos(rng)), c2(pos(rng), pos(rng));
    const double r1 = rad(rng), r2 = rad(rng);
    if ((c2 - c1).norm() <= r1 + r2 + 1e-3) continue;  // all four tangents exist
    for (int o1 : {-1, 1})
      for (int o2 : {-1, 1}) {
        const CableCircle a{c1, r1, o1}, b{c2, r2, o2};
        const auto tp = commonTangent(a, b);
        ASSERT_TRUE(tp.has_value());
        expectValidTangent(a, b, *tp);
        ++checked;
      }
  }
  EXPECT_GT(checked, 4000);
}

TEST(Tangent, PointDiscBothOrdersAndOrientations) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(-5.0, 5.0), rad(0.05, 2.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const Vec2 p(pos(rng), pos(rng)), c(pos(rng), pos(rng));
    const double r = rad(rng);
    if ((c - p).norm() <= r + 1e-3) continue;
    for (int o : {-1, 1}) {
      const CableCircle point{p, 0.0, 1}, disc{c, r, o};
      const auto in = commonTangent(point, disc);
      const auto out = commonTangent(disc, point);
      ASSERT_TRUE(in && out);
      expectValidTangent(point, disc, *in);
      expectValidTangent(disc, point, *out);
      EXPECT_NEAR((in->on_from - p).norm(), 0.0, 1e-12);
    }
  }
}

TEST(Tangent, MatchesPaperAlgorithm3ForPointCircle) {
  // Alg. 3 transcribed: alpha = direction of d = p2 - p1; phi = asin(r/|d|);
  // positive orientation: alpha - pi/2 - phi, else alpha + pi/2 + phi.
  const Vec2 p1(0.3, -1.2), p2(2.0, 0.7);
  const double r = 0.6;
  const Vec2 d = p2 - p1;
  const double alpha = std::atan2(d.y(), d.x());
  const double phi = std::asin(r / d.norm());
  for (int o : {-1, 1}) {
    const double a = o > 0 ? alpha - std::numbers::pi / 2 - phi : alpha + std::numbers::pi / 2 + phi;
    const Vec2 expected = p2 + r * Vec2(std::cos(a), std::sin(a));
    const auto tp = commonTangent({p1, 0.0, 1}, {p2, r, o});
    ASSERT_TRUE(tp);
    EXPECT_NEAR((tp->on_to - expected).norm(), 0.0, 1e-12);
  }
}

TEST(Tangent, NoTangentWhenTheSpanWouldCrossAnOverlap) {
  // Crossed tangents of overlapping discs and a point inside a disc do not exist.
  EXPECT_FALSE(commonTangent({Vec2(0, 0), 1.0, 1}, {Vec2(1.5, 0), 1.0, -1}));
  EXPECT_FALSE(commonTangent({Vec2(0.2, 0), 0.0, 1}, {Vec2(0, 0), 1.0, 1}));
  // Equal orientation on overlapping discs still has its outer tangent.
  EXPECT_TRUE(commonTangent({Vec2(0, 0), 1.0, 1}, {Vec2(1.5, 0), 1.0, 1}));
}

TEST(SurfaceDistance, SignFollowsOrientationAndArcLengthIsRadiusTimesAngle) {
  const double r = 0.4, angle = 0.3;
  const Vec2 old_point = r * Vec2(std::cos(1.0 + angle), std::sin(1.0 + angle));
  const Vec2 new_point = r * Vec2(std::cos(1.0), std::sin(1.0));
  // From new to old is counter-clockwise by `angle`.
  EXPECT_NEAR(sectionSurfaceDistance(Section::circle(r), old_point, new_point, +1), r * angle, 1e-14);
  EXPECT_NEAR(sectionSurfaceDistance(Section::circle(r), old_point, new_point, -1), -r * angle, 1e-14);
  EXPECT_NEAR(sectionSurfaceDistance(Section::circle(r), new_point, old_point, +1), -r * angle, 1e-14);
}

TEST(WrappedArc, MeasuresInTheOrientationSenseOverAFullTurn) {
  const double r = 2.0;
  const Vec2 east(r, 0), north(0, r), south(0, -r);
  EXPECT_NEAR(sectionWrappedArc(Section::circle(r), east, north, +1), r * std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(sectionWrappedArc(Section::circle(r), east, north, -1), r * 3 * std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(sectionWrappedArc(Section::circle(r), south, north, +1), r * std::numbers::pi, 1e-12);
}

}  // namespace
}  // namespace reeve::test_tangent
