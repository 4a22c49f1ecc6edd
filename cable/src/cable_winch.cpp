// Winches (beyond the paper): an end of an open cable reeled in or paid
// out at a commanded speed or to a commanded length, with a bounded pull.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "links.h"
#include "reeve/cable/cable.h"

namespace reeve {

std::pair<int, int> CableSystem::winchSpan(const Cable& cable) const {
  const int last = static_cast<int>(cable.links.size()) - 1;
  return cable.winch->at_start ? std::pair{0, 0} : std::pair{last, previousActive(cable, last)};
}

void CableSystem::setWinch(int c, const WinchDef& winch) {
  Cable& cable = cables_[c];
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument("cable '" + cable.name + "': winch: " + what);
  };
  if (cable.closed) fail("a closed cable has no end to reel");
  const int k = winch.at_start ? 0 : static_cast<int>(cable.links.size()) - 1;
  if (cable.links[k].type != LinkType::Attachment) fail("the end link must be an attachment (the winch's drum)");
  if (!(winch.max_speed > 0.0)) fail("max_speed must be > 0");
  if (!(winch.max_pull > 0.0)) fail("max_pull must be > 0");
  if (!std::isfinite(winch.speed) || std::abs(winch.speed) > winch.max_speed)
    fail("speed must be finite and within max_speed");
  if (winch.target_stored && !(*winch.target_stored >= 0.0 && std::isfinite(*winch.target_stored)))
    fail("target_stored must be finite and >= 0");
  double after = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < winch.schedule.size(); ++i) {
    const WinchCommand& command = winch.schedule[i];
    const std::string at = "schedule[" + std::to_string(i) + "]: ";
    if (!(std::isfinite(command.from_s) && command.from_s > after))
      fail(at + "from_s must be finite and after the command before");
    after = command.from_s;
    if (!std::isfinite(command.speed) || std::abs(command.speed) > winch.max_speed)
      fail(at + "speed must be finite and within max_speed");
    if (command.target_stored && !(*command.target_stored >= 0.0 && std::isfinite(*command.target_stored)))
      fail(at + "target_stored must be finite and >= 0");
  }
  cable.winch = winch;
  buildRuns(cable);  // the pull limit on the run it reels
}

double CableSystem::winchWork() const {
  double work = 0.0;
  for (const CableUpdate& u : updates_) work += u.winch_total;
  for (int c = 0; c < static_cast<int>(cables_.size()); ++c) {
    const Cable& cable = cables_[c];
    const double pull = winchPull(c);
    work += cable.reeled * pull * (1.0 + cable.compliance_per_m * std::max(0.0, pull));
    // Stalled, it pays out at its next update what the solve could not
    // pull in (reel(): its slip), booked there against what it reeled:
    // counted now too. (Without it, a winch reeling in far more than its
    // load follows, a constant pull as an MJCF tendon motor or muscle is,
    // showed its whole reel as work between updates: 56 J for 25.6 J done,
    // and the ledger's balance rising frame by frame.)
    if (!cable.winch || world_.lastSubstep() == 0.0 || cable.joints[winchSpan(cable).second].parted) continue;
    const PathId id = cable.joints[cable.joints[winchSpan(cable).second].run].path;
    if (const auto slip = stallSlip(cable, world_.pathLength(id), world_.lastSubstep())) work -= pull * *slip;
  }
  return work;
}

std::optional<double> CableSystem::stallSlip(const Cable& cable, double length, double h) const {
  const auto [k, j] = winchSpan(cable);
  const PathConstraint& path = world_.path(cable.joints[cable.joints[j].run].path);
  if (!std::isfinite(cable.winch->max_pull) || !(-path.lambda >= cable.winch->max_pull * h * h * (1.0 - 1e-9)))
    return std::nullopt;
  // What the run stretched past its compliance's stretch at that pull: an
  // elastic cable keeps the stretch its pull holds (paid out too, its
  // tension fell to nothing and chattered back up, the ledger counting
  // each drop as energy made).
  const double elastic = path.compliance * -path.lambda / (h * h);
  return std::min(std::max(0.0, length - path.rest_length - elastic), cable.links[k].stored);
}

double CableSystem::winchPull(int c) const {
  const Cable& cable = cables_[c];
  return cable.winch ? tension(c, winchSpan(cable).second) : 0.0;
}

void CableSystem::reel(Cable& cable, double start_s, double h) {
  WinchDef& winch = *cable.winch;
  // Commands due by the middle of this substep take over, in order.
  std::size_t due = 0;
  while (due < winch.schedule.size() && winch.schedule[due].from_s <= start_s + 0.5 * h) {
    winch.speed = winch.schedule[due].speed;
    winch.target_stored = winch.schedule[due].target_stored;
    ++due;
  }
  winch.schedule.erase(winch.schedule.begin(), winch.schedule.begin() + static_cast<std::ptrdiff_t>(due));
  const auto [k, j] = winchSpan(cable);
  Link& drum = cable.links[k];
  CableJoint& span = cable.joints[j];
  cable.fed = 0.0;
  if (span.parted) {  // the cable broke: nothing left to reel
    cable.reeled = 0.0;
    return;
  }
  // Stalled: the last solve held the pull at max_pull and the run came out
  // longer than its rest length; the winch paid that out. Measured at the
  // poses that solve left (the anchors are still its anchors).
  const PathConstraint& path = world_.path(cable.joints[span.run].path);
  const double pull = -path.lambda / (h * h) * span.weight;  // N, what the last solve pulled with
  const double length = solvedLength(world_, path);  // the run's, as that solve left it
  // Cable reeled in stretched by the pull: its rest length x (1 + strain).
  // Reeled against a run that solve could not pull (a span between static
  // bodies behind a stuck friction link), it is still to be paid for by
  // the solve that takes the stretch up.
  updates_[&cable - cables_.data()].winch_work += pull * cable.reeled * (1.0 + cable.compliance_per_m * std::max(0.0, pull));
  if (pull > 0.0 || length <= path.rest_length) cable.reeled = 0.0;
  const std::optional<double> slip = stallSlip(cable, length, h);
  const bool stalled = slip.has_value();
  if (stalled) {
    // That slip already happened in the last solve (the run is that long
    // now), so it is not fed: the dashpot would read it as this substep's
    // shortening and cut the tension.
    const double slipped = *slip;
    double given = slipped;
    // Still stalled, and this substep's motion (the run's length at the
    // poses the integration predicts) takes it past the end of the cable
    // and the stretch of its pull: it all goes now, and the solve holds the
    // tied end where the cable runs out. (Booked at the next update, the
    // last of the stretch was left for that solve to project out,
    // launching the load up; issue 28, item 4.)
    if (drum.stored > given && world_.pathLength(cable.joints[span.run].path) >
                                   path.rest_length + drum.stored + path.compliance * winch.max_pull)
      given = drum.stored;
    span.rest_length += given;
    drum.stored -= given;
    cable.fed += given - slipped;
    updates_[&cable - cables_.data()].winch_work -= pull * given;
  }
  // This substep's command: cable reeled in (> 0), within what the span
  // holds and what the drum stores.
  const double step = winch.max_speed * h;
  double in = winch.target_stored ? std::clamp(*winch.target_stored - drum.stored, -step, step)
                                  : std::clamp(winch.speed * h, -step, step);
  // Outpulled with its drum empty, a winch hauls nothing: the tied end
  // holds. (Reeling in what its stall then paid straight back out, it
  // chattered between its cap and the tied end's hold every substep, the
  // load jerked up and dropped, and the cable's dashpot saw motion that
  // was not there; item 4.)
  if (stalled && drum.stored == 0.0) in = std::min(in, 0.0);
  in = std::clamp(in, -drum.stored, span.rest_length);
  span.rest_length -= in;
  drum.stored += in;
  cable.reeled += in;
  cable.fed -= in * (1.0 + cable.compliance_per_m * std::max(0.0, pull));  // stretched as it pulled
}

}  // namespace reeve
