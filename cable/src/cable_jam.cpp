// A tie point hauled into its wheel jams there: a crane's two-blocking
// (issue 29, item 4: hilbert3's load hauled into its last wheel); one
// hauled into a pinhole, likewise.
//
// Nothing in the cable model stops a tie point at its wheel's rim. Once
// the span between them has run out, the wheel winds on and slips, or
// carries the tie point round the rim until the cable's end leaves the
// wheel for the next one; the load was dragged through hilbert3's wheels
// at up to metres a second and the bookkeeping broke at 24.8 s. What stops
// a real one is the hook against the sheave and its cheeks: contact and
// friction. Reeve holds it there with a ball joint between the wheel and
// the tie point's body, at the tie point as the run-out found it. The span,
// of no length now, has no row (a distance row's direction is undefined at
// zero length) and reads no tension; the ball carries its pull. The jam
// lasts: the wheel and the load move as one from then on, the cable to
// the wheel pulling on both.
#include <algorithm>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "link_geometry.h"
#include "reeve/cable/cable.h"

namespace reeve {
namespace {

// A span runs out before its tie point reaches the rim when a solve is
// unconverged (the wheel wound cable the load did not give: Gauss-Seidel
// on a wheel 1e-6 of its load). That is a slip, not a jam: only a tie
// point within this fraction of the wheel's radius of its tangent point,
// or inside the wheel, jams. (A slider hauled along a rail onto a
// pulley's rim by an unlimited motor ran out 0.07 r short of it: the rail,
// the drive and the cable fight there.)
constexpr double kJamReach = 0.25;

// A tie point jams at a pinhole within this fraction of the cable's mean
// span (its total length over its spans) of it (the knot against the
// hole), or once it has passed through it within a substep. (Of the total
// length, a rope threaded through 512 bars' holes, 4 km in 2048 spans,
// jammed its tie 1.9 m from the first hole at the first substep.)
constexpr double kPinholeJamReach = 1e-3;

}  // namespace

bool CableSystem::jamAtPinhole(Cable& cable, int c, int j, double time_s) {
  // A tie point drawn into a pinhole has nowhere to go: the span between
  // them ran out, and with nothing to stop it the body went through the
  // hole and the cable pulled it back from the other side (the direct
  // solver's start projection made 29 kJ of it in a frame; the end
  // projection let a load rise 2 m past the beam it hung from). Held as at
  // a wheel: a ball joint at the hole, the span without a row, and the
  // pinhole holding the cable from then on (the knot in it), so the run
  // ends there.
  CableJoint& span = cable.joints[j];
  Link& from = cable.links[j];
  Link& to = cable.links[span.to];
  const bool hole_first = from.type == LinkType::Pinhole;
  Link& hole = hole_first ? from : to;
  const Link& tie = hole_first ? to : from;
  const bool ties = tie.type == LinkType::Attachment || (tie.type == LinkType::Hybrid && tie.attached);
  if (cable.junction >= 0 || span.jammed || span.parted || hole.type != LinkType::Pinhole || !hole.active || !ties ||
      hole.body == tie.body)
    return false;
  const Vec3& tie_local = hole_first ? span.local_b : span.local_a;
  const BodyState &h = world_.body(hole.body), &t = world_.body(tie.body);
  const Vec3 now = t.toWorld(tie_local) - h.toWorld(hole.point);
  const Vec3 before = t.toWorldAtSubstepStart(tie_local) - h.toWorldAtSubstepStart(hole.point);
  const double reach = kPinholeJamReach * cable.total_length / static_cast<double>(cable.joints.size());
  if (now.norm() > reach && now.dot(before) > 0.0) return false;
  updates_[c].jams.push_back({j, hole.body, tie.body, h.toWorld(hole.point), static_cast<int>(&hole - cable.links.data()), hole.mu});
  updates_[c].events.push_back({CableEvent::Kind::SpanRunsOut, time_s, c, j, hole.orientation});
  span.jammed = true;
  hole.mu = std::numeric_limits<double>::infinity();
  hole.slipping = false;
  return true;
}

bool CableSystem::jam(Cable& cable, int c, int j) {
  CableJoint& span = cable.joints[j];
  const bool wheel_first = cable.links[j].rolls();
  const Link& wheel = wheel_first ? cable.links[j] : cable.links[span.to];
  const Link& tie = wheel_first ? cable.links[span.to] : cable.links[j];
  const bool ties = tie.type == LinkType::Attachment || (tie.type == LinkType::Hybrid && tie.attached);
  if (!ties || !wheel.rolls() || wheel.slides() || tie.body == wheel.body) return false;
  const Vec3 tie_point = world_.worldPoint(tie.body, wheel_first ? span.local_b : span.local_a);
  const Vec3 anchor = world_.worldPoint(wheel.body, wheel_first ? span.local_a : span.local_b);
  const double radius = wheel.section.perimeter() / (2.0 * std::numbers::pi);
  const bool inside = !tangentFromPoint(wheel.section, toPlane(world_.body(wheel.body), tie_point), 1, true);
  if (!inside && (tie_point - anchor).norm() > kJamReach * radius) return false;
  if (!span.jammed) updates_[c].jams.push_back({j, wheel.body, tie.body, tie_point});
  span.jammed = true;
  return true;
}

void CableSystem::rejamSplit(Cable& cable, int c, int j, int mid) {
  // The jammed span merged away once the wheel carried its tie point past
  // the tangent point (mergeEmptyLinks); carried back, the cable from it
  // wraps the wheel again. The new span from a point the ball holds on
  // the rim to the same rim is of no length, its direction undefined: as a
  // row it threw a 1 kg knot 9e6 m in a substep (DESIGN, "Forty-fourth
  // session"). It is the jammed span again.
  const BodyId wheel = cable.links[mid].body;
  const auto held = [&](int k) {
    const Link& tie = cable.links[k];
    return !tie.rolls() && std::find(jams_.begin(), jams_.end(), std::pair{wheel, tie.body}) != jams_.end();
  };
  if (held(j)) jam(cable, c, j);
  if (held(cable.joints[mid].to)) jam(cable, c, mid);
}

void CableSystem::addJamJoints(double time_s) {
  for (int c = 0; c < static_cast<int>(cables_.size()); ++c) {
    if (updates_[c].news_at > time_s) continue;  // a later substep's (endUpdate)
    for (const JamRequest& r : updates_[c].jams) {
      const std::pair key{r.wheel, r.tie};
      if (std::find(jams_.begin(), jams_.end(), key) != jams_.end()) continue;
      SphericalDef ball;
      ball.body = r.wheel;
      ball.other = r.tie;
      ball.anchor = r.tie_point;
      try {
        world_.addSpherical(ball);
      } catch (const std::invalid_argument&) {  // nothing to hold (a tie point not finite)
        cables_[c].joints[r.joint].jammed = false;
        if (r.pinhole >= 0) {  // it slides again
          Link& hole = cables_[c].links[r.pinhole];
          hole.mu = r.pinhole_mu;
          hole.slipping = hole.mu == 0.0;
          buildRuns(cables_[c]);
        }
        continue;
      }
      jams_.push_back(key);
    }
    updates_[c].jams.clear();
  }
}

}  // namespace reeve
