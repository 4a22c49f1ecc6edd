// A pendulum's period in closed form, for the tests of pegs and swings.
#pragma once

#include <cmath>
#include <numbers>

namespace reeve::test {

/// Complete elliptic integral of the first kind, K(k) = pi / (2 AGM(1, k')).
inline double ellipticK(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 30; ++i) {
    const double m = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = m;
  }
  return std::numbers::pi / (2.0 * a);
}

/// Time (s) for a pendulum of length L (m) released at amplitude theta
/// (rad) to reach the bottom: a quarter period, sqrt(L / g) K(sin(theta / 2)).
inline double quarterPeriod(double L, double theta, double g) {
  return std::sqrt(L / g) * ellipticK(std::sin(0.5 * theta));
}

}  // namespace reeve::test
