#include "reeve/machines/rope_chain.h"

#include <algorithm>
#include <stdexcept>

namespace reeve {

namespace {

// Points of the polyline at arc lengths i L / N (L its length).
std::vector<Vec3> resample(const std::vector<Vec3>& line, int segments) {
  const double total = chainLength(line);
  std::vector<Vec3> out{line.front()};
  std::size_t k = 1;
  double s_before = 0.0;  // arc length at line[k - 1]
  for (int i = 1; i < segments; ++i) {
    const double s = total * i / segments;
    while (k + 1 < line.size() && s_before + (line[k] - line[k - 1]).norm() < s) {
      s_before += (line[k] - line[k - 1]).norm();
      ++k;
    }
    const double len = (line[k] - line[k - 1]).norm();
    const double t = len > 0.0 ? std::clamp((s - s_before) / len, 0.0, 1.0) : 0.0;
    out.push_back(line[k - 1] + t * (line[k] - line[k - 1]));
  }
  out.push_back(line.back());
  return out;
}

}  // namespace

double chainLength(const std::vector<Vec3>& vertices) {
  double len = 0.0;
  for (std::size_t i = 1; i < vertices.size(); ++i) len += (vertices[i] - vertices[i - 1]).norm();
  return len;
}

std::vector<Vec3> chainVertices(const std::vector<RopePathPoint>& path, int segments, double lift) {
  if (segments < 1) throw std::invalid_argument("need at least one segment");
  if (path.size() < 2) throw std::invalid_argument("the cable path has fewer than two points");
  std::vector<Vec3> line;
  line.reserve(path.size());
  for (const RopePathPoint& point : path) line.push_back(point.p + lift * point.outward);
  return resample(line, segments);
}

std::vector<Vec3> clearChainVertices(const std::vector<RopePathPoint>& path, int segments,
                                     const std::function<bool(const std::vector<Vec3>&)>& clear) {
  std::vector<Vec3> chain = chainVertices(path, segments, 0.0);
  if (clear(chain)) return chain;
  // Bracket the least clearing lift by doubling, then halve the bracket.
  const double longest = polylineLength(path);
  double lo = 0.0, hi = 1e-6 * longest;
  while (!clear(chainVertices(path, segments, hi))) {
    lo = hi;
    hi *= 2.0;
    if (hi > longest)
      throw std::invalid_argument("no lift up to the cable's length clears the sections it wraps by the rods' "
                                  "radius (too few segments to wrap them, or an end that close to one)");
  }
  while (hi - lo > 1e-12 * longest) {
    const double mid = 0.5 * (lo + hi);
    (clear(chainVertices(path, segments, mid)) ? hi : lo) = mid;
  }
  return chainVertices(path, segments, hi);
}

}  // namespace reeve
