// Views of cables: tensions, lengths, tangent points, totals; rest lengths set by hand.
#include "reeve/cable/cable.h"

namespace reeve {

std::vector<CableEvent> CableSystem::takeEvents() {
  std::vector<CableEvent> out;
  out.swap(events_);
  return out;
}

bool CableSystem::jointEnabled(int c, int j) const { return cables_[c].links[j].active; }

double CableSystem::tension(int c, int j) const {
  const Cable& cable = cables_[c];
  return jointEnabled(c, j) ? world_.pathTension(cable.joints[cable.joints[j].run].path) : 0.0;
}

double CableSystem::restLength(int c, int j) const {
  return jointEnabled(c, j) ? cables_[c].joints[j].rest_length : 0.0;
}

double CableSystem::length(int c, int j) const {
  return jointEnabled(c, j) ? spanLength(cables_[c], j) : 0.0;
}

double CableSystem::spanLength(const Cable& cable, int j) const {
  return (endPointOf(cable, j) - startPointOf(cable, j)).norm();
}

Vec3 CableSystem::startPoint(int c, int j) const { return startPointOf(cables_[c], j); }

Vec3 CableSystem::endPoint(int c, int j) const { return endPointOf(cables_[c], j); }

Vec3 CableSystem::startPointOf(const Cable& cable, int j) const {
  return world_.worldPoint(cable.links[j].body, cable.joints[j].local_a);
}

Vec3 CableSystem::endPointOf(const Cable& cable, int j) const {
  const CableJoint& joint = cable.joints[j];
  return world_.worldPoint(cable.links[joint.to].body, joint.local_b);
}

void CableSystem::setRestLength(int c, int j, double rest_length_m) {
  Cable& cable = cables_[c];
  cable.joints[j].rest_length = rest_length_m;
  syncRuns(cable);
}

double CableSystem::totalLength(int c) const {
  double total = 0.0;
  for (int j = 0; j < static_cast<int>(cables_[c].joints.size()); ++j) total += restLength(c, j);
  for (const Link& l : cables_[c].links) total += l.stored;
  return total;
}

}  // namespace reeve
