#include "reeve/cable/cable.h"

#include <stdexcept>

namespace reeve {
namespace {

Vec2 xy(const Vec3& v) { return Vec2(v.x(), v.y()); }

// The link's cross-section seen from the cable plane of `frame` (body-local
// z = 0 of that body). A point for attachments; for a rolling link on
// another body its centre projected into the frame's plane, with the
// orientation flipped if that body's plane normal points the other way.
CableCircle circleInFrame(const Link& link, const BodyState& body, const BodyState& frame) {
  if (link.type == LinkType::Attachment)
    return {xy(frame.toLocal(body.toWorld(link.point))), 0.0, 1};
  const Vec3 normal = body.q * Vec3::UnitZ();
  const Vec3 frame_normal = frame.q * Vec3::UnitZ();
  const int flip = normal.dot(frame_normal) < 0.0 ? -1 : 1;
  return {xy(frame.toLocal(body.x)), link.radius, flip * link.orientation};
}

// A tangent point given in the frame's plane, as a body-local point of the
// link's own body in its own cable plane.
Vec3 anchorOnBody(const Vec2& p, const BodyState& frame, const BodyState& body) {
  Vec3 local = body.toLocal(frame.toWorld(Vec3(p.x(), p.y(), 0.0)));
  local.z() = 0.0;
  return local;
}

}  // namespace

CableSystem::CableSystem(World& world) : world_(world) {
  world_.addSubstepHook([this](World&, double) { update(); });
}

int CableSystem::addCable(const CableDef& def) {
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument("cable '" + def.name + "': " + what);
  };
  const int n = static_cast<int>(def.links.size());
  if (n < 2) fail("needs at least two links");
  if (def.links.front().type != LinkType::Attachment || def.links.back().type != LinkType::Attachment)
    fail("the first and last links must be attachments");
  if (!def.rest_lengths.empty() && static_cast<int>(def.rest_lengths.size()) != n - 1)
    fail("rest_lengths needs one value per joint (" + std::to_string(n - 1) + ")");
  if (def.compliance < 0.0) fail("compliance must be >= 0");

  Cable cable;
  cable.name = def.name;
  for (int k = 0; k < n; ++k) {
    const LinkDef& ld = def.links[k];
    if (ld.body < 0 || ld.body >= world_.bodyCount()) fail("link " + std::to_string(k) + ": no such body");
    Link link{ld.body, ld.type, ld.orientation, ld.point, 0.0, 0.0};
    if (ld.type == LinkType::Rolling) {
      link.radius = circularSectionRadius(world_.bodyDef(ld.body).shape);
      if (link.radius <= 0.0)
        fail("link " + std::to_string(k) + ": rolling needs a body with a circular cross-section");
      if (ld.orientation != 1 && ld.orientation != -1)
        fail("link " + std::to_string(k) + ": orientation must be +1 or -1");
    }
    cable.links.push_back(link);
  }
  // Everything is checked before the World is touched, so a failed cable
  // leaves no constraint behind.
  std::vector<DistanceConstraint> spans(n - 1);
  for (int j = 0; j + 1 < n; ++j) {
    DistanceConstraint& c = spans[j];
    const auto anchors = tangentAnchors(cable, j);
    if (!anchors) fail("joint " + std::to_string(j) + ": the links overlap, no tangent exists");
    c.a = cable.links[j].body;
    c.b = cable.links[j + 1].body;
    c.local_a = anchors->first;
    c.local_b = anchors->second;
    c.compliance = def.compliance;
    c.rest_length = def.rest_lengths.empty() ? currentLength(c, world_.body(c.a), world_.body(c.b))
                                             : def.rest_lengths[j];
    if (!(c.rest_length >= 0.0)) fail("joint " + std::to_string(j) + ": rest length must be >= 0");
  }
  for (int k = 1; k + 1 < n; ++k) {
    Link& link = cable.links[k];
    if (link.type == LinkType::Rolling)
      link.stored = wrappedArc(xy(spans[k - 1].local_b), xy(spans[k].local_a), link.radius, link.orientation);
  }
  for (const DistanceConstraint& c : spans) cable.joints.push_back({world_.addDistance(c)});
  cables_.push_back(std::move(cable));
  return static_cast<int>(cables_.size() - 1);
}

void CableSystem::update() {
  for (Cable& cable : cables_)
    for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) updateJoint(cable, j);
}

std::optional<std::pair<Vec3, Vec3>> CableSystem::tangentAnchors(const Cable& cable,
                                                                 int j) const {
  const Link& l = cable.links[j];
  const Link& r = cable.links[j + 1];
  if (l.type != LinkType::Rolling && r.type != LinkType::Rolling)
    return std::pair{l.point, r.point};
  const BodyState& bl = world_.body(l.body);
  const BodyState& br = world_.body(r.body);
  const BodyState& frame = l.type == LinkType::Rolling ? bl : br;
  const auto t = commonTangent(circleInFrame(l, bl, frame), circleInFrame(r, br, frame));
  if (!t) return std::nullopt;
  return std::pair{l.type == LinkType::Rolling ? anchorOnBody(t->on_from, frame, bl) : l.point,
                   r.type == LinkType::Rolling ? anchorOnBody(t->on_to, frame, br) : r.point};
}

void CableSystem::updateJoint(Cable& cable, int j) {
  Link& l = cable.links[j];
  Link& r = cable.links[j + 1];
  if (l.type != LinkType::Rolling && r.type != LinkType::Rolling) return;
  const auto anchors = tangentAnchors(cable, j);
  if (!anchors) return;  // overlapping sections: keep the old anchors
  DistanceConstraint& c = world_.distance(cable.joints[j].constraint);
  // Alg. 1 l. 4-5 and Alg. 2 l. 8-9: the anchors turned with their bodies
  // since the last update; the arc from the new tangent point back to the
  // old anchor is cable paid out into the span (leaving side) or taken up
  // from it (arriving side).
  if (l.type == LinkType::Rolling) {
    const double s = surfaceDistance(xy(c.local_a), xy(anchors->first), l.radius, l.orientation);
    c.rest_length += s;
    l.stored -= s;
  }
  if (r.type == LinkType::Rolling) {
    const double s = surfaceDistance(xy(c.local_b), xy(anchors->second), r.radius, r.orientation);
    c.rest_length -= s;
    r.stored += s;
  }
  c.local_a = anchors->first;
  c.local_b = anchors->second;
}

double CableSystem::tension(int c, int j) const {
  return world_.tension(cables_[c].joints[j].constraint);
}

double CableSystem::restLength(int c, int j) const {
  return world_.distance(cables_[c].joints[j].constraint).rest_length;
}

double CableSystem::length(int c, int j) const {
  const DistanceConstraint& d = world_.distance(cables_[c].joints[j].constraint);
  return currentLength(d, world_.body(d.a), world_.body(d.b));
}

Vec3 CableSystem::startPoint(int c, int j) const {
  const DistanceConstraint& d = world_.distance(cables_[c].joints[j].constraint);
  return world_.body(d.a).toWorld(d.local_a);
}

Vec3 CableSystem::endPoint(int c, int j) const {
  const DistanceConstraint& d = world_.distance(cables_[c].joints[j].constraint);
  return world_.body(d.b).toWorld(d.local_b);
}

double CableSystem::totalLength(int c) const {
  double total = 0.0;
  for (const CableJoint& j : cables_[c].joints) total += world_.distance(j.constraint).rest_length;
  for (const Link& l : cables_[c].links) total += l.stored;
  return total;
}

}  // namespace reeve
