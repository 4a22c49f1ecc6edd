#include "clip.h"

#include <algorithm>
#include <utility>

namespace reeve {

void clipToPrism(const std::vector<Vec3>& face, const Vec3& n, std::vector<Vec3>& points,
                 std::vector<Vec3>& scratch) {
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : face) centre += v;
  centre /= static_cast<double>(face.size());
  double size = 0.0;
  for (const Vec3& v : face) size = std::max(size, (v - centre).norm());
  const double slop = kClipSlop * size;
  const std::size_t k = face.size();
  for (std::size_t e = 0; e < k && !points.empty(); ++e) {
    // Side plane through the face edge, parallel to n, unit normal pointing
    // in. A point within the slop outside it counts as inside, and is its
    // own crossing: an edge is cut only where it leaves from strictly inside.
    const Vec3& r = face[e];
    Vec3 w = n.cross(face[(e + 1) % k] - r).normalized();
    if (w.dot(centre - r) < 0.0) w = -w;
    const auto side = [&](const Vec3& p) { return w.dot(p - r); };
    const auto clipEdge = [&](const Vec3& p, const Vec3& q) {  // p's part, and the crossing
      const double sp = side(p), sq = side(q);
      const bool in_p = sp >= -slop, in_q = sq >= -slop;
      if (in_p) scratch.push_back(p);
      if (in_p != in_q && (in_p ? sp : sq) > 0.0) scratch.push_back(p + (q - p) * (sp / (sp - sq)));
    };
    scratch.clear();
    if (points.size() == 1) {
      if (side(points[0]) >= -slop) scratch.push_back(points[0]);
    } else if (points.size() == 2) {
      clipEdge(points[0], points[1]);
      if (side(points[1]) >= -slop) scratch.push_back(points[1]);
    } else {
      for (std::size_t i = 0; i < points.size(); ++i) clipEdge(points[i], points[(i + 1) % points.size()]);
    }
    std::swap(points, scratch);
  }
}

}  // namespace reeve
