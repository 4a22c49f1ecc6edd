#include "reeve/render/slack_curve.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace reeve {
namespace {

// sinh(x) / x, exact near 0.
double sinhc(double x) { return std::abs(x) < 1e-4 ? 1.0 + x * x / 6.0 : std::sinh(x) / x; }

// The x > 0 with sinh(x) / x = r (r > 1): Newton on log(sinh(x) / x),
// which is convex and increasing, kept inside a bisection bracket.
double solveSinhc(double r) {
  double lo = 0.0, hi = 1.0;
  while (sinhc(hi) < r && hi < 700.0) lo = hi, hi *= 2.0;
  double x = r < 1.0 + 1e-3 ? std::sqrt(6.0 * (r - 1.0)) : 0.5 * (lo + hi);
  x = std::clamp(x, lo, hi);
  const double target = std::log(r);
  for (int i = 0; i < 100; ++i) {
    const double f = std::log(sinhc(x)) - target;
    if (f > 0.0) hi = x;
    else lo = x;
    const double slope = x < 1e-4 ? x / 3.0 : 1.0 / std::tanh(x) - 1.0 / x;  // d/dx log(sinhc)
    double next = slope > 0.0 ? x - f / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 1e-15 * x) return next;
    x = next;
  }
  return x;
}

double polylineLength(const std::vector<Vec3>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

// Points at equal arc lengths along the catenary of length `length` from
// the origin to (h, v) in the (ex, ey) plane, ey up, h > 0, length >
// hypot(h, v): y = c (cosh((x - x0) / c) - cosh(x0 / c)).
void catenary(std::vector<Vec3>& points, const Vec3& a, const Vec3& ex, const Vec3& ey,
              double h, double v, double length) {
  const double xi = solveSinhc(std::sqrt(length * length - v * v) / h);
  const double c = h / (2.0 * xi);
  // The vertex sits where tanh of the mean of the end parameters is v / L.
  const double x0 = 0.5 * h - c * std::atanh(v / length);
  const double s0 = std::sinh(-x0 / c), y0 = std::cosh(-x0 / c);
  const int segments = static_cast<int>(points.size()) - 1;
  for (int i = 1; i < segments; ++i) {
    const double s = length * i / segments;
    const double u = std::asinh(s / c + s0);  // (x - x0) / c at arc length s
    points[i] = a + ex * (x0 + c * u) + ey * (c * (std::cosh(u) - y0));
  }
}

}  // namespace

bool isSlack(double rest, double chord) { return rest > chord * (1.0 + kSlackThreshold); }

std::vector<Vec3> slackCurve(const Vec3& a, const Vec3& b, double length, const Vec3& down,
                             int segments) {
  if (segments < 2) throw std::invalid_argument("slackCurve: needs at least 2 segments");
  if (!(length >= 0.0 && std::isfinite(length)))
    throw std::invalid_argument("slackCurve: length must be >= 0 and finite");
  if (!(down.allFinite() && down.norm() > 0.0))
    throw std::invalid_argument("slackCurve: down must be non-zero and finite");
  std::vector<Vec3> points(segments + 1);
  points.front() = a;
  points.back() = b;
  const Vec3 d = b - a;
  const double chord = d.norm();
  if (!(length > chord)) {
    for (int i = 1; i < segments; ++i) points[i] = a + d * (double(i) / segments);
    return points;
  }
  const Vec3 g = down.normalized();
  const Vec3 across = d - d.dot(g) * g;  // the chord's horizontal part
  const double h = across.norm();
  const double v = -d.dot(g);  // how far b is above a

  if (h <= 1e-9 * length) {
    // Folded: down to the lowest point p, `drop` below a, and up to b,
    // |p - a| + |p - b| = length (increasing in drop: bisection).
    const auto pointAt = [&](double drop) { return Vec3(a + 0.5 * across + g * drop); };
    const auto reach = [&](double drop) {
      const Vec3 p = pointAt(drop);
      return (p - a).norm() + (b - p).norm();
    };
    double lo = std::max(0.0, -v), hi = lo + length;
    for (int i = 0; i < 200 && hi - lo > 1e-15 * length; ++i) {
      const double mid = 0.5 * (lo + hi);
      (reach(mid) < length ? lo : hi) = mid;
    }
    const Vec3 p = pointAt(0.5 * (lo + hi));
    const double first = (p - a).norm();
    const int down_segments = std::clamp(static_cast<int>(std::lround(segments * first / length)),
                                         1, segments - 1);
    for (int i = 1; i <= down_segments; ++i) points[i] = a + (p - a) * (double(i) / down_segments);
    for (int i = down_segments + 1; i < segments; ++i)
      points[i] = p + (b - p) * (double(i - down_segments) / (segments - down_segments));
    return points;
  }

  // The polyline's chords are shorter than the arcs they cut: lengthen the
  // catenary until the polyline has the cable's length (converges at the
  // rate of that shortfall, ~1e-3 for 48 segments).
  const Vec3 ex = across / h, ey = -g;
  double target = length;
  for (int iteration = 0; iteration < 60; ++iteration) {
    catenary(points, a, ex, ey, h, v, target);
    const double shortfall = length - polylineLength(points);
    if (std::abs(shortfall) <= 1e-14 * length) break;
    target += shortfall;
  }
  return points;
}

}  // namespace reeve
