// The per-substep cable update: paper Alg. 1 (tangent points, rest
// lengths) and Alg. 2 (stored cable, hybrid links, merge, split); runs
// through pinholes and sliding wraps are in cable_runs.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

#include "link_geometry.h"
#include "links.h"
#include "reeve/cable/cable.h"

namespace reeve {
namespace {

// Splits wait until a span cuts this deep (m) into a section, so a span
// that has just merged, grazing its link, does not split straight back.
constexpr double kSplitMargin = 1e-6;

// A span within this fraction of a sphere's or hull's outer radius of its
// link's cable plane is in it (rounding off a planar machine's plane).
constexpr double kSamePlane = 1e-9;

// Where a span from world point `p` to `q` that the split test sees
// crossing the inactive link (or sweeping past its centre: `swept`) wraps
// it: the cable-plane offset (m, body-local z) and, for a sphere or hull,
// the body's section there; nullopt where it passes beside the body. The
// split tests see the span projected into the cable plane (sec. 3.4), so
// a span two radii beside a wheel, parallel to its plane, would wrap it:
// wheels_3d run on split the light box's span onto the wheel beside its
// own, then merged and split it between the two until it ran out, 8.8e4 J
// made in one frame. Within a section radius of the plane, the section
// stands for the cable (a wheel's groove; the paper's machines lie there).
// Farther out, a span passing within the body's thickness meets it there,
// and is wrapped where it met it (a bar, a peg; a given section too: a
// string passing a 10 cm peg 8 cm from its given 3 cm groove, wrapped in
// the groove's plane, was longer than the span by the detour, and made
// 1.8 J). A sphere's or hull's section changes with depth: met off the
// plane, the span wraps the body's section where it met it, if it cuts
// that (a string passing a ball 7 cm off its plane, wrapped at the ball's
// full 10 cm radius in the plane, made 1.1 J).
struct Wrap {
  double plane_offset;
  bool sliced;  // the link's new section is `slice`, the body's own there
};
std::optional<Wrap> wrapAt(const Link& link, const Shape& shape, const BodyState& body, const Vec3& p,
                           const Vec3& q, bool swept, Section& slice, std::vector<Vec2>& points) {
  if (link.depth != Link::Depth::Slice) {
    if (!swept && !spanCutsSection(link.section, body, p, q, kSplitMargin)) return std::nullopt;
    const double z = spanDepth(body, link.section.centre, p, q);
    const double radius = link.section.perimeter() / (2.0 * std::numbers::pi);
    if (std::abs(z - link.plane_offset) <= radius) return Wrap{link.plane_offset, false};
    if (std::abs(z) > halfDepth(shape)) return std::nullopt;
    return Wrap{z, false};
  }
  // Every section lies within the outer circle: most spans stop here.
  if (!swept && !spanCutsSection(Section{Section::Kind::Circle, outerRadius(shape), {}}, body, p, q, kSplitMargin))
    return std::nullopt;
  // In the plane to rounding (a planar machine's): its own section.
  const double z = spanDepth(body, Vec2::Zero(), p, q);  // the shape's own sections are centred
  if (std::abs(z - link.plane_offset) <= kSamePlane * outerRadius(shape)) {
    if (!swept && !spanCutsSection(link.section, body, p, q, kSplitMargin)) return std::nullopt;
    return Wrap{link.plane_offset, false};
  }
  if (!ownSection(shape, z, slice, points) || (!swept && !spanCutsSection(slice, body, p, q, kSplitMargin)))
    return std::nullopt;
  return Wrap{z, true};
}

// The turn (rad) of dq = q q_last^-1 about n, its axle's world direction
// (local z), with whole turns from `spin` (rad), the turn known otherwise:
// the geometry gives the turn only up to whole turns.
double unwrappedTurn(const Quat& dq, const Vec3& n, double spin) {
  const double twist = 2.0 * atan2Small(dq.vec().dot(n), dq.w());
  return spin + wrapAngle(twist - spin);
}

// The bearing (rad) of the world point p from the link's section centre,
// in its cable plane, in the body's frame.
double bearing(const Link& link, const BodyState& body, const Vec3& p) {
  const Vec2 r = toPlane(body, p) - link.section.centre;
  return std::atan2(r.y(), r.x());
}

}  // namespace

double CableSystem::travelSinceSolve(const Cable& cable, int k, int j, double h) const {
  // The bearing of the span's other end as the last solve left both bodies
  // (x_prev, q_prev) and as integrated since; the body's turn between, in
  // whole turns from its spin (integrate() turns it by h omega exactly).
  const Link& link = cable.links[k];
  const bool leaving = k == 0;
  const CableJoint& joint = cable.joints[j];
  const BodyState& body = world_.body(link.body);
  const BodyState& other = world_.body(cable.links[leaving ? joint.to : j].body);
  const Vec3& other_local = leaving ? joint.local_b : joint.local_a;
  const Vec3 now = other.toWorld(other_local);
  const Vec3 before = other.toWorldAtSubstepStart(other_local);
  const Vec3 local_before = body.moves() ? Vec3(body.q_prev.conjugate() * (before - body.x_prev)) : body.toLocal(before);
  const Vec2 r = Vec2(local_before.x(), local_before.y()) - link.section.centre;
  const Vec3 n = planeNormal(body.q);
  const double turn = body.moves() ? unwrappedTurn(body.q * body.q_prev.conjugate(), n, (h * body.omega).dot(n)) : 0.0;
  return turn - reeve::wrapAngle(bearing(link, body, now) - std::atan2(r.y(), r.x()) + turn);
}

bool CableSystem::spunByItsLoad(const Cable& cable, int k, int j) const {
  const Link& link = cable.links[k];
  const CableJoint& joint = cable.joints[j];
  const BodyState& body = world_.body(link.body);
  const BodyState& other = world_.body(cable.links[k == 0 ? joint.to : j].body);
  if (!(other.inv_mass > 0.0) || other.kinematic) return false;
  const double radius = link.section.perimeter() / (2.0 * std::numbers::pi);
  const double rim = body.inertia(2, 2) / (radius * radius);  // kg, about the cable plane's normal (local z)
  return rim * other.inv_mass < kSpunByItsLoad;
}

double CableSystem::turnSinceUpdate(BodyId b, double spin) const {
  const BodyState& body = world_.body(b);
  return unwrappedTurn(body.q * last_q_[b].conjugate(), planeNormal(body.q), spin);
}

void CableSystem::measureTurns(int island, double h, int substep) {
  // Whole turns from the last solve's own turn (BodyState::solve_turn, as
  // far as the direct solver turned it) and this substep's integration
  // (h omega).
  for (int k = rolling_begin_[island + 1]; k < rolling_begin_[island + 2]; ++k) {
    const BodyId b = rolling_by_island_[k];
    const BodyState& body = world_.body(b);
    // An update by hand between steps counted the last solve's turn.
    const Vec3 solved = substep > 0 || !solve_turn_counted_ ? body.solve_turn : Vec3::Zero();
    const Vec3 n = planeNormal(body.q);
    const Quat dq = body.q * last_q_[b].conjugate();
    turn_[b] = unwrappedTurn(dq, n, (h * body.omega + solved).dot(n));
    // A rotor turns about its axle alone, and its axle stays put; a static
    // body stays put; unless moved by hand (a pose set between steps), which
    // this sees: dq's vector part off the axle, or a new position.
    const Vec3& axle = body.rotor_axis;
    steady_[b] = (body.isRotor() && axle.x() * axle.x() + axle.y() * axle.y() <= 1e-30) ||
                 (!body.moves() && !body.kinematic);
    const Vec3 v = dq.vec();
    in_place_[b] = steady_[b] && body.x == last_x_[b] && (v - v.dot(n) * n).squaredNorm() <= 1e-30;
    last_q_[b] = body.q;
    move_[b] = (body.x - last_x_[b]).norm();
    last_x_[b] = body.x;
  }
}

namespace {

// Items 0..n-1 sorted by island (-1 first) into `order`, island i's from
// begin[i + 1] to begin[i + 2]; a counting sort, stable, into storage kept.
template <class IslandOf>
void groupByIsland(int n, IslandOf island_of, std::vector<int>& order, std::vector<int>& begin) {
  int islands = 0;
  for (int k = 0; k < n; ++k) islands = std::max(islands, island_of(k) + 1);
  begin.assign(islands + 2, 0);
  for (int k = 0; k < n; ++k) ++begin[island_of(k) + 2];
  for (int i = 1; i < islands + 2; ++i) begin[i] += begin[i - 1];  // begin[i + 1]: where island i starts
  order.resize(n);
  for (int k = 0; k < n; ++k) order[begin[island_of(k) + 1]++] = k;
  // Each start has moved on to its island's end: one place up, they start.
  for (int i = islands + 1; i > 0; --i) begin[i] = begin[i - 1];
  begin[0] = 0;
}

}  // namespace

void CableSystem::beginUpdate(double h) {
  // Nothing here changes when called again within a step (World::
  // IslandHook::whole_steps).
  poses_predicted_ = h > 0.0;
  if (updates_.size() != cables_.size()) {
    const std::size_t added = updates_.size();
    updates_.resize(cables_.size());
    for (std::size_t c = added; c < cables_.size(); ++c) reserveSlice(static_cast<int>(c));
  }
  // Sorted again only when the islands were built again (a cable added
  // couples its links, which builds them).
  if (grouped_for_ == world_.islandsBuilt()) return;
  grouped_for_ = world_.islandsBuilt();
  // A cable's links are one island (World::coupleBodies), or on none.
  const auto cable_island = [&](int c) {
    for (const Link& link : cables_[c].links)
      if (const int island = world_.islandOfBody(link.body); island >= 0) return island;
    return -1;
  };
  groupByIsland(static_cast<int>(cables_.size()), cable_island, cables_by_island_, cable_begin_);
  groupByIsland(
      static_cast<int>(rolling_bodies_.size()), [&](int k) { return world_.islandOfBody(rolling_bodies_[k]); },
      rolling_by_island_, rolling_begin_);
  for (int& k : rolling_by_island_) k = rolling_bodies_[k];
}

void CableSystem::reserveSlice(int c) {
  std::size_t room = 0;
  for (const Link& link : cables_[c].links)
    if (link.depth == Link::Depth::Slice) room = std::max(room, sectionRoom(world_.bodyDef(link.body).shape));
  updates_[c].slice_points.reserve(room);
  updates_[c].slice.vertices.reserve(2 * room);
}

bool CableSystem::updateIsland(int island, double time_s, double h, int substep) {
  if (island + 2 >= static_cast<int>(rolling_begin_.size()) && island + 2 >= static_cast<int>(cable_begin_.size()))
    return false;  // no cable on it
  if (island + 2 < static_cast<int>(rolling_begin_.size())) measureTurns(island, h, substep);
  bool news = false;
  if (island + 2 < static_cast<int>(cable_begin_.size()))
    for (int k = cable_begin_[island + 1]; k < cable_begin_[island + 2]; ++k)
      news |= updateCable(cables_by_island_[k], time_s, h);
  return news;
}

void CableSystem::update(double time_s, double h) {
  const int islands = world_.islandCount();
  beginUpdate(h);
  for (int i = -1; i < islands; ++i) updateIsland(i, time_s, h, 0);
  endUpdate(time_s);
  solve_turn_counted_ = h == 0.0;
}

void CableSystem::endUpdate(double time_s) {
  if (poses_predicted_) solve_turn_counted_ = false;  // a substep's update, after its integration
  poses_predicted_ = false;
  // Only a cable's event, jam or broken invariant is news: without any,
  // this thread reads no cable's record (each stays in the cache of the
  // thread that updates it).
  if (!news_.exchange(false, std::memory_order_relaxed)) return;
  // The news of updates that ended by time_s; an island running ahead on
  // its own (World::IslandHook::whole_steps) leaves its later news to the
  // endUpdate of its substep.
  const auto due = [&](const CableUpdate& u) { return u.news_at <= time_s; };
  bool later = false;
  for (CableUpdate& u : updates_) {
    const bool news = !u.events.empty() || !u.jams.empty() || u.breached;
    if (news && !due(u)) later = true;
    if (!due(u)) continue;
    events_.insert(events_.end(), u.events.begin(), u.events.end());
    u.events.clear();
  }
  if (later) news_.store(true, std::memory_order_relaxed);
  addJamJoints(time_s);
  if (breach_) return;  // the first one says what went wrong
  // Each cable checked its own (updateCable); the first in cable order is
  // the one found.
  int breached = -1;
  for (int c = 0; c < static_cast<int>(updates_.size()) && breached < 0; ++c)
    if (updates_[c].breached && due(updates_[c])) breached = c;
  if (breached < 0) return;
  if (auto b = cableBreach(breached)) {
    b->time_s = time_s;
    // Its own rolling bodies: another island's may be at another substep.
    for (const Link& link : cables_[breached].links) {
      if (!link.rolls()) continue;
      const BodyId body = link.body;
      if (b->fastest < 0 || std::abs(turn_[body]) > std::abs(b->fastest_turn)) {
        b->fastest = body;
        b->fastest_turn = turn_[body];
      }
      // Its size for the tangents: the smallest of its cable sections (the
      // radius of a circle of the same perimeter).
      double radius = std::numeric_limits<double>::infinity();
      for (const Cable& c : cables_)
        for (const Link& other : c.links)
          if (other.body == body && other.rolls())
            radius = std::min(radius, other.section.perimeter() / (2.0 * std::numbers::pi));
      if (b->farthest < 0 || move_[body] / radius > b->farthest_move / b->farthest_radius) {
        b->farthest = body;
        b->farthest_move = move_[body];
        b->farthest_radius = radius;
      }
    }
    breach_ = std::move(b);
  }
}

bool CableSystem::updateCable(int c, double time_s, double h) {
  Cable& cable = cables_[c];
  CableUpdate& out = updates_[c];
  ++out.count;
  if (out.fixed.size() != cable.joints.size()) out.fixed.assign(cable.joints.size(), FixedSpan{});
  out.winch_work = 0.0;  // this substep's, added to winch_total below
  const std::size_t events_before = out.events.size();
  if (h > 0.0 && std::isfinite(cable.breaking_tension)) breakOverloaded(cable, c, time_s, h);
  if (cable.winch && h > 0.0) reel(cable, time_s - h, h);
  // Runs' rest lengths as the last solve left them, before this
  // substep's turns pay cable in and out.
  out.friction_loss += settleRuns(cable, h, h == 0.0, &cable);
  for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) updateJoint(cable, c, j, time_s);
  if (cable.broken) releaseFreeEnds(cable, c, time_s);
  switchHybrids(cable, c, time_s, h);
  mergeEmptyLinks(cable, c, time_s);
  splitAtCrossedLinks(cable, c, time_s);
  if (h > 0.0) switchSlips(cable, h);
  buildRuns(cable);
  watchHeldRuns(cable, c, time_s, out.events.size() != events_before);
  // A run of one span whose tangent points were kept lies where it lay
  // (PathConstraint::placement), unless a link switched, merged or split
  // since updateJoint kept them.
  if (out.events.size() == events_before && out.fixed.size() == cable.joints.size())
    for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
      const CableJoint& joint = cable.joints[j];
      PathConstraint& path = world_.path(joint.path);
      if (joint.run == j && path.enabled && path.points.size() == 2 && out.fixed[j].update == out.count)
        path.placement = out.fixed[j].found;
    }
  // A junction's path once a substep, from its branches' new runs: its
  // cables update in cable order on one thread (one island), so after the
  // last of them.
  if (cable.junction >= 0 && c == junctions_[cable.junction].cables_last)
    buildJunction(junctions_[cable.junction]);
  out.winch_total += out.winch_work;
  out.breached = cableBreach(c).has_value();
  const bool news = out.breached || !out.events.empty() || !out.jams.empty();
  if (news) {
    out.news_at = time_s;
    news_.store(true, std::memory_order_relaxed);
  }
  return news;
}

bool CableSystem::keepsTangents(const Cable& cable, int c, int j) const {
  // Two circles that stayed where they were have the same tangents in the
  // world (paper App. A; Fig. 6's alternation converges to them), so the
  // last update's, in the bodies' turned frames, are this one's.
  const CableJoint& joint = cable.joints[j];
  const FixedSpan& fixed = updates_[c].fixed[j];
  const Link &from = cable.links[j], &to = cable.links[joint.to];
  return fixed.update == updates_[c].count - 1 && fixed.to == joint.to && from.rolls() && to.rolls() &&
         fixed.sides == from.orientation * 2 + to.orientation && in_place_[from.body] && in_place_[to.body];
}

void CableSystem::updateJoint(Cable& cable, int c, int j, double time_s) {
  Link& from = cable.links[j];
  CableJoint& joint = cable.joints[j];
  Link& to = cable.links[joint.to];
  if (!from.active || joint.parted || joint.jammed) return;
  if ((from.type == LinkType::Pinhole || to.type == LinkType::Pinhole) && jamAtPinhole(cable, c, j, time_s)) return;
  if (!from.rolls() && !to.rolls()) return;
  const BodyState &from_body = world_.body(from.body), &to_body = world_.body(to.body);
  FixedSpan& fixed = updates_[c].fixed[j];
  const bool kept = keepsTangents(cable, c, j);
  const auto anchors =
      kept ? std::optional{std::pair{from_body.toLocal(fixed.a), to_body.toLocal(fixed.b)}}
           : spanAnchors(from, from_body, to, to_body, joint.local_b, to.rolls() ? turn_[to.body] : 0.0);
  // Circles that stay in space: on a steady body, about its axle if it turns.
  const auto stays = [&](const Link& link) {
    return link.section.kind == Section::Kind::Circle && steady_[link.body] &&
           (link.section.centre == Vec2::Zero() || !world_.body(link.body).moves());
  };
  if (anchors && from.rolls() && to.rolls() && stays(from) && stays(to)) {
    if (!kept) {  // found afresh; kept ones stay as they were in the world, not rounded through the poses
      fixed.a = from_body.toWorld(anchors->first);
      fixed.b = to_body.toWorld(anchors->second);
      fixed.found = updates_[c].count;
    }
    fixed.update = updates_[c].count;
    fixed.to = joint.to;
    fixed.sides = from.orientation * 2 + to.orientation;
  } else {
    fixed.update = -1;
  }
  if (!anchors) {  // overlapping sections, or a tie point inside its wheel: keep the old anchors
    // A tie point drawn inside the wheel it is wound onto has run its span
    // out too (a load hauled up into its drum; item 9), and jams there.
    if (from.rolls() != to.rolls() && !joint.ran_out)
      updates_[c].events.push_back({CableEvent::Kind::SpanRunsOut, time_s, c, j, (from.rolls() ? from : to).orientation});
    joint.ran_out |= from.rolls() != to.rolls();
    if (joint.ran_out) jam(cable, c, j);
    return;
  }
  // Alg. 1 l. 4-5 and Alg. 2 l. 8-9: the anchors turned with their bodies
  // since the last update; the arc from the new tangent point back to the
  // old anchor is cable paid out into the span (leaving side) or taken up
  // from it (arriving side).
  // Kept tangent points stayed in the world while the wheel turned under
  // them: its arc is r turn (sectionSurfaceDistance's, with no angle to
  // take).
  const auto arc = [&](const Link& link, const Vec3& old_anchor, const Vec3& anchor) {
    const double turn = turn_[link.body];
    return kept ? link.orientation * link.section.radius * turn : payOut(link, old_anchor, anchor, turn);
  };
  // Both ends wind at the span's strain as the last solve left it: the
  // span's rest length changes once both have. (Changed by the first end
  // before the second read it, a belt running in the cable's order wound
  // on at its arriving ends the strain less the cable the leaving ends had
  // just paid out, 1.6e-3 at 10 rad/s against a 1e-3 strain: its wraps
  // lost their stretch to its spans, whose tension climbed 80 N in 1 s,
  // while turned the other way round it kept them.)
  const double taken_a = from.rolls() ? windLink(cable, j, j, -arc(from, joint.local_a, anchors->first)) : 0.0;
  const double taken_b = to.rolls() ? windLink(cable, joint.to, j, arc(to, joint.local_b, anchors->second)) : 0.0;
  joint.rest_length -= taken_a;
  joint.rest_length -= taken_b;
  const double wound_a = std::max(0.0, taken_a), wound_b = std::max(0.0, taken_b);  // taken up by each end
  // A span holds no less than no cable. A wheel that turned further than
  // the span could feed it (an unconverged solve: Gauss-Seidel on a wheel
  // 1e-6 of its load) slips on the cable: what it could not wind stays in
  // the span, so the total length is kept and the span pulls its far end in.
  // A span that held cable and has none left ran out (a tie point reached
  // the rim; item 9): said once, until it holds cable again.
  if (joint.rest_length < 0.0 && wound_a + wound_b > 0.0) {
    const double deficit = std::min(-joint.rest_length, wound_a + wound_b);
    from.takeRest(deficit * wound_a / (wound_a + wound_b));
    to.takeRest(deficit * wound_b / (wound_a + wound_b));
    joint.rest_length += deficit;
    if (!joint.ran_out)
      updates_[c].events.push_back({CableEvent::Kind::SpanRunsOut, time_s, c, j, (wound_a >= wound_b ? from : to).orientation});
    joint.ran_out = true;
  } else if (joint.rest_length > 0.0) {
    joint.ran_out = false;
  }
  joint.local_a = anchors->first;
  joint.local_b = anchors->second;
  if (joint.ran_out) jam(cable, c, j);
}

double CableSystem::restOfArc(const Cable& cable, int k, int j, double arc) const {
  if (cable.compliance_per_m == 0.0) return arc;
  if (arc < 0.0) {
    Link link = cable.links[k];
    return -link.windOff(-arc);
  }
  // At the span's strain as the last solve left it: its stretch past its
  // rest length (the spring's; a damped cable's lambda holds its dashpot's
  // pull too), so that the stretch that winds on is the span's own and
  // carries its elastic energy with it. (An estimate of the strain further
  // on, midway through the winding, was second order in the substep for
  // the hand's tendons but made a stiff cable's wound layers stretch from
  // nothing where the span's far end moved with the winding.)
  const CableJoint& span = cable.joints[j];
  const BodyState& a = world_.body(cable.links[j].body);
  const BodyState& b = world_.body(cable.links[span.to].body);
  const auto solved = [&](const BodyState& body, const Vec3& local) {
    return poses_predicted_ ? Vec3(body.x_prev + body.q_prev * local) : body.toWorld(local);
  };
  const double length = (solved(b, span.local_b) - solved(a, span.local_a)).norm();
  if (!(length > span.rest_length) || !(span.rest_length > 0.0)) return arc;  // slack: it winds on unstretched
  return arc * span.rest_length / length;
}

double CableSystem::windLink(Cable& cable, int k, int j, double arc) {
  Link& link = cable.links[k];
  if (arc < 0.0) return -link.windOff(-arc);
  const double rest = restOfArc(cable, k, j, arc);
  link.windOn(rest, arc - rest);
  return rest;
}

double CableSystem::wind(Cable& cable, int k, int j, double arc) {
  // Wound as rest length, an elastic cable's arc left the span short of
  // the cable it gave the wheel, by its strain: the span stretched as it
  // wound, energy from nothing (1/2 T strain per metre; the hand's tendons
  // at 8-30 % strain made 0.02 J as its fingers curled, at any substep).
  const double rest = windLink(cable, k, j, arc);
  cable.joints[j].rest_length -= rest;
  return rest;
}

void CableSystem::switchHybrids(Cable& cable, int c, double time_s, double h) {
  if (cable.closed) return;
  const int last = static_cast<int>(cable.links.size()) - 1;
  for (const int k : {0, last}) {
    Link& link = cable.links[k];
    if (link.type != LinkType::Hybrid) continue;
    const bool leaving = k == 0;  // the span leaves the first link, arrives at the last
    const int j = leaving ? 0 : previousActive(cable, k);
    CableJoint& joint = cable.joints[j];
    if (joint.parted) continue;
    Vec3& anchor = leaving ? joint.local_a : joint.local_b;
    if (!link.attached) {
      if (link.stored >= 0.0) continue;
      // Alg. 2 l. 12-13: the cable has run out; it is tied where it ends.
      // Within this substep it ran out |stored| before the tangent point was
      // reached, so its end has turned that far past it, on towards the
      // span; tying it at the tangent point instead would leave the span
      // too long by |stored| and the solver would yank the spool round.
      // The wrap runs from its end to the tangent point in the sense o
      // where the span leaves the link, from the tangent point to its end
      // where it arrives: past the tangent point is +o |stored| there, -o
      // here. (Taken as +o at an arriving end too, a spool at a cable's far
      // end was tied a quarter turn the wrong way round, at its line-up's
      // far side: the span 2 r too long, its 100 kg load thrown up at 2.4
      // m/s.)
      const double past = (leaving ? -1.0 : 1.0) * link.orientation * link.stored;
      const double end = boundaryPosition(link.section, planePoint(anchor)) + past;
      link.attached = true;
      link.point = fromPlane(link, boundaryPoint(link.section, end));
      anchor = link.point;
      joint.rest_length += link.stored;  // the overdraft, so the total is kept
      link.unwindAll();
      link.tie_bearing = bearing(link, world_.body(link.body), leaving ? endPointOf(cable, j) : startPointOf(cable, j));
      updates_[c].events.push_back({CableEvent::Kind::HybridRunsOut, time_s, c, k, link.orientation});
      continue;
    }
    // Alg. 2 l. 14-20: the tie point is hidden from the span's other end
    // once it has passed one of the two rolling tangent points a+ and a-;
    // then the wraps from it to a+ and to a- add up to less than the whole
    // boundary. Roll again from the tangent point it passed (below).
    const BodyState& body = world_.body(link.body);
    const Vec3 other_end = leaving ? endPointOf(cable, j) : startPointOf(cable, j);
    const Vec2 seen_from = toPlane(body, other_end);
    const Vec2 tie = planePoint(link.point);
    // The tie point's travel round the section since the last update,
    // relative to the span (rad, + counter-clockwise in the plane): the
    // body's turn less the other end's bearing change, whole turns from
    // the turn (the bearing in the body's frame moves by -turn).
    const double bearing_now = bearing(link, body, other_end), turn = turn_[link.body];
    const double travel =
        std::isnan(link.tie_bearing) ? 0.0 : turn - reeve::wrapAngle(bearing_now - link.tie_bearing + turn);
    link.tie_bearing = bearing_now;
    double wrap[2] = {0.0, 0.0};
    Vec2 tangent[2];
    bool found = true;
    for (int i = 0; i < 2; ++i) {
      const int o = i == 0 ? 1 : -1;
      const auto t = tangentFromPoint(link.section, seen_from, o, leaving);
      if (!t) {
        found = false;
        break;
      }
      tangent[i] = *t;
      wrap[i] = leaving ? sectionWrappedArc(link.section, tie, *t, o) : sectionWrappedArc(link.section, *t, tie, o);
    }
    if (!found) continue;
    // Seen, it may still have been carried round past a tangent point and
    // back into view since the last solve: by more than the hidden arc
    // (half a turn, more for a near other end), as an arc on the circle of
    // the section's perimeter as far as from that tangent point, the way
    // it went, to where it is (wrap[], the long way round). Its place
    // alone cannot tell: a spool that ran out spinning on at a whole turn
    // a substep (hybrid.json's at 377 rad/s at one substep of 1/60 s, 754
    // at two) was never seen hidden, and spun on with its load hanging
    // still, a third of the scene's kinetic energy locked in an aliased
    // spin (DESIGN, "Fifty-ninth session"). Only the integration's turn
    // counts, and only a spool that carries its own spin (spunByItsLoad).
    const double perimeter = link.section.perimeter();
    const double carried = h > 0.0 ? travelSinceSolve(cable, k, j, h) : 0.0;
    int swept = -1;  // the wrap[] index a sweep winds on from
    if (std::abs(carried) > std::numbers::pi && !spunByItsLoad(cable, k, j)) {
      const int s = (leaving ? -carried : carried) > 0.0 ? 0 : 1;
      if (std::abs(carried) * perimeter / (2.0 * std::numbers::pi) >= wrap[s]) swept = s;
    }
    if (wrap[0] + wrap[1] >= perimeter && swept < 0) continue;
    // The tie point is hidden past the tangent point it passed, so the
    // cable wraps from that tangent point to it in the sense it travelled:
    // orientation -sense where the span leaves the link (its wrap runs
    // from the tie to the tangent point), +sense where it arrives. A spool
    // that ran out and spins on winds back on the other way (a yo-yo); one
    // turned back winds on as before. With no travel measured yet, the
    // short way round. Taken the short way whatever the travel, a spool
    // turning 3.4 rad a substep past its run-out (a yo-yo on a braking cart
    // at one substep a frame) wound on the way it came, ran out again at
    // once and was spun up by its load: 27 J made in a frame (DESIGN,
    // "Thirty-sixth session").
    // Swept round, it winds on from the tangent point it passed, and the
    // turn's whole turns beyond the first wind on too.
    int i = wrap[0] <= wrap[1] ? 0 : 1;  // i = 0: orientation +1
    if (travel != 0.0) i = (leaving ? -travel : travel) > 0.0 ? 0 : 1;
    double wound = wrap[i];
    if (swept >= 0 && wrap[0] + wrap[1] >= perimeter) {
      i = swept;
      const double arc = std::abs(carried) * perimeter / (2.0 * std::numbers::pi);
      wound = wrap[i] + perimeter * std::floor((arc - wrap[i]) / perimeter);
    }
    link.attached = false;
    link.tie_bearing = std::numeric_limits<double>::quiet_NaN();
    link.orientation = i == 0 ? 1 : -1;
    link.unwindAll();
    wind(cable, k, j, wound);
    anchor = fromPlane(link, tangent[i]);
    updates_[c].events.push_back({CableEvent::Kind::HybridRollsAgain, time_s, c, k, link.orientation});
  }
}

void CableSystem::mergeEmptyLinks(Cable& cable, int c, double time_s) {
  // Alg. 2 l. 23-25, Fig. 11a: an interior rolling link whose stored cable
  // went negative no longer touches the cable; its two spans become one.
  const int n = static_cast<int>(cable.links.size());
  for (int k = 0; k < n; ++k) {
    Link& link = cable.links[k];
    if (link.type != LinkType::Rolling || !link.active || isEnd(cable, k) || link.stored >= 0.0) continue;
    const int p = previousActive(cable, k);
    CableJoint& in = cable.joints[p];
    const CableJoint& out = cable.joints[k];
    if (p == out.to) continue;  // a belt keeps at least two links
    if (in.parted || out.parted) continue;  // a free end: releaseFreeEnds
    in.to = out.to;
    in.local_b = out.local_b;
    in.rest_length += out.rest_length + link.stored;
    in.jammed = false;  // a jammed span merged away: its tie point is held by its ball, the cable reaches it
    link.unwindAll();
    link.active = false;
    link.side = std::numeric_limits<double>::quiet_NaN();  // measured afresh from the next update
    link.slipping = link.mu == 0.0;  // a friction link starts sticking when it is split in again
    link.slip_speed = 0.0;
    updates_[c].events.push_back({CableEvent::Kind::Merge, time_s, c, k, link.orientation});
  }
}

void CableSystem::splitAtCrossedLinks(Cable& cable, int c, double time_s) {
  // Alg. 2 l. 26-28, Fig. 11b: a span that cuts into the section of an
  // inactive link lying between its ends in the cable is split there; the
  // rest length is shared so both parts have the same strain. So is one
  // that swept past the whole section within a substep (a 1 cm peg under a
  // pendulum at one substep a frame, issue 28 item 12): the section's
  // centre changed sides of it, between its ends.
  const int n = static_cast<int>(cable.links.size());
  for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
    if (!cable.links[j].active || cable.joints[j].parted || cable.joints[j].jammed) continue;
    CableJoint& in = cable.joints[j];
    for (int k = (j + 1) % n; k != in.to; k = (k + 1) % n) {
      Link& mid = cable.links[k];
      const double before = mid.side;
      const BodyState& body = world_.body(mid.body);
      const Vec3 p = startPointOf(cable, j), q = endPointOf(cable, j);
      const auto [side, along] = spanSide(body, mid.section.centre, p, q);
      mid.side = side;
      // isnan first: an ordered comparison with NaN raises FE_INVALID.
      const bool swept = !std::isnan(before) && before * side < 0.0 && along > 0.0 && along < 1.0;
      CableUpdate& update = updates_[c];
      const Shape& shape = world_.bodyDef(mid.body).shape;
      std::optional<Wrap> met_at = wrapAt(mid, shape, body, p, q, swept, update.slice, update.slice_points);
      if (!met_at) continue;
      Link& from = cable.links[j];
      Link& to = cable.links[in.to];
      // The cable wraps the section on the side the span met it from, not
      // the side the link was given: a span met with the centre on its left
      // (side < 0) goes round it counter-clockwise. The given side would
      // take it round the far side, stretched, or (longer than the cable)
      // let the wheel through it (DESIGN "A span wraps a wheel on the side
      // it meets it from").
      const double met = !std::isnan(before) && before != 0.0 ? before : side;
      const int given = mid.orientation;
      const double given_plane = mid.plane_offset;
      if (met != 0.0) mid.orientation = met < 0.0 ? 1 : -1;
      mid.plane_offset = met_at->plane_offset;
      if (met_at->sliced) std::swap(mid.section, update.slice);  // which keeps the given one
      mid.active = true;  // so that the tangents below see it rolling
      const auto refuse = [&] {
        mid.active = false;
        mid.orientation = given;
        mid.plane_offset = given_plane;
        if (met_at->sliced) std::swap(mid.section, update.slice);
      };
      const auto first = spanAnchors(from, world_.body(from.body), mid, world_.body(mid.body), Vec3::Zero());
      const auto second = spanAnchors(mid, world_.body(mid.body), to, world_.body(to.body), in.local_b);
      if (!first || !second) {
        refuse();
        continue;
      }
      // Moving the span's ends to the new tangent points pays cable in or
      // out of the end links, as in updateJoint(); the wrap around the new
      // link comes from the span (all as rest lengths: restOfArc).
      const double onto_from = from.rolls() ? -payOut(from, in.local_a, first->first, 0.0) : 0.0;
      const double onto_to = to.rolls() ? payOut(to, in.local_b, second->second, 0.0) : 0.0;
      const double wrap = sectionWrappedArc(mid.section, planePoint(first->second), planePoint(second->first),
                                            mid.orientation);
      const double rest_from = restOfArc(cable, j, j, onto_from), rest_to = restOfArc(cable, in.to, j, onto_to);
      const double rest_wrap = restOfArc(cable, k, j, wrap);
      const double rest = in.rest_length - rest_from - rest_to - rest_wrap;
      if (rest < 0.0) {  // a slack span swept deep into the section: not enough cable to wrap it
        refuse();
        continue;
      }
      if (from.rolls()) windLink(cable, j, j, onto_from);
      if (to.rolls()) windLink(cable, in.to, j, onto_to);
      mid.unwindAll();
      windLink(cable, k, j, wrap);
      mid.side = std::numeric_limits<double>::quiet_NaN();
      CableJoint& out = cable.joints[k];
      out.to = in.to;
      out.local_a = second->first;
      out.local_b = second->second;
      in.to = k;
      in.local_a = first->first;
      in.local_b = first->second;
      const double l_in = spanLength(cable, j), l_out = spanLength(cable, k);
      in.rest_length = l_in + l_out > 0.0 ? rest * l_in / (l_in + l_out) : 0.5 * rest;
      out.rest_length = rest - in.rest_length;
      // The slice's room went to the link with it: room again (this
      // substep's event allows the heap) for the next slice tested.
      if (met_at->sliced) update.slice.vertices.reserve(2 * sectionRoom(shape));
      update.events.push_back({CableEvent::Kind::Split, time_s, c, k, mid.orientation});
      rejamSplit(cable, c, j, k);
      break;  // the new spans are checked again next substep
    }
  }
}

}  // namespace reeve
