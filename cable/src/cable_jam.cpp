// A tie point hauled into its wheel jams there: a crane's two-blocking
// (issue 29, item 4: hilbert3's load hauled into its last wheel).
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

}  // namespace

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

void CableSystem::addJamJoints() {
  for (int c = 0; c < static_cast<int>(cables_.size()); ++c) {
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
        continue;
      }
      jams_.push_back(key);
    }
    updates_[c].jams.clear();
  }
}

}  // namespace reeve
