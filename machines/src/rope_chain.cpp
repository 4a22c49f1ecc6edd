#include "reeve/machines/rope_chain.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace reeve {

namespace {

struct Sample {
  Vec3 p;
  Vec3 outward;
};

// Points of the polyline at arc lengths i L / N, with interpolated outward
// directions (zero where either neighbour lies on a straight span).
std::vector<Sample> resample(const std::vector<RopePathPoint>& path, int segments) {
  const double total = polylineLength(path);
  std::vector<Sample> out;
  out.push_back({path.front().p, Vec3::Zero()});
  std::size_t k = 1;
  double s_before = 0.0;  // arc length at path[k - 1]
  for (int i = 1; i < segments; ++i) {
    const double s = total * i / segments;
    while (k + 1 < path.size() && s_before + (path[k].p - path[k - 1].p).norm() < s) {
      s_before += (path[k].p - path[k - 1].p).norm();
      ++k;
    }
    const double len = (path[k].p - path[k - 1].p).norm();
    const double t = len > 0.0 ? std::clamp((s - s_before) / len, 0.0, 1.0) : 0.0;
    Sample smp;
    smp.p = path[k - 1].p + t * (path[k].p - path[k - 1].p);
    const Vec3& n0 = path[k - 1].outward;
    const Vec3& n1 = path[k].outward;
    smp.outward = (n0.isZero() || n1.isZero()) ? Vec3::Zero() : ((1 - t) * n0 + t * n1).normalized();
    out.push_back(smp);
  }
  out.push_back({path.back().p, Vec3::Zero()});
  return out;
}

std::vector<Vec3> lifted(const std::vector<Sample>& samples, double lift) {
  std::vector<Vec3> v;
  v.reserve(samples.size());
  for (const Sample& s : samples) v.push_back(s.p + lift * s.outward);
  return v;
}

}  // namespace

double chainLength(const std::vector<Vec3>& vertices) {
  double len = 0.0;
  for (std::size_t i = 1; i < vertices.size(); ++i) len += (vertices[i] - vertices[i - 1]).norm();
  return len;
}

std::vector<Vec3> chainVertices(const std::vector<RopePathPoint>& path, int segments,
                                double target_length) {
  if (segments < 1) throw std::invalid_argument("need at least one segment");
  if (path.size() < 2) throw std::invalid_argument("the cable path has fewer than two points");
  const std::vector<Sample> samples = resample(path, segments);
  double lo = 0.0, hi = polylineLength(path);
  const double tol = 1e-13 * target_length;
  if (chainLength(lifted(samples, lo)) > target_length + tol)
    throw std::invalid_argument("the chain's chords are already longer than the cable");
  if (chainLength(lifted(samples, hi)) < target_length)
    throw std::invalid_argument("the chain cannot be lengthened to the cable's length");
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (chainLength(lifted(samples, mid)) < target_length ? lo : hi) = mid;
  }
  return lifted(samples, 0.5 * (lo + hi));
}

}  // namespace reeve
