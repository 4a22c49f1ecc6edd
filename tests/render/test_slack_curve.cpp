#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "reeve/render/slack_curve.h"

namespace reeve::test_slack_curve {
namespace {

constexpr int kSegments = 48;

double polylineLength(const std::vector<Vec3>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

struct Case {
  const char* name;
  Vec3 a, b;
  double slack;  // rest length / chord
  Vec3 down;
};

const Case kCases[] = {
    {"level", Vec3(-1, 0, 0), Vec3(1, 0, 0), 1.2, Vec3(0, -9.81, 0)},
    {"b higher", Vec3(-1, 0, 0), Vec3(1, 0.7, 0), 1.1, Vec3(0, -9.81, 0)},
    {"b lower", Vec3(0, 2, 0), Vec3(0.5, 0.1, 0.3), 1.5, Vec3(0, -1, 0)},
    {"barely loose", Vec3(-1, 0.2, 0), Vec3(1, -0.1, 0), 1.0 + 2e-4, Vec3(0, -9.81, 0)},
    {"very loose", Vec3(-0.1, 0, 0), Vec3(0.1, 0.05, 0), 20.0, Vec3(0, -9.81, 0)},
    {"steep", Vec3(0, 0, 0), Vec3(0.01, 1, 0), 1.05, Vec3(0, -9.81, 0)},
    {"tilted gravity", Vec3(0, 0, 0), Vec3(1, 1, 1), 1.3, Vec3(1, -2, 0.5)},
    {"vertical chord", Vec3(0, 1, 0), Vec3(0, 0, 0), 1.6, Vec3(0, -9.81, 0)},
};

TEST(SlackCurve, HasTheRestLengthAndEndsAtTheTiePoints) {
  for (const Case& c : kCases) {
    const double length = c.slack * (c.b - c.a).norm();
    const auto curve = slackCurve(c.a, c.b, length, c.down, kSegments);
    ASSERT_EQ(curve.size(), std::size_t(kSegments + 1)) << c.name;
    EXPECT_EQ(curve.front(), c.a) << c.name;
    EXPECT_EQ(curve.back(), c.b) << c.name;
    EXPECT_NEAR(polylineLength(curve), length, 1e-6 * length) << c.name;
    for (const Vec3& p : curve) EXPECT_TRUE(p.allFinite()) << c.name;
  }
}

// Height along -down, and the chord's height at the same horizontal place.
TEST(SlackCurve, SagsBelowTheChordOnTheGravitySide) {
  for (const Case& c : kCases) {
    const double length = c.slack * (c.b - c.a).norm();
    const auto curve = slackCurve(c.a, c.b, length, c.down, kSegments);
    const Vec3 g = c.down.normalized();
    const Vec3 d = c.b - c.a;
    const Vec3 across = d - d.dot(g) * g;
    // Every point lies in the vertical plane through the chord.
    const Vec3 normal = across.norm() > 1e-9 ? across.cross(g).normalized() : Vec3::Zero();
    double lowest = -std::numeric_limits<double>::infinity();  // depth along g
    double sag = -std::numeric_limits<double>::infinity();     // below the chord
    for (const Vec3& p : curve) {
      EXPECT_NEAR((p - c.a).dot(normal), 0.0, 1e-9) << c.name;
      lowest = std::max(lowest, (p - c.a).dot(g));
      if (across.norm() > 1e-9) {
        // On the gravity side of the chord at the same horizontal place.
        const double t = (p - c.a).dot(across) / across.squaredNorm();
        const double below = (p - (c.a + t * d)).dot(g);
        EXPECT_GE(below, -1e-9) << c.name;
        sag = std::max(sag, below);
      }
    }
    // The lowest point is no higher than the lower end (the curve may fall
    // all the way to it when barely loose), and the curve sags clearly
    // below the chord: a parabola of the same length sags
    // sqrt(3 / 8 * chord * excess) at its middle.
    const double deeper_end = std::max(0.0, d.dot(g));
    EXPECT_GE(lowest, deeper_end - 1e-12) << c.name;
    if (across.norm() > 1e-9) {
      const double excess = (c.slack - 1.0) * d.norm();
      EXPECT_GT(sag, 0.2 * std::sqrt(0.375 * across.norm() * excess)) << c.name;
    } else {
      EXPECT_GT(lowest, deeper_end + 0.4 * (c.slack - 1.0) * d.norm()) << c.name;
    }
  }
}

TEST(SlackCurve, LevelEndsHangBelowBothEnds) {
  const auto curve = slackCurve(Vec3(-1, 0, 0), Vec3(1, 0, 0), 2.0 * 1.001, Vec3(0, -9.81, 0), 48);
  double lowest = 0.0;
  for (const Vec3& p : curve) lowest = std::min(lowest, p.y());
  EXPECT_LT(lowest, -0.03);  // a parabola: sqrt(3 / 8 * 2 * 0.002) = 0.039
}

TEST(SlackCurve, LevelEndsHangSymmetricallyAsACatenary) {
  // Ends at (+-1, 0), length 2.4: y = c (cosh(x / c) - cosh(1 / c)) with
  // 2 c sinh(1 / c) = 2.4 (c = 0.8436...). The middle point is the vertex.
  const auto curve = slackCurve(Vec3(-1, 0, 0), Vec3(1, 0, 0), 2.4, Vec3(0, -1, 0), 48);
  double c = 1.0, lo = 0.1, hi = 10.0;
  for (int i = 0; i < 200; ++i) {  // bisection on 2 c sinh(1 / c) = 2.4
    c = 0.5 * (lo + hi);
    (2.0 * c * std::sinh(1.0 / c) > 2.4 ? lo : hi) = c;
  }
  const Vec3& middle = curve[24];
  EXPECT_NEAR(middle.x(), 0.0, 1e-9);
  EXPECT_NEAR(middle.y(), c * (1.0 - std::cosh(1.0 / c)), 1e-3);  // the polyline's chords cut short
  for (int i = 0; i <= 48; ++i) {
    EXPECT_NEAR(curve[i].x(), -curve[48 - i].x(), 1e-9);
    EXPECT_NEAR(curve[i].y(), curve[48 - i].y(), 1e-9);
  }
}

TEST(SlackCurve, IsTheStraightChordWhenTheLengthIsTheChord) {
  const Vec3 a(0.2, -0.3, 0.1), b(1.4, 0.9, -0.5);
  for (double length : {(b - a).norm(), 0.5 * (b - a).norm()}) {
    const auto curve = slackCurve(a, b, length, Vec3(0, -9.81, 0), 10);
    ASSERT_EQ(curve.size(), 11u);
    EXPECT_EQ(curve.front(), a);
    EXPECT_EQ(curve.back(), b);
    const Vec3 u = (b - a).normalized();
    for (int i = 0; i <= 10; ++i) {
      const Vec3 off = curve[i] - a;
      EXPECT_NEAR((off - off.dot(u) * u).norm(), 0.0, 1e-12);
      EXPECT_NEAR(off.dot(u), (b - a).norm() * i / 10.0, 1e-12);
    }
  }
}

TEST(SlackCurve, RejectsBadArguments) {
  const Vec3 a = Vec3::Zero(), b = Vec3::UnitX(), down = -Vec3::UnitY();
  EXPECT_THROW(slackCurve(a, b, 2.0, down, 1), std::invalid_argument);
  EXPECT_THROW(slackCurve(a, b, -1.0, down, 8), std::invalid_argument);
  EXPECT_THROW(slackCurve(a, b, std::numeric_limits<double>::infinity(), down, 8),
               std::invalid_argument);
  EXPECT_THROW(slackCurve(a, b, 2.0, Vec3::Zero(), 8), std::invalid_argument);
}

TEST(SlackCurve, IsSlackBeyondOnePartInTenThousand) {
  EXPECT_FALSE(isSlack(1.0, 1.0));
  EXPECT_FALSE(isSlack(1.00009, 1.0));
  EXPECT_TRUE(isSlack(1.00011, 1.0));
  EXPECT_FALSE(isSlack(0.9, 1.0));  // stretched: taut
}

}  // namespace
}  // namespace reeve::test_slack_curve
