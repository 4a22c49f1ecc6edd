#include "reeve/machines/rope_path.h"

#include <cmath>

namespace reeve {

namespace {

Vec2 planePoint(const BodyState& body, const Vec3& world) {
  const Vec3 l = body.toLocal(world);
  return Vec2(l.x(), l.y());
}

}  // namespace

std::vector<RopePathPoint> ropeCentreline(const CableSystem& cables, int c, double max_step_rad) {
  const Cable& cable = cables.cables().at(c);
  if (cable.closed) throw std::invalid_argument("cable '" + cable.name + "' is closed (a belt)");
  const auto& links = cable.links;
  if (links.front().type != LinkType::Attachment || links.back().type != LinkType::Attachment)
    throw std::invalid_argument("cable '" + cable.name + "' must end in attachment links");
  std::vector<RopePathPoint> out;
  const int joints = static_cast<int>(cable.joints.size());
  for (int j = 0; j < joints; ++j) {
    const Link& from = links[j];
    if (from.type == LinkType::Pinhole)
      throw std::invalid_argument("cable '" + cable.name + "' has a pinhole link (not supported)");
    if (!cables.jointEnabled(c, j)) {
      if (j == 0) throw std::invalid_argument("cable '" + cable.name + "': first joint disabled");
      continue;  // inactive link: the cable does not touch it
    }
    const Vec3 start = cables.startPoint(c, j), end = cables.endPoint(c, j);
    if (cables.restLength(c, j) > cables.length(c, j) * (1.0 + 1e-9) + 1e-12)
      throw std::invalid_argument("cable '" + cable.name + "' has a slack span (joint " +
                                  std::to_string(j) + "; not supported)");
    if (j > 0 && from.rolls()) {
      // The wrap on link j: from where the previous span arrived to here.
      const BodyState& body = cables.world().body(from.body);
      const Vec3 arrival = out.back().p;
      const auto arc = sectionArcPoints(from.section, planePoint(body, arrival), planePoint(body, start),
                                        from.orientation, max_step_rad);
      for (std::size_t i = 1; i + 1 < arc.size(); ++i) {
        const Vec3 local(arc[i].x(), arc[i].y(), from.plane_offset);
        RopePathPoint pt;
        pt.p = body.toWorld(local);
        const Vec2 out_of = arc[i] - from.section.centre;  // a polygon's is 0
        const Vec3 radial(out_of.x(), out_of.y(), 0.0);
        pt.outward = body.q * radial.normalized();
        out.push_back(pt);
      }
    }
    if (out.empty() || (out.back().p - start).norm() > 1e-12) out.push_back({start, Vec3::Zero()});
    out.push_back({end, Vec3::Zero()});
  }
  return out;
}

double polylineLength(const std::vector<RopePathPoint>& path) {
  double len = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) len += (path[i].p - path[i - 1].p).norm();
  return len;
}

}  // namespace reeve
