#include "reeve/machines/rope_path.h"

#include <cmath>

namespace reeve {

namespace {

Vec2 planePoint(const BodyState& body, const Vec3& world) {
  const Vec3 l = body.toLocal(world);
  return Vec2(l.x(), l.y());
}

// Away from `link`'s section at `local`, a point of its plane: unit, world.
Vec3 outwardAt(const Link& link, const BodyState& body, const Vec2& local) {
  const Vec2 out_of = local - link.section.centre;  // a polygon's centre is 0
  return body.q * Vec3(out_of.x(), out_of.y(), 0.0).normalized();
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
    const Link& to = links[cable.joints[j].to];
    const bool start_wraps = j > 0 && from.rolls(), end_wraps = &to != &links.back() && to.rolls();
    if (cables.restLength(c, j) > cables.length(c, j) * (1.0 + 1e-9) + 1e-12)
      throw std::invalid_argument("cable '" + cable.name + "' has a slack span (joint " +
                                  std::to_string(j) + "; not supported)");
    const BodyState& from_body = cables.world().body(from.body);
    if (start_wraps) {
      // The wrap on link j: from where the previous span arrived to here.
      const auto arc = sectionArcPoints(from.section, planePoint(from_body, out.back().p),
                                        planePoint(from_body, start), from.orientation, max_step_rad);
      for (std::size_t i = 1; i + 1 < arc.size(); ++i)
        out.push_back({from_body.toWorld(Vec3(arc[i].x(), arc[i].y(), from.plane_offset)),
                       outwardAt(from, from_body, arc[i])});
    }
    if (out.empty() || (out.back().p - start).norm() > 1e-12)
      out.push_back({start, start_wraps ? outwardAt(from, from_body, planePoint(from_body, start)) : Vec3::Zero()});
    const BodyState& to_body = cables.world().body(to.body);
    out.push_back({end, end_wraps ? outwardAt(to, to_body, planePoint(to_body, end)) : Vec3::Zero()});
  }
  return out;
}

double polylineLength(const std::vector<RopePathPoint>& path) {
  double len = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) len += (path[i].p - path[i - 1].p).norm();
  return len;
}

}  // namespace reeve
