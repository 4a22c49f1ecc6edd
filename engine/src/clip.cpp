#include "clip.h"

#include <utility>

namespace reeve {

void clipToPrism(const std::vector<Vec3>& face, const Vec3& n, std::vector<Vec3>& points,
                 std::vector<Vec3>& scratch) {
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : face) centre += v;
  centre /= static_cast<double>(face.size());
  const std::size_t k = face.size();
  for (std::size_t e = 0; e < k && !points.empty(); ++e) {
    // Side plane through the face edge, parallel to n, normal pointing in.
    const Vec3& r = face[e];
    Vec3 w = n.cross(face[(e + 1) % k] - r);
    if (w.dot(centre - r) < 0.0) w = -w;
    const auto side = [&](const Vec3& p) { return w.dot(p - r); };  // >= 0: inside
    const auto cut = [&](const Vec3& p, const Vec3& q) {
      const double sp = side(p), sq = side(q);
      return Vec3(p + (q - p) * (sp / (sp - sq)));
    };
    scratch.clear();
    if (points.size() == 1) {
      if (side(points[0]) >= 0.0) scratch.push_back(points[0]);
    } else if (points.size() == 2) {
      const Vec3 &p = points[0], &q = points[1];
      const bool in_p = side(p) >= 0.0, in_q = side(q) >= 0.0;
      if (in_p) scratch.push_back(p);
      if (in_p != in_q) scratch.push_back(cut(p, q));
      if (in_q) scratch.push_back(q);
    } else {
      for (std::size_t i = 0; i < points.size(); ++i) {
        const Vec3 &p = points[i], &q = points[(i + 1) % points.size()];
        const bool in_p = side(p) >= 0.0, in_q = side(q) >= 0.0;
        if (in_p) scratch.push_back(p);
        if (in_p != in_q) scratch.push_back(cut(p, q));
      }
    }
    std::swap(points, scratch);
  }
}

}  // namespace reeve
