// Cables that break (beyond the paper): a span pulled past the cable's
// breaking tension parts, and the free ends it leaves run off whatever
// cannot hold them.
#include <algorithm>
#include <cmath>

#include "links.h"
#include "reeve/cable/cable.h"

namespace reeve {
namespace {

// Whether a free end can pull on the span beyond `link`: tied there, or
// wound on a wheel it cannot slip on while cable is left on it. A pinhole
// or a wrap with friction holds nothing: with no tension on the free side,
// the capstan bound T_far <= exp(mu theta) x 0 leaves none on the other.
bool holdsFreeEnd(const Link& link) {
  switch (link.type) {
    case LinkType::Attachment:
    case LinkType::Hybrid: return true;
    case LinkType::Rolling: return !std::isfinite(link.mu) && link.stored >= 0.0;
    case LinkType::Pinhole: return false;
  }
  return false;
}

}  // namespace

void CableSystem::breakOverloaded(Cable& cable, int c, double time_s, double h) {
  // A run's path pulls with at most the breaking tension (buildRuns): a
  // run the last solve held at it and still could not keep to its length
  // (less the stretch its compliance allows at that tension) asked for
  // more than the cable bears, and its hardest pulled span (weight 1)
  // parts. It passed at most the breaking tension x h of impulse in that
  // substep, as a real cable does; solved uncapped, it passed all the
  // impulse the solve asked for and the bodies lost most of their speed
  // (issue 28, item 13). Lengths are those the last solve left. A damped
  // run pulls with its dashpot too: what that solve left undone is its
  // damped row's, (C + gamma dC) / (1 + gamma) - compliance' T (correction.h:
  // dampedRow), dC since its start length, still the path's.
  int worst = -1;
  double worst_excess = 0.0;  // m past what the run could stretch: the most overloaded run parts
  for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
    const CableJoint& joint = cable.joints[j];
    if (!cable.links[j].active || joint.parted || joint.run != j) continue;  // each run once, at its start
    const PathConstraint& path = world_.path(joint.path);
    if (!path.enabled || -path.lambda < cable.breaking_tension * h * h * (1.0 - 1e-9)) continue;
    const double length = solvedLength(world_, path);
    const double gamma = path.compliance * path.damping / h;
    const double excess = (length - path.rest_length + gamma * (length - path.start_length) -
                           path.compliance * cable.breaking_tension) / (1.0 + gamma);
    if (excess <= std::max(worst_excess, 1e-9 * std::max(1.0, path.rest_length))) continue;  // held at its rating
    worst_excess = excess;
    worst = j;  // the run's hardest pulled span: the heaviest capstan weight
    for (int k = 0; k < static_cast<int>(cable.joints.size()); ++k)
      if (cable.joints[k].run == j && !cable.joints[k].parted && cable.links[k].active &&
          cable.joints[k].weight > cable.joints[worst].weight)
        worst = k;
  }
  if (worst < 0) return;
  part(cable, worst, 0.5);
  updates_[c].events.push_back(
      {CableEvent::Kind::Break, time_s - h, c, worst, cable.links[worst].orientation, cable.breaking_tension});
  releaseFreeEnds(cable, c, time_s);
  buildRuns(cable);  // the parted span leaves its run before anything reads it
}

void CableSystem::part(Cable& cable, int j, double share_a) {
  CableJoint& joint = cable.joints[j];
  // The ends hang loose with the cable the span held, so the total length
  // is kept.
  joint.tail_a = share_a * joint.rest_length;
  joint.tail_b = joint.rest_length - joint.tail_a;
  cable.links[j].windOn(joint.tail_a, 0.0);
  cable.links[joint.to].windOn(joint.tail_b, 0.0);
  joint.rest_length = 0.0;
  joint.parted = true;
  cable.broken = true;
}

void CableSystem::releaseFreeEnds(Cable& cable, int c, double time_s) {
  const int n = static_cast<int>(cable.links.size());
  for (bool released = true; released;) {
    released = false;
    for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
      const CableJoint& gone = cable.joints[j];
      if (!gone.parted || !cable.links[j].active) continue;
      // The free end at link j (its span arrives from p) and at link `to`
      // (its span leaves to the link after it).
      for (const int k : {j, gone.to}) {
        Link& link = cable.links[k];
        if (holdsFreeEnd(link)) continue;
        const bool before = k == j;  // the free end's other span arrives at k
        if (before ? (!cable.closed && k == 0) : (!cable.closed && k == n - 1)) continue;
        const int other = before ? previousActive(cable, k) : k;
        CableJoint& span = cable.joints[other];
        if (span.parted) continue;
        // Everything on link k runs off with the end and hangs from the
        // span's far link, with the span's own cable.
        span.rest_length += link.stored;
        link.unwindAll();
        part(cable, other, before ? 1.0 : 0.0);
        link.slipping = link.mu == 0.0;
        link.slip_speed = link.slip_speed_before = 0.0;
        updates_[c].events.push_back({CableEvent::Kind::RunsOff, time_s, c, k, link.orientation});
        released = true;
      }
    }
  }
}

}  // namespace reeve
