// Views of cables: tensions, lengths, tangent points, totals; rest lengths set by hand.
#include <cmath>
#include <string>

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
  cable.total_length = totalLength(c);
}

std::optional<std::string> CableSystem::invariantViolation() const {
  for (int c = 0; c < static_cast<int>(cables_.size()); ++c) {
    const Cable& cable = cables_[c];
    const double slack = 1e-9 * cable.total_length;
    const auto name = [&cable] { return "cable '" + cable.name + "': "; };  // built only on a failure
    for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j)
      if (cable.links[j].active && cable.joints[j].rest_length < -slack)
        return name() + "joint " + std::to_string(j) + " has a negative rest length (" +
               std::to_string(cable.joints[j].rest_length) + " m)";
    for (int k = 0; k < static_cast<int>(cable.links.size()); ++k)
      if (cable.links[k].active && cable.links[k].rolls() && cable.links[k].stored < -slack)
        return name() + "link " + std::to_string(k) + " stores a negative length of cable (" +
               std::to_string(cable.links[k].stored) + " m)";
    const double total = totalLength(c);
    if (std::abs(total - cable.total_length) > slack)
      return name() + "the total length changed from " + std::to_string(cable.total_length) + " m to " +
             std::to_string(total) + " m";
  }
  return std::nullopt;
}

double CableSystem::totalLength(int c) const {
  double total = 0.0;
  for (int j = 0; j < static_cast<int>(cables_[c].joints.size()); ++j) total += restLength(c, j);
  for (const Link& l : cables_[c].links) total += l.stored;
  return total;
}

}  // namespace reeve
