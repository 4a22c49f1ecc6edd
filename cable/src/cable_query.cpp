// Views of cables: tensions, lengths, tangent points, totals; rest lengths set by hand.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include "link_geometry.h"
#include "links.h"
#include "reeve/cable/cable.h"

namespace reeve {

std::vector<CableEvent> CableSystem::takeEvents() {
  std::vector<CableEvent> out;
  out.swap(events_);
  return out;
}

bool CableSystem::jointEnabled(int c, int j) const {
  return cables_[c].links[j].active && !cables_[c].joints[j].parted && !cables_[c].joints[j].jammed;
}

double CableSystem::tension(int c, int j) const {
  const Cable& cable = cables_[c];
  const CableJoint& joint = cable.joints[j];
  return jointEnabled(c, j) ? world_.pathTension(tensionPath(cable, j)) * joint.weight * cable.junction_scale : 0.0;
}

double CableSystem::frictionLoss() const {
  // The last solve's friction, which the next update books, counted now:
  // the ledger's balance after a frame then holds its last substep's too
  // (at one substep a frame it came a frame late, the balance rising by
  // it then, which the watch took for energy made: a winch starting to
  // haul over a friction drum, +2.3 J at 1 x 1).
  double pending = 0.0;
  const double h = world_.lastSubstep();
  for (const Cable& cable : cables_) {
    if (h == 0.0 || std::none_of(cable.links.begin(), cable.links.end(), [](const Link& l) { return l.mu > 0.0; }))
      continue;
    pending += settleRuns(cable, h, true, nullptr);
  }
  // Under the start projection a force's work is read with the velocity at
  // the substep's start (World::addWork): a slip's, with (s_n-1 + s_n) / 2
  // of the last two substeps' slides. At a slipping wrap the tension gained
  // across the link is T_slip's throughout, so that is the last substep's
  // loss halved (exactly, from rest).
  double booked = 0.0;
  for (const CableUpdate& u : updates_) booked += u.friction_loss;
  return booked + (world_.ledgerLag() > 0.0 ? 0.5 : 1.0) * pending;
}

double CableSystem::storedElasticEnergy() const {
  double energy = 0.0;
  for (const Cable& cable : cables_)
    if (cable.compliance_per_m > 0.0)
      for (const Link& link : cable.links)
        if (link.active)
          for (const WoundLayer& layer : link.layers)
            if (layer.rest > 0.0) energy += layer.stretch * layer.stretch / (2.0 * cable.compliance_per_m * layer.rest);
  return energy;
}

double CableSystem::restLength(int c, int j) const {
  return jointEnabled(c, j) ? cables_[c].joints[j].rest_length : 0.0;
}

std::optional<std::pair<double, double>> CableSystem::pendingPayOut(const Cable& cable, int j) const {
  const Link& from = cable.links[j];
  const CableJoint& joint = cable.joints[j];
  const Link& to = cable.links[joint.to];
  if (!from.rolls() && !to.rolls()) return std::pair(0.0, 0.0);
  const auto anchors = spanAnchors(from, world_.body(from.body), to, world_.body(to.body), joint.local_b);
  if (!anchors) return std::nullopt;
  // Since the last update (a substep's start) only the solve has turned
  // the bodies, unless an update by hand has counted that already.
  const auto turn = [&](BodyId b) {
    return turnSinceUpdate(b, solve_turn_counted_ ? 0.0 : world_.body(b).solve_turn.dot(world_.body(b).q * Vec3::UnitZ()));
  };
  return std::pair(from.rolls() ? payOut(from, joint.local_a, anchors->first, turn(from.body)) : 0.0,
                   to.rolls() ? -payOut(to, joint.local_b, anchors->second, turn(to.body)) : 0.0);
}

double CableSystem::restLengthNow(int c, int j) const {
  if (!jointEnabled(c, j)) return 0.0;
  const auto paid = pendingPayOut(cables_[c], j);
  const Cable& cable = cables_[c];
  const double rest = cable.joints[j].rest_length;
  if (!paid) return rest;
  // Cable paid in from each end, as rest length (restOfArc).
  const int to = cable.joints[j].to;
  const double in_a = cable.links[j].rolls() ? -restOfArc(cable, j, j, -paid->first) : 0.0;
  const double in_b = cable.links[to].rolls() ? -restOfArc(cable, to, j, -paid->second) : 0.0;
  return std::max(0.0, rest + in_a + in_b);
}

double CableSystem::storedNow(int c, int k) const {
  const Cable& cable = cables_[c];
  double stored = cable.links[k].stored;
  if (!cable.links[k].active || !cable.links[k].rolls()) return stored;
  for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
    const bool leaves = j == k, arrives = cable.joints[j].to == k;
    if ((!leaves && !arrives) || !jointEnabled(c, j)) continue;
    if (const auto paid = pendingPayOut(cable, j))
      stored += restOfArc(cable, k, j, -(leaves ? paid->first : paid->second));  // the arc onto the link
  }
  return stored;
}

double CableSystem::length(int c, int j) const {
  return jointEnabled(c, j) ? spanLength(cables_[c], j) : 0.0;
}

double CableSystem::lengthNow(int c, int j) const {
  if (!jointEnabled(c, j)) return 0.0;
  const Cable& cable = cables_[c];
  const Link &from = cable.links[j], &to = cable.links[cable.joints[j].to];
  if (!from.rolls() && !to.rolls()) return spanLength(cable, j);
  const auto anchors = spanAnchors(from, world_.body(from.body), to, world_.body(to.body), cable.joints[j].local_b);
  if (!anchors) return spanLength(cable, j);
  return (world_.worldPoint(to.body, anchors->second) - world_.worldPoint(from.body, anchors->first)).norm();
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
  if (cable.junction < 0) return;
  Junction& junction = junctions_[cable.junction];
  junction.total_length = 0.0;
  for (std::size_t b = 0; b < junction.cables.size(); ++b)
    junction.total_length += junction.scales[b] * cables_[junction.cables[b]].total_length;
}

std::optional<CableBreach> CableSystem::findBreach() const {
  for (int c = 0; c < static_cast<int>(cables_.size()); ++c)
    if (auto b = cableBreach(c)) return b;
  return std::nullopt;
}

namespace {

// A length in a breach's message: to 10 significant digits, where
// std::to_string's 6 decimals showed a change of 1e-7 m as none and a
// rest length of -1e-8 m as -0.000000.
std::string metres(double m) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g m", m);
  return text;
}

}  // namespace

std::optional<CableBreach> CableSystem::cableBreach(int c) const {
  const Cable& cable = cables_[c];
  const double slack = 1e-9 * cable.total_length;
  // Messages are built only on a failure: this runs every substep.
  const auto broken = [&](std::string what, bool spool_ran_out = false) {
    CableBreach b;
    b.what = "cable '" + cable.name + "': " + std::move(what);
    b.cable = c;
    b.spool_ran_out = spool_ran_out;
    return b;
  };
  for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j)
    if (cable.links[j].active && !cable.joints[j].parted && cable.joints[j].rest_length < -slack)
      return broken("joint " + std::to_string(j) + " has a negative rest length (" +
                    metres(cable.joints[j].rest_length) + ")");
  for (int k = 0; k < static_cast<int>(cable.links.size()); ++k) {
    const Link& link = cable.links[k];
    if (link.active && link.rolls() && link.stored < -slack)
      return broken("link " + std::to_string(k) + " stores a negative length of cable (" + metres(link.stored) + ")",
                    link.type == LinkType::Rolling && isEnd(cable, k));
  }
  const double total = totalLength(c);
  if (std::abs(total - cable.total_length) > slack)
    return broken("the total length changed from " + metres(cable.total_length) + " to " + metres(total) + " (by " +
                  metres(total - cable.total_length) + ")");
  if (c < static_cast<int>(updates_.size()) && updates_[c].held) return updates_[c].held;
  if (cable.junction < 0) return std::nullopt;
  const Junction& junction = junctions_[cable.junction];
  double joined = 0.0;  // its branches trade cable: the junction keeps the sum
  for (std::size_t b = 0; b < junction.cables.size(); ++b) joined += junction.scales[b] * totalLength(junction.cables[b]);
  if (std::abs(joined - junction.total_length) > 1e-9 * junction.total_length)
    return broken("its junction '" + junction.name + "': the total length changed from " +
                  metres(junction.total_length) + " to " + metres(joined) + " (by " +
                  metres(joined - junction.total_length) + ")");
  return std::nullopt;
}

std::optional<std::string> CableSystem::invariantViolation() const {
  if (auto b = findBreach()) return std::move(b->what);
  return std::nullopt;
}

double CableSystem::totalLength(int c) const {
  double total = 0.0;
  const Cable& cable = cables_[c];
  for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j)
    if (cable.links[j].active && !cable.joints[j].parted) total += cable.joints[j].rest_length;  // jammed too
  for (const Link& l : cable.links) total += l.stored;
  return total;
}

}  // namespace reeve
