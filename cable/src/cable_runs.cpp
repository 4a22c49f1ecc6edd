// Runs: spans joined through links the cable slides over or through
// (frictionless pinholes, paper Alg. 1 l. 8-16; sliding wraps and friction
// links that slip, beyond the paper) are solved as one path constraint.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include "link_geometry.h"
#include "links.h"
#include "reeve/cable/cable.h"

namespace reeve {
namespace {

// A run's end at `anchor` on `link`: where the cable sticks to a rolling
// circle it is a rolling end, held on the circle while a solve turns the
// wheel (path_constraint.h: SolvePoint); elsewhere a point fixed on the
// body (a tie point, a pinhole, a polygon's vertex). Set in place, so that
// a run set again every substep copies no more than it changes. A spool's
// end (a hybrid link still rolling) pays out its stored cable, as wound on
// the rim, and no more: a turn of o (the link's orientation) about the
// plane's normal pays out where the span leaves it (`leaving`), -o where
// it arrives (CableSystem::updateJoint's arcs).
void setRunEnd(PathPoint& point, const Link& link, const Vec3& anchor, bool leaving) {
  point.body = link.body;
  point.local = anchor;
  if (link.rolls() && !link.slides() && link.section.kind == Section::Kind::Circle) {
    point.roll_axis = Vec3::UnitZ();
    point.roll_centre = fromPlane(link, link.section.centre);
  } else {
    point.roll_axis.setZero();
    point.roll_centre.setZero();
  }
  const bool store = link.type == LinkType::Hybrid && !link.attached && point.roll_axis.z() != 0.0;
  point.roll_store = store ? std::max(0.0, link.arc()) : 0.0;
  point.store_sense = store ? (leaving ? link.orientation : -link.orientation) : 0;
  point.slides = false;
}

// Whether the cable slides over `link`'s circle inside a run (a sliding
// wrap or a slipping friction link): its tangent points there are held
// where the update put them while a solve turns the body
// (PathPoint::slides), in a weighted run, a loop or a run over a rotor,
// which only the path kernel solves (the direct solver's rows hold none).
bool slidesOverCircle(const Link& link) {
  return link.rolls() && link.slides() && link.section.kind == Section::Kind::Circle;  // not a pinhole
}

// `point` (on `link`) marked as a tangent point the cable slides past.
void markSliding(PathPoint& point, const Link& link) {
  point.slides = true;
  point.roll_axis = Vec3::UnitZ();
  point.roll_centre = fromPlane(link, link.section.centre);
}

PathPoint runEnd(const Link& link, const Vec3& anchor, bool leaving) {
  PathPoint point;
  setRunEnd(point, link, anchor, leaving);
  return point;
}

// Calls f(j, loop) for the first span j of every run: each active link
// that holds the cable starts one; a closed cable that slides over every
// link is one loop, started at its first active link.
template <class F>
void forEachRun(const Cable& cable, F f) {
  const int joints = static_cast<int>(cable.joints.size());
  bool held = false;
  for (int j = 0; j < joints; ++j)
    if (cable.links[j].active && !cable.links[j].slides()) {
      held = true;
      if (!cable.joints[j].parted && !cable.joints[j].jammed) f(j, false);
    }
  if (held || !cable.closed) return;
  for (int j = 0; j < joints; ++j)
    if (cable.links[j].active && !cable.joints[j].parted) return f(j, true);
}

// Whether span k's far link ends the run started at j.
bool endsRun(const Cable& cable, int j, bool loop, int k) {
  const int to = cable.joints[k].to;
  return loop ? to == j : !cable.links[to].slides();
}

// Calls visit(k) for the spans of the run started at j, in cable order.
template <class Visit>
void walkRun(const Cable& cable, int j, bool loop, Visit visit) {
  for (int k = j;; k = cable.joints[k].to) {
    visit(k);
    if (endsRun(cable, j, loop, k)) return;
  }
}

bool hasFriction(const Link& link) { return link.mu > 0.0 && std::isfinite(link.mu); }

// World point of a body-local anchor as the last solve left it (before
// this substep's integration), or now if `now`. On a rolling link too: the
// anchors are those the last update found, which turned with the body
// through the solve and no further. (Taken at this substep's turn instead,
// a slipping wrap on a hinged wheel measured its slip less the wheel's
// next turn, stuck and slipped by turns, and created energy: issue 28.)
// A slipping wrap's tangent points too, which the solve held where they
// were (PathPoint::slides): turned here as if the cable stuck through the
// solve, as the next update pays the solve's turn out, so that the share
// measures the slip less that turn. (Held here too, the slip lagged the
// update's pay-out by a solve: a wrap on a hinged wheel made 7e-4 J at
// 1 x 1 under the start projection.)
Vec3 pointAt(const BodyState& body, const Vec3& local, bool now) {
  return now ? body.toWorld(local) : body.x_prev + body.q_prev * local;
}

}  // namespace

void CableSystem::syncRuns(Cable& cable) {
  settleRuns(cable, 0.0, true, &cable);
  buildRuns(cable);
  if (cable.junction >= 0) buildJunction(junctions_[cable.junction]);
}

double CableSystem::settleRuns(const Cable& cable, double h, bool now, Cable* settle) const {
  // A run's rest length is shared out in proportion to its spans' lengths:
  // equal strain, as Alg. 1 l. 8-16 intends, where the tension is the same
  // throughout; with friction, where span k pulls with T_k, in proportion
  // to L_k / (1 + c T_k), c the compliance per metre. The cable that moves
  // forward past a sliding link here, less what the body's turn carried
  // (the last update paid that out as if the cable stuck), is its slip over
  // the last substep. Lengths are those the last solve left
  // (the poses before this substep's integration, when h > 0): a friction
  // link that sticks from now on keeps its spans as they were, not as the
  // integration's prediction would share them.
  const auto spanLengthSolved = [&](int k) {
    const CableJoint& span = cable.joints[k];
    const BodyState& a = world_.body(cable.links[k].body);
    const BodyState& b = world_.body(cable.links[span.to].body);
    return (pointAt(b, span.local_b, now) - pointAt(a, span.local_a, now)).norm();
  };
  double friction = 0.0;
  forEachRun(cable, [&](int j, bool loop) {
    double rest = 0.0, length = 0.0, weighed = 0.0;
    bool weighted = false;
    int spans = 0;
    walkRun(cable, j, loop, [&](int k) {
      rest += cable.joints[k].rest_length;
      weighted |= cable.joints[k].weight != 1.0;
      ++spans;
    });
    if (spans == 1) return;  // a span alone keeps its rest length: no length to measure
    walkRun(cable, j, loop, [&](int k) { length += spanLengthSolved(k); });
    if (!(length > 0.0)) return;
    weighted &= cable.compliance_per_m > 0.0;
    const double tension = h > 0.0 ? -world_.path(cable.joints[j].path).lambda / (h * h) : 0.0;
    const auto share = [&](int k) {
      return spanLengthSolved(k) / (1.0 + cable.compliance_per_m * tension * cable.joints[k].weight);
    };
    if (weighted) walkRun(cable, j, loop, [&](int k) { weighed += share(k); });
    double before = 0.0, after = 0.0;  // rest lengths up to here, before and after sharing
    // Each span's rest length is read before it is written, and nothing
    // read later depends on it: `settle` may be `cable` itself.
    walkRun(cable, j, loop, [&](int k) {
      const CableJoint& span = cable.joints[k];
      before += span.rest_length;
      const double settled = weighted ? rest * share(k) / weighed : rest * spanLengthSolved(k) / length;
      after += settled;
      if (settle) settle->joints[k].rest_length = settled;
      if (h == 0.0 || endsRun(cable, j, loop, k)) return;
      if (settle) settle->links[span.to].slip_speed = (before - after) / h;
      // The work friction took out over the last substep: the slip times
      // the tension it gained across the link (the energy ledger; never a
      // credit where friction pushed the slip along).
      if (hasFriction(cable.links[span.to]))
        friction += std::max(0.0, (cable.joints[span.to].weight - span.weight) * tension * (before - after));
    });
  });
  return friction;
}

void CableSystem::switchSlips(Cable& cable, double h) {
  // Coulomb friction along the wrap (the capstan equation): a sticking link
  // slips once the tension on one side exceeds exp(mu theta) times the
  // other's; a slipping one sticks again once its slip stops or turns.
  const int n = static_cast<int>(cable.links.size());
  for (int k = 0; k < n; ++k) {
    Link& link = cable.links[k];
    if (!link.active || !hasFriction(link) || cable.joints[k].parted) continue;
    // A wheel holding a jammed tie point holds its cable too (cable_jam.cpp).
    if (cable.joints[k].jammed || cable.joints[previousActive(cable, k)].jammed) continue;
    if (link.slipping) {
      // Sticks when the slip stopped, or will have by the next update at
      // its present deceleration (a substep's lag is a substep of friction
      // pushing the wrong way). A run the last solve left slack carries no
      // friction to stop it: it slides on, so that the cable a winch pays
      // out into it reaches the load (item 6: stuck, the span between a
      // static pinhole and a static drum kept the slack, the load fell free
      // through it and was caught by a jerk, by turns).
      const double next = 2.0 * link.slip_speed - link.slip_speed_before;
      link.slip_speed_before = link.slip_speed;
      if (world_.path(cable.joints[cable.joints[k].run].path).lambda == 0.0) continue;
      if (link.slip_sense * link.slip_speed > 0.0 && link.slip_sense * next > 0.0) continue;
      link.slipping = false;
      continue;
    }
    link.slip_speed = link.slip_speed_before = 0.0;
    startsSlipping(cable, k, h);
  }
}

double CableSystem::solvedTension(const Cable& cable, int j, double h) const {
  // An inextensible run that nothing moves (a winch's span between a
  // static drum and a pinhole) cannot be solved: stretched, it pulls as
  // hard as anything pulls against it, and slips over the link towards
  // itself (issue 28, item 6: read as 0 N, the link slipped the other
  // way, paying the winch's cable out to the load, which the path then
  // flung up at up to 10 m/s).
  const PathId id = tensionPath(cable, j);
  const PathConstraint& path = world_.path(id);
  if (path.compliance == 0.0 &&
      std::none_of(path.points.begin(), path.points.end(),
                   [&](const PathPoint& q) { return world_.body(q.body).moves(); }) &&
      world_.pathLength(id) > path.rest_length)
    return std::numeric_limits<double>::infinity();
  return -path.lambda / (h * h) * cable.joints[j].weight * cable.junction_scale;
}

bool CableSystem::startsSlipping(Cable& cable, int k, double h) const {
  Link& link = cable.links[k];
  const double in = solvedTension(cable, previousActive(cable, k), h), out = solvedTension(cable, k, h);
  const double bound = std::exp(link.mu * wrapAngle(cable, k));
  if (out > bound * in) link.slip_sense = 1;
  else if (in > bound * out) link.slip_sense = -1;
  else return false;
  link.slipping = true;
  return true;
}

bool CableSystem::recheckSlips(double h) {
  // Issue 28, item 3: switched only at the update, a link kept for a whole
  // substep what the last solve decided, and at one substep a frame a
  // sticking rope took whatever its solve asked of it (a winch reversing
  // over a fixed drum: 172 N held against 0 N past a bound of 1.87), a
  // slipping one slid on against its friction. Checked against this
  // solve's own tensions and slip, a link that broke its assumption
  // switches and the World solves the substep again.
  bool changed = false;
  for (Cable& cable : cables_) {
    bool switched = false;
    bool settled = false;  // settled_: the runs as the next update will settle them, each link's slip
    const int n = static_cast<int>(cable.links.size());
    for (int k = 0; k < n; ++k) {
      Link& link = cable.links[k];
      if (!link.active || !hasFriction(link) || cable.joints[k].parted) continue;
      if (!link.slipping) {
        switched |= startsSlipping(cable, k, h);
        continue;
      }
      if (world_.path(cable.joints[cable.joints[k].run].path).lambda == 0.0) continue;  // slack: slides on
      if (!settled) {
        settled_ = cable;
        settleRuns(settled_, h, true, &settled_);
        settled = true;
      }
      if (link.slip_sense * settled_.links[k].slip_speed >= 0.0) continue;
      link.slipping = false;  // slid back against its friction: it sticks, and may slip the other way
      link.slip_speed = link.slip_speed_before = 0.0;
      switched = true;
    }
    if (switched) buildRuns(cable);
    changed |= switched;
  }
  return changed;
}

void CableSystem::buildRuns(Cable& cable) {
  // Each run is one path: its points are the first span's start, each
  // pinhole, each sliding wrap's arrival and departure tangent points (the
  // chord between them is fixed on the body, so the path's rest length
  // counts it instead of the wrapped arc, which is stored cable) and the
  // last span's end. A slipping friction link multiplies the tension of
  // the spans after it by exp(+-mu theta): the path's weights.
  for (CableJoint& joint : cable.joints) world_.path(joint.path).enabled = false;
  forEachRun(cable, [&](int j, bool loop) {
    PathConstraint& path = world_.path(cable.joints[j].path);
    path.placement = 0;  // updateCable's to keep
    path.fed = 0.0;
    double rest = 0.0, chords = 0.0;
    double stretch = 0.0;  // sum of weight x rest length: the compliance's
    if (!loop && endsRun(cable, j, loop, j)) {
      // A run of one span (most runs): its two ends, weight 1.
      CableJoint& span = cable.joints[j];
      if (cable.winch && j == winchSpan(cable).second) path.fed = cable.fed;
      span.run = j;
      span.weight = 1.0;
      path.points.resize(2);
      setRunEnd(path.points[0], cable.links[j], span.local_a, true);
      setRunEnd(path.points[1], cable.links[span.to], span.local_b, false);
      path.weights.clear();
      rest = stretch = span.rest_length;
    } else {
      path.points.clear();
      path.weights.clear();
      path.points.push_back(runEnd(cable.links[j], cable.joints[j].local_a, true));
      if (loop && slidesOverCircle(cable.links[j])) markSliding(path.points.back(), cable.links[j]);
      double w = 1.0, heaviest = 1.0;
      bool slidesOverRotor = false;
      walkRun(cable, j, loop, [&](int k) {
        CableJoint& span = cable.joints[k];
        if (cable.winch && k == winchSpan(cable).second) path.fed = cable.fed;
        const Link& to = cable.links[span.to];
        span.run = j;
        span.weight = w;
        rest += span.rest_length;
        path.weights.push_back(w);
        const bool last = endsRun(cable, j, loop, k);
        if (to.type == LinkType::Pinhole && !last) {
          path.points.push_back({to.body, to.point});
        } else {
          path.points.push_back(last && !loop ? runEnd(to, span.local_b, false) : PathPoint{to.body, span.local_b});
          if (to.rolls() && (!last || loop)) {  // the chord to the departure tangent point
            const Vec3& departure = cable.joints[span.to].local_a;
            chords += (departure - span.local_b).norm();
            path.weights.push_back(w);
            path.points.push_back({to.body, departure});
            if (slidesOverCircle(to)) {
              markSliding(path.points.end()[-2], to);
              markSliding(path.points.back(), to);
              slidesOverRotor |= world_.body(to.body).isRotor();
            }
          }
        }
        if (!last && hasFriction(to)) w *= std::exp(to.slip_sense * to.mu * wrapAngle(cable, span.to));
        heaviest = std::max(heaviest, w);
      });
      stretch = rest;
      if (heaviest != 1.0 ||
          std::any_of(path.weights.begin(), path.weights.end(), [](double x) { return x != 1.0; })) {
        stretch = 0.0;
        for (double& x : path.weights) x /= heaviest;
        walkRun(cable, j, loop, [&](int k) {
          cable.joints[k].weight /= heaviest;
          stretch += cable.joints[k].weight * cable.joints[k].rest_length;
        });
      } else if (!loop && !slidesOverRotor) {
        path.weights.clear();
        for (PathPoint& point : path.points)
          if (point.slides) point = PathPoint{point.body, point.local};  // the direct solver's rows: fixed points
      }
      // A loop (a closed cable sliding over every wheel), and a run that
      // slides over a rotor's circle (a wheel on a fixed axle), keep their
      // tangent points held on their circles and their weights of 1, as a
      // slipping wrap's run: the path kernel solves them (between the
      // direct solver's iterations, as friction). As the direct solver's
      // row their points were fixed on the wheels, so a solve's turn
      // swung them off their circles and stretched the belt by r a^2: a
      // frictionless belt over two centred hinged wheels locked a free
      // motor (0 rad/s where it spins up alone to 100), and one gripping
      // the driven wheel made 2e9 J (DESIGN, "Fifty-fourth session",
      // "Fifty-fifth session"). A run over moving bodies that are not
      // rotors (a tendon over a joint's cylinder on a link) stays the
      // direct solver's row: in the kernel it converged as Gauss-Seidel
      // does, off the MJCF models' statics.
    }
    path.rest_length = rest + chords;
    path.compliance = cable.compliance_per_m * stretch;
    // Its spans' dashpots in series, each pulled with its weight's share:
    // the path's length changes by T sum w_i L_i / damping_times_m per s.
    path.damping = stretch > 0.0 ? cable.damping_times_m / stretch : 0.0;
    // A cable pulls with at most its breaking tension (its heaviest span,
    // weight 1): past it, it parts (breakOverloaded) having passed no more.
    path.max_tension = cable.breaking_tension;
    path.enabled = true;
  });
  // A winch's pull is limited while its drum holds cable to pay out under
  // the load (it stalls: reel()); an empty drum holds the cable's tied end
  // whatever the pull (issue 28, item 4: capped, the inextensible span
  // stretched from nothing, 1.9 m in 1 s under 10 kg at 60 N).
  if (cable.winch && !cable.joints[winchSpan(cable).second].parted &&
      cable.links[winchSpan(cable).first].stored > 0.0) {
    PathConstraint& reeled = world_.path(cable.joints[cable.joints[winchSpan(cable).second].run].path);
    reeled.max_tension = std::min(reeled.max_tension, cable.winch->max_pull);
  }
}

void CableSystem::watchHeldRuns(Cable& cable, int c, double time_s, bool switched) {
  // A rigid run through bodies that no constraint moves (static, or
  // kinematic: moved by their schedules) has no row that can pull it in:
  // the solvers leave out rows of bodies that do not move. A kinematic body
  // carrying it away, or a kinematic drum hauling it, then stretched it
  // unseen, and a body that joined the run later (a merge) was yanked by
  // all of it at once (45 kJ in a frame). Holding it takes an unbounded
  // tension: a cable with a breaking tension parts, one without stops the
  // run (CableBreach::held_stretched). A run that can slip at an end (a
  // friction link, which the stick-or-slip recheck lets go), that holds
  // its stretch as tension (an elastic cable) or that a winch's capped pull
  // reels is not held; the stretch it started with (a split's share of a
  // loaded span's strain) is no growth.
  CableUpdate& out = updates_[c];
  const int n = static_cast<int>(cable.joints.size());
  if (out.held_least.size() != cable.joints.size() || switched)
    out.held_least.assign(n, std::numeric_limits<double>::quiet_NaN());
  if (out.held || cable.compliance_per_m != 0.0) return;
  const double tolerance = 1e-6 * std::max(1.0, cable.total_length);  // m: no rounding
  int parts = -1;  // the run that parts
  forEachRun(cable, [&](int j, bool loop) {
    const PathConstraint& path = world_.path(cable.joints[j].path);
    bool held = path.enabled && path.weights.empty() && path.max_tension == cable.breaking_tension;
    walkRun(cable, j, loop, [&](int k) {
      held = held && !hasFriction(cable.links[k]) && !hasFriction(cable.links[cable.joints[k].to]);
    });
    for (const PathPoint& p : path.points) held = held && !world_.body(p.body).moves();
    double& least = out.held_least[j];
    if (!held) {
      least = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    const double stretch = world_.pathLength(cable.joints[j].path) - path.rest_length;
    least = std::isnan(least) ? stretch : std::min(least, stretch);
    if (out.held || parts >= 0 || !(stretch - std::max(0.0, least) > tolerance)) return;
    if (std::isfinite(cable.breaking_tension)) {
      parts = j;
      return;
    }
    const auto name = [&](BodyId b) {
      return b == kWorldBody ? std::string("the world") : "'" + world_.bodyDef(b).name + "'";
    };
    char by[32], rest[32];
    std::snprintf(by, sizeof by, "%.4g m", stretch);
    std::snprintf(rest, sizeof rest, "%.6g m", path.rest_length);
    CableBreach b;
    b.cable = c;
    b.held_stretched = true;
    b.stretch = stretch;
    b.what = "cable '" + cable.name + "': its run from " + name(path.points.front().body) + " to " +
             name(path.points.back().body) + " is " + by + " longer than its rest length (" + rest +
             "), and none of the bodies it passes can move";
    out.held = std::move(b);
  });
  if (parts < 0) return;
  // As breakOverloaded parts a run: its first span (all of a held run's
  // spans pull alike), at the cable's rating.
  part(cable, parts, 0.5);
  out.events.push_back(
      {CableEvent::Kind::Break, time_s, c, parts, cable.links[parts].orientation, cable.breaking_tension});
  releaseFreeEnds(cable, c, time_s);
  buildRuns(cable);
  out.held_least.assign(n, std::numeric_limits<double>::quiet_NaN());
}

double CableSystem::wrapAngle(const Cable& cable, int k) const {
  const Link& link = cable.links[k];
  const int p = previousActive(cable, k);
  if (link.type == LinkType::Pinhole) {  // the angle between the arriving and the leaving span
    const Vec3 u_in = endPointOf(cable, p) - startPointOf(cable, p);
    const Vec3 u_out = endPointOf(cable, k) - startPointOf(cable, k);
    const double norms = u_in.norm() * u_out.norm();
    return norms > 0.0 ? std::acos(std::clamp(u_in.dot(u_out) / norms, -1.0, 1.0)) : 0.0;
  }
  if (link.section.kind == Section::Kind::Circle) return link.arc() / link.section.radius;
  // A polygon: the turn from the arriving span's direction to the leaving
  // one's, in the link's sense, plus the whole turns its stored cable
  // holds beyond the geometric wrap.
  const BodyState& body = world_.body(link.body);
  const Vec2 d_in = toPlane(body, endPointOf(cable, p)) - toPlane(body, startPointOf(cable, p));
  const Vec2 d_out = toPlane(body, endPointOf(cable, k)) - toPlane(body, startPointOf(cable, k));
  double turn = link.orientation * std::atan2(d_in.x() * d_out.y() - d_in.y() * d_out.x(), d_in.dot(d_out));
  if (turn < 0.0) turn += 2.0 * std::numbers::pi;
  const double arc = sectionWrappedArc(link.section, planePoint(cable.joints[p].local_b),
                                       planePoint(cable.joints[k].local_a), link.orientation);
  return turn + 2.0 * std::numbers::pi * std::round((link.arc() - arc) / link.section.perimeter());
}

}  // namespace reeve
