// Junctions: cables joined into one length constraint, sum_b s_b L_b <= R
// with s_b = 1 / divisor_b (MuJoCo's spatial tendon branches). Each cable
// is one run (cable_runs.cpp builds its path); the junction's path is all
// of their points in cable order, each cable's segments scaled by s_b and
// the segment from one cable's end to the next one's start by 0, so that
// C = sum_b s_b L_b - R and dC/dp = sum_b s_b dL_b/dp: cable b pulls with
// s_b T, the constraint stays conservative and the direct solver takes it
// as a row like any other (PathConstraint::scales).
#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "links.h"
#include "reeve/cable/cable.h"

namespace reeve {

std::string CableSystem::branchProblem(int c) const {
  const Cable& cable = cables_[c];
  if (cable.closed) return "is closed (a branch is open, tied at both ends)";
  if (cable.junction >= 0) return "is a branch of another junction already";
  if (cable.winch) return "has a winch";
  if (std::isfinite(cable.breaking_tension)) return "has a breaking tension";
  const int n = static_cast<int>(cable.links.size());
  for (const int end : {0, n - 1})
    if (cable.links[end].type != LinkType::Attachment)
      return "has link " + std::to_string(end) + " at an end that is not an attachment";
  for (int k = 1; k + 1 < n; ++k) {
    const Link& link = cable.links[k];
    const bool slides = link.type == LinkType::Pinhole ? !(link.mu > 0.0) : link.type == LinkType::Rolling && link.mu == 0.0;
    if (!slides)
      return "has link " + std::to_string(k) +
             " that holds the cable (a branch slides over every link between its ends: pinholes without friction, "
             "rolling links with mu 0)";
  }
  bool moves = false;
  for (const Link& link : cable.links) moves |= world_.body(link.body).moves();
  if (!moves) return "touches no moving body (its length never changes)";
  return "";
}

int CableSystem::addJunction(const JunctionDef& def) {
  const int count = static_cast<int>(def.cables.size());
  if (count < 2) throw std::invalid_argument("a junction joins at least two cables, got " + std::to_string(count));
  if (def.divisors.size() != def.cables.size())
    throw std::invalid_argument("a junction needs one divisor per cable: " + std::to_string(count) + " cables, " +
                                std::to_string(def.divisors.size()) + " divisors");
  std::set<int> seen;
  for (int b = 0; b < count; ++b) {
    const int c = def.cables[b];
    if (c < 0 || c >= static_cast<int>(cables_.size()))
      throw std::invalid_argument("junction cable " + std::to_string(b) + ": no cable " + std::to_string(c));
    if (!seen.insert(c).second)
      throw std::invalid_argument("junction cable " + std::to_string(b) + ": cable '" + cables_[c].name + "' twice");
    if (!(def.divisors[b] > 0.0) || !std::isfinite(def.divisors[b]))
      throw std::invalid_argument("junction cable " + std::to_string(b) + ": a divisor > 0 and finite, got " +
                                  std::to_string(def.divisors[b]));
    if (const std::string problem = branchProblem(c); !problem.empty())
      throw std::invalid_argument("cable '" + cables_[c].name + "' " + problem);
  }
  Junction junction;
  junction.name = def.name;
  junction.cables = def.cables;
  junction.cables_last = *std::max_element(def.cables.begin(), def.cables.end());
  for (const double d : def.divisors) junction.scales.push_back(1.0 / d);
  PathConstraint path;
  path.points.resize(2);  // filled by buildJunction()
  junction.path = world_.addPath(std::move(path));
  const int index = static_cast<int>(junctions_.size());
  for (int b = 0; b < count; ++b) {
    cables_[def.cables[b]].junction = index;
    cables_[def.cables[b]].junction_scale = junction.scales[b];
  }
  junctions_.push_back(std::move(junction));
  Junction& added = junctions_.back();
  buildJunction(added);
  for (int b = 0; b < count; ++b) added.total_length += added.scales[b] * totalLength(added.cables[b]);
  return index;
}

void CableSystem::buildJunction(Junction& junction) {
  // Each branch is one run, started by its first span (its first link is
  // an attachment), whose path buildRuns has just made.
  const int count = static_cast<int>(junction.cables.size());
  const auto branchPath = [&](int b) -> PathConstraint& { return world_.path(cables_[junction.cables[b]].joints[0].path); };
  // The rest length moves between the branches as they move: each keeps
  // rest in proportion to its length (equal strain), the junction's
  // sum_b s_b R_b unchanged. Its spans' rest lengths scale with it, and
  // the cable's total length by as much. Lengths as the last solve left
  // them within a substep's update (as settleRuns takes them), not at
  // the integration's prediction: shared there, a balanced block's
  // cables read up to g h^2 off their lengths.
  const auto lengthOf = [&](int b) {
    const PathConstraint& own = branchPath(b);
    double length = 0.0;
    for (std::size_t i = 0; i + 1 < own.points.size(); ++i) {
      const BodyState &p = world_.body(own.points[i].body), &q = world_.body(own.points[i + 1].body);
      const Vec3& a = own.points[i].local;
      const Vec3& e = own.points[i + 1].local;
      length += poses_predicted_ ? (q.toWorldAtSubstepStart(e) - p.toWorldAtSubstepStart(a)).norm()
                                 : (q.toWorld(e) - p.toWorld(a)).norm();
    }
    return length;
  };
  double rest = 0.0, measured = 0.0;
  for (int b = 0; b < count; ++b) {
    rest += junction.scales[b] * branchPath(b).rest_length;
    measured += junction.scales[b] * lengthOf(b);
  }
  // All or none: a branch that cannot take its share (no span cable to
  // scale, or less than it would give) leaves every share as it was, so
  // the sum stays.
  const auto spansOf = [&](int b) {
    double spans = 0.0;
    for (const CableJoint& joint : cables_[junction.cables[b]].joints) spans += joint.rest_length;
    return spans;
  };
  const auto change = [&](int b) { return rest * lengthOf(b) / measured - branchPath(b).rest_length; };
  bool shares = measured > 0.0;
  for (int b = 0; b < count && shares; ++b) shares = spansOf(b) > 0.0 && spansOf(b) + change(b) >= 0.0;
  for (int b = 0; b < count && shares; ++b) {
    Cable& cable = cables_[junction.cables[b]];
    const double moved = change(b), factor = (spansOf(b) + moved) / spansOf(b);
    for (CableJoint& joint : cable.joints) joint.rest_length *= factor;
    branchPath(b).rest_length += moved;
    cable.total_length += moved;
  }
  PathConstraint& path = world_.path(junction.path);
  path.points.clear();
  path.scales.clear();
  path.rest_length = path.compliance = 0.0;
  double flow = 0.0;  // sum_b s_b^2 / damping_b: the dashpots in series, each pulled with s_b T
  bool damped = true;
  for (int b = 0; b < count; ++b) {
    PathConstraint& own = branchPath(b);
    const double s = junction.scales[b];
    if (!path.points.empty()) path.scales.push_back(0.0);  // no cable from one branch's end to the next one's start
    path.points.insert(path.points.end(), own.points.begin(), own.points.end());
    path.scales.insert(path.scales.end(), own.points.size() - 1, s);
    path.rest_length += s * own.rest_length;
    path.compliance += s * s * own.compliance;
    if (own.compliance > 0.0) {
      damped &= own.damping > 0.0;
      if (own.damping > 0.0) flow += s * s / own.damping;
    }
    own.enabled = false;
  }
  path.damping = damped && flow > 0.0 ? 1.0 / flow : 0.0;
  path.enabled = true;
}

PathId CableSystem::tensionPath(const Cable& cable, int j) const {
  return cable.junction >= 0 ? junctions_[cable.junction].path : cable.joints[cable.joints[j].run].path;
}

}  // namespace reeve
