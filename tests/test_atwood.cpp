// Atwood machine with a massive wheel (solid cylinder, I = M r^2 / 2):
// a = (m2 - m1) g / (m1 + m2 + I / r^2), T1 = m1 (g + a), T2 = m2 (g - a).
#include <gtest/gtest.h>

#include "atwood_machine.h"

namespace reeve::test_atwood {
namespace {

void expectAnalytic(double m1, double m2, int substeps, int iterations) {
  Atwood a(m1, m2, substeps, iterations);
  const int frames = 30;  // 0.5 s at 60 Hz
  for (int f = 0; f < frames; ++f) a.world.step(1.0 / 60.0);
  const double t = a.world.time();
  const double acc = a.acceleration();
  EXPECT_NEAR(-a.world.body(a.box2).v.y() / t, acc, 0.01 * acc);
  EXPECT_NEAR(a.world.body(a.box1).v.y() / t, acc, 0.01 * acc);
  const double t1 = m1 * (a.g + acc), t2 = m2 * (a.g - acc);
  EXPECT_NEAR(a.cables.tension(a.cable, 0), t1, 0.01 * t1);
  EXPECT_NEAR(a.cables.tension(a.cable, 1), t2, 0.01 * t2);
  // The wheel turns with the cable: omega r = v (no slip).
  EXPECT_NEAR(-a.world.body(a.wheel).omega.z() * a.r, -a.world.body(a.box2).v.y(), 0.01 * acc * t);
}

// Substeps with few iterations (SCA 2020) and the paper's one step per
// frame with ten iterations must both meet the analytic values.
TEST(Atwood, MassRatio1To2MatchesAnalyticAccelerationAndTensions) {
  expectAnalytic(1.0, 2.0, 20, 2);
  expectAnalytic(1.0, 2.0, 40, 1);
  expectAnalytic(1.0, 2.0, 1, 10);
}

TEST(Atwood, MassRatio1To100MatchesAnalyticAccelerationAndTensions) {
  expectAnalytic(0.1, 10.0, 20, 2);
  expectAnalytic(0.1, 10.0, 40, 1);
  expectAnalytic(0.1, 10.0, 1, 10);
}

TEST(Atwood, CableLengthIsConservedAndStaysTaut) {
  Atwood a(1.0, 2.0, 20, 2);
  const double total = a.cables.totalLength(a.cable);
  for (int f = 0; f < 30; ++f) a.world.step(1.0 / 60.0);
  EXPECT_NEAR(a.cables.totalLength(a.cable), total, 1e-9 * total);
  for (int j = 0; j < 2; ++j)
    EXPECT_NEAR(a.cables.length(a.cable, j), a.cables.restLength(a.cable, j), 1e-4);
}

}  // namespace
}  // namespace reeve::test_atwood
