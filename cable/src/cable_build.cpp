// Building cables: validation, initial tangent points, rest lengths,
// stored cable and compliance (paper sec. 3, Alg. 2 line 2).
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "link_geometry.h"
#include "links.h"
#include "reeve/cable/cable.h"

namespace reeve {
namespace {

bool hasSection(const Section& s) {
  return s.kind == Section::Kind::Polygon || s.radius > 0.0;
}

}  // namespace

const char* eventName(CableEvent::Kind kind) {
  switch (kind) {
    case CableEvent::Kind::HybridRunsOut: return "hybrid_runs_out";
    case CableEvent::Kind::HybridRollsAgain: return "hybrid_rolls_again";
    case CableEvent::Kind::Merge: return "merge";
    case CableEvent::Kind::Split: return "split";
    case CableEvent::Kind::Break: return "break";
    case CableEvent::Kind::RunsOff: return "runs_off";
    case CableEvent::Kind::SpanRunsOut: return "span_runs_out";
  }
  return "?";
}

CableSystem::CableSystem(World& world) : world_(world) {
  world_.addSubstepHook(World::IslandHook{
      [this](World&, double h) { beginUpdate(h); },
      [this](World&, double h, int island, const World::SubstepClock& clock) {
        return updateIsland(island, clock.time_s + h, h, clock.substep);
      },
      [this](World& w, double h) { endUpdate(w.time() + h); }, true});
}

int CableSystem::addCable(const CableDef& def) {
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument("cable '" + def.name + "': " + what);
  };
  const int n = static_cast<int>(def.links.size());
  const int joints = def.closed ? n : n - 1;
  if (n < 2) fail("needs at least two links");
  if (!def.rest_lengths.empty() && static_cast<int>(def.rest_lengths.size()) != joints)
    fail("rest_lengths needs one value per joint (" + std::to_string(joints) + ")");
  if (!(def.compliance >= 0.0)) fail("compliance must be >= 0");
  if (!std::isfinite(def.damping) || def.damping < 0.0) fail("damping must be finite and >= 0");
  if (def.damping > 0.0 && def.compliance == 0.0) fail("damping needs compliance > 0 (a rigid cable does not stretch)");
  if (std::isnan(def.breaking_tension) || def.breaking_tension <= 0.0) fail("the breaking tension must be > 0");

  Cable cable;
  cable.name = def.name;
  cable.closed = def.closed;
  cable.breaking_tension = def.breaking_tension;
  int active = 0;
  for (int k = 0; k < n; ++k) {
    const LinkDef& ld = def.links[k];
    const std::string at = "link " + std::to_string(k) + ": ";
    const bool end = !def.closed && (k == 0 || k == n - 1);
    if (ld.body < 0 || ld.body >= world_.bodyCount()) fail(at + "no such body");
    if (ld.type == LinkType::Pinhole && end) fail(at + "a pinhole cannot end a cable");
    if (ld.type == LinkType::Hybrid && !end) fail(at + "hybrid links end open cables (spools)");
    if (!ld.active && (end || ld.type != LinkType::Rolling))
      fail(at + "only interior rolling links can start inactive");
    if (ld.stored && !(*ld.stored >= 0.0)) fail(at + "stored cable must be >= 0");
    if (ld.mu && (end || (ld.type != LinkType::Rolling && ld.type != LinkType::Pinhole)))
      fail(at + "friction (mu) is for interior rolling links and pinholes, where the cable can slide");
    if (ld.mu && !(*ld.mu >= 0.0 && std::isfinite(*ld.mu))) fail(at + "mu must be finite and >= 0");
    Link link;
    link.body = ld.body;
    link.type = ld.type;
    link.orientation = ld.orientation;
    link.point = ld.point;
    link.plane_offset = ld.plane_offset;
    link.active = ld.active;
    if (ld.mu) link.mu = *ld.mu;
    else if (ld.type == LinkType::Pinhole) link.mu = 0.0;  // a pinhole is frictionless unless told
    link.slipping = link.mu == 0.0;
    if (ld.type == LinkType::Rolling || ld.type == LinkType::Hybrid) {
      if (hasSection(ld.section)) {
        link.section = ld.section;
      } else if (auto own = ownSection(world_.bodyDef(ld.body).shape, ld.plane_offset)) {
        link.section = *own;
        const Shape::Type shape = world_.bodyDef(ld.body).shape.type;
        if (shape == Shape::Type::Sphere || shape == Shape::Type::Hull) link.depth = Link::Depth::Slice;
      } else {
        fail(at + "the cable plane misses the body; give the link a section");
      }
      if (ld.orientation != 1 && ld.orientation != -1) fail(at + "orientation must be +1 or -1");
    }
    if (def.compliance > 0.0 && link.rolls()) link.layers.reserve(kReservedLayers);
    active += link.active;
    cable.links.push_back(std::move(link));
  }
  if (active < 2) fail("needs at least two active links");
  bool any_non_pinhole = false;
  for (const Link& link : cable.links) any_non_pinhole |= link.type != LinkType::Pinhole;
  if (def.closed && !any_non_pinhole) fail("a closed cable needs a link that is not a pinhole");

  // Everything is checked before the World is touched, so a failed cable
  // leaves nothing behind.
  cable.joints.resize(joints);
  for (int j = 0; j < joints; ++j) {
    CableJoint& joint = cable.joints[j];
    joint.to = nextActive(cable, j);
    if (!cable.links[j].active) continue;
    const Link& from = cable.links[j];
    const Link& to = cable.links[joint.to];
    const auto anchors = spanAnchors(from, world_.body(from.body), to, world_.body(to.body), Vec3::Zero());
    if (!anchors) fail("joint " + std::to_string(j) + ": no tangent between its links (do they overlap?)");
    joint.local_a = anchors->first;
    joint.local_b = anchors->second;
    joint.rest_length = def.rest_lengths.empty() ? spanLength(cable, j) : def.rest_lengths[j];
    if (!(joint.rest_length >= 0.0)) fail("joint " + std::to_string(j) + ": rest length must be >= 0");
  }
  double total = 0.0;
  for (int k = 0; k < n; ++k) {
    Link& link = cable.links[k];
    if (link.active && link.rolls()) {
      // An elastic cable is wound at the strain its rest lengths give the
      // span arriving at the link (the first link: the span leaving it),
      // the strain at which more winds on from there (restOfArc).
      const int j = k == 0 && !def.closed ? 0 : previousActive(cable, k);
      const double span_rest = cable.joints[j].rest_length, length = spanLength(cable, j);
      const double strain =
          def.compliance > 0.0 && span_rest > 0.0 ? std::max(0.0, length / span_rest - 1.0) : 0.0;
      double rest = 0.0;
      if (def.links[k].stored) {
        rest = *def.links[k].stored;
      } else if (!isEnd(cable, k)) {
        rest = sectionWrappedArc(link.section, planePoint(cable.joints[previousActive(cable, k)].local_b),
                                 planePoint(cable.joints[k].local_a), link.orientation) /
               (1.0 + strain);
      }
      link.windOn(rest, rest * strain);
    }
    total += link.stored;
  }
  for (int j = 0; j < joints; ++j) total += cable.links[j].active ? cable.joints[j].rest_length : 0.0;
  cable.compliance_per_m = total > 0.0 ? def.compliance / total : 0.0;
  cable.damping_times_m = total > 0.0 ? def.damping * total : 0.0;
  for (CableJoint& joint : cable.joints) {
    PathConstraint path;
    path.points.resize(2);  // filled by buildRuns()
    joint.path = world_.addPath(std::move(path));
  }
  syncRuns(cable);
  for (int j = 0; j < joints && !def.rest_lengths.empty(); ++j)
    if (std::abs(cable.joints[j].rest_length - def.rest_lengths[j]) > 1e-9 * std::max(1.0, def.rest_lengths[j])) {
      cable.given_rest_lengths = def.rest_lengths;  // re-shared by its runs
      break;
    }
  for (const Link& link : cable.links) {
    if (link.type != LinkType::Rolling && link.type != LinkType::Hybrid) continue;
    if (std::find(rolling_bodies_.begin(), rolling_bodies_.end(), link.body) == rolling_bodies_.end())
      rolling_bodies_.push_back(link.body);
    if (last_q_.size() <= static_cast<size_t>(link.body)) {
      last_q_.resize(link.body + 1, Quat::Identity());
      turn_.resize(link.body + 1, 0.0);
      last_x_.resize(link.body + 1, Vec3::Zero());
      move_.resize(link.body + 1, 0.0);
      steady_.resize(link.body + 1, 0);
      in_place_.resize(link.body + 1, 0);
    }
    last_q_[link.body] = world_.body(link.body).q;
    last_x_[link.body] = world_.body(link.body).x;
  }
  cable.total_length = total;
  // Friction links are checked against each solve (recheckSlips); the
  // World keeps what a solve changes only while something may ask again.
  const bool friction = std::any_of(cable.links.begin(), cable.links.end(),
                                    [](const Link& l) { return l.mu > 0.0 && std::isfinite(l.mu); });
  if (friction && !rechecks_slips_) {
    world_.addResolveCheck([this](World&, double h) { return recheckSlips(h); });
    rechecks_slips_ = true;
  }
  // Its spans move from link to link and its jams join a wheel to a tie
  // point: one island (World::coupleBodies) from the start.
  std::vector<BodyId> bodies;
  for (const Link& link : cable.links) bodies.push_back(link.body);
  world_.coupleBodies(bodies);
  cables_.push_back(std::move(cable));
  return static_cast<int>(cables_.size() - 1);
}

}  // namespace reeve
