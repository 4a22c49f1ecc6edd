#include "links.h"

namespace reeve {

int nextActive(const Cable& cable, int k) {
  const int n = static_cast<int>(cable.links.size());
  for (int i = k + 1; i < k + n; ++i)
    if ((cable.closed || i < n) && cable.links[i % n].active) return i % n;
  return k;
}

int previousActive(const Cable& cable, int k) {
  const int n = static_cast<int>(cable.links.size());
  for (int i = k - 1; i > k - n; --i)
    if ((cable.closed || i >= 0) && cable.links[(i + n) % n].active) return (i + n) % n;
  return 0;
}

double solvedLength(const World& world, const PathConstraint& path) {
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < path.points.size(); ++i) {
    const BodyState& a = world.body(path.points[i].body);
    const BodyState& b = world.body(path.points[i + 1].body);
    length += ((b.x_prev + b.q_prev * path.points[i + 1].local) - (a.x_prev + a.q_prev * path.points[i].local)).norm();
  }
  return length;
}

}  // namespace reeve
