// The engine's small math (math.h): atan2Small's series against libm's
// atan2 on the angles a substep turns a body or a tangent point, the
// rotation vector it gives back a rotation's angle from, and the scalar
// rotation that must round as Eigen's does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <utility>

#include "reeve/engine/math.h"

namespace reeve::test_math {
namespace {

// Units in the last place between a and b (same sign, finite).
double ulps(double a, double b) {
  if (a == b) return 0.0;
  return std::abs(a - b) / std::abs(std::nextafter(b, 2.0 * b) - b);
}

TEST(Atan2Small, IsLibmsAngleToRoundingWhereItsSeriesApplies) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), exponent(-300.0, 3.0);
  double worst = 0.0;
  for (int k = 0; k < 200000; ++k) {
    const double x = std::pow(10.0, exponent(random));
    // Half of them anywhere in the window, half of them tiny angles.
    const double y = k % 2 ? 0.125 * x * unit(random) : x * std::pow(10.0, exponent(random) / 30.0 - 10.0) * unit(random);
    const double want = std::atan2(y, x);
    if (want == 0.0) {
      EXPECT_EQ(atan2Small(y, x), 0.0);
      continue;
    }
    worst = std::max(worst, ulps(atan2Small(y, x), want));
  }
  // The window's edge, where the series' truncation is largest.
  for (const double y : {0.125, -0.125, std::nextafter(0.125, 0.0)}) worst = std::max(worst, ulps(atan2Small(y, 1.0), std::atan2(y, 1.0)));
  std::printf("[ measured ] atan2Small: at most %.2f ulp from atan2 over 200,000 angles\n", worst);
  EXPECT_LE(worst, 2.0);
}

TEST(Atan2Small, IsLibmsOutsideItsWindow) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const auto& [y, x] : {std::pair{0.2, 1.0}, {-0.2, 1.0}, {1.0, 0.0}, {0.0, -1.0}, {1e-3, -1.0}, {-1.0, -1e-3},
                             {0.0, 0.0}, {1.0, inf}, {inf, 1.0}}) {
    EXPECT_EQ(atan2Small(y, x), std::atan2(y, x)) << y << ", " << x;
  }
  EXPECT_TRUE(std::isnan(atan2Small(nan, 1.0)));
  EXPECT_TRUE(std::isnan(atan2Small(0.1, nan)));
}

TEST(RotationVector, GivesBackTheAngleOfARotation) {
  const Vec3 axis = Vec3(1.0, -2.0, 0.5).normalized();
  for (const double angle : {1e-12, 1e-6, 1e-3, 0.1, 0.2, 0.25, 0.5, 1.0, 3.0}) {
    const Quat q(Eigen::AngleAxisd(angle, axis));
    const Vec3 phi = rotationVector(q);
    EXPECT_NEAR(phi.norm(), angle, 4e-16 * angle + 1e-300) << angle;
    EXPECT_NEAR((phi / phi.norm() - axis).norm(), 0.0, 1e-15) << angle;
  }
}

TEST(Rotated, IsEigensQuaternionTimesVectorBitForBit) {
  // rotated() stands in for Eigen's q * v in kernels run every substep;
  // a shipped scene's every output must stay the same to the bit, so each
  // coordinate must be the same double, for any unit q and any v (of any
  // size, and axes exactly).
  std::mt19937_64 random(11);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> scale(-12.0, 12.0);
  int checked = 0;
  for (int k = 0; k < 100000; ++k) {
    const Quat q = Quat(normal(random), normal(random), normal(random), normal(random)).normalized();
    Vec3 v(normal(random), normal(random), normal(random));
    if (k % 4 == 0) v = Vec3::Unit(k % 3);
    v *= std::pow(10.0, scale(random));
    const Vec3 eigen = q * v;
    const Scalars3 ours = rotated(q, v);
    ASSERT_EQ(ours.x, eigen.x()) << "q " << q.coeffs().transpose() << ", v " << v.transpose();
    ASSERT_EQ(ours.y, eigen.y()) << "q " << q.coeffs().transpose() << ", v " << v.transpose();
    ASSERT_EQ(ours.z, eigen.z()) << "q " << q.coeffs().transpose() << ", v " << v.transpose();
    ++checked;
  }
  EXPECT_EQ(checked, 100000);
}

}  // namespace
}  // namespace reeve::test_math
