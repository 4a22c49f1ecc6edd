// Light bodies placed on their spans (light_bodies.h).
#include "light_bodies.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "island.h"
#include "reeve/engine/world.h"

namespace reeve {
namespace {

// A span the placement can take: a rigid two-point path between two
// bodies. Its end on a run's end body may roll (the solve holds its
// tangent point and counts the cable its turn pays out: placeLightBodies);
// a member is tied at a fixed point (findLightBodies).
inline bool plainSpan(const PathConstraint& p) {
  return p.points.size() == 2 && p.enabled && p.weights.empty() && p.compliance == 0.0 &&
         p.points[0].body != p.points[1].body;
}

bool dynamic(const World& world, BodyId id) {
  if (id == kWorldBody) return false;
  const BodyState& b = world.body(id);
  return b.inv_mass > 0.0 && !b.isRotor() && !b.kinematic;
}

// The mass (kg) a hinged wheel (a rotor) at a run's end sets against the
// pull of its span `path` at the tie point `end`: its rim's, I / r^2 at
// the point's distance r from its axle, and the dynamic bodies its other
// spans lead to, which its turn moves (a knot's cable over a 2 kg wheel
// to 100 kg on its other side pulls against 1 + 100 kg). Infinite for any
// other body that does not move.
double rotorMass(const World& world, const Island& island, const PathPoint& end, int path) {
  const BodyState& b = world.body(end.body);
  if (end.body == kWorldBody || !b.isRotor()) return std::numeric_limits<double>::infinity();
  const Vec3& axle = b.rotor_axis;
  const double r2 = (end.local - axle.dot(end.local) * axle).squaredNorm();
  if (!(r2 > 0.0)) return std::numeric_limits<double>::infinity();
  double mass = axle.dot(b.inertia * axle) / r2;
  for (const int i : island.paths) {
    const PathConstraint& other = world.path(i);
    if (i == path || !other.enabled || other.points.size() != 2) continue;
    for (int k = 0; k < 2; ++k)
      if (other.points[k].body == end.body && dynamic(world, other.points[1 - k].body))
        mass += 1.0 / world.body(other.points[1 - k].body).inv_mass;
  }
  return mass;
}

// Whether anything but plain spans acts on `id`: a joint, a distance
// constraint, a contact or another path.
bool heldOtherwise(const World& world, const Island& island, BodyId id) {
  const auto on = [&](BodyId a, BodyId b) { return a == id || b == id; };
  for (const int i : island.hinges)
    if (on(world.hinges()[i].a, world.hinges()[i].b)) return true;
  for (const int i : island.prismatics)
    if (on(world.prismatics()[i].a, world.prismatics()[i].b)) return true;
  for (const int i : island.sphericals)
    if (on(world.sphericals()[i].a, world.sphericals()[i].b)) return true;
  for (const int i : island.fixeds)
    if (on(world.fixedJoints()[i].a, world.fixedJoints()[i].b)) return true;
  for (const int i : island.distances)
    if (on(world.distance(i).a, world.distance(i).b)) return true;
  for (const int i : island.manifolds)
    if (on(world.contactManifolds()[i].a, world.contactManifolds()[i].b)) return true;
  for (const int i : island.paths) {
    const PathConstraint& p = world.path(i);
    if (!p.enabled || plainSpan(p)) continue;
    for (const PathPoint& point : p.points)
      if (point.body == id) return true;
  }
  return false;
}

// The point nearest p on the sphere about c of radius r.
Vec3 ontoSphere(const Vec3& p, const Vec3& c, double r) {
  const Vec3 w = p - c;
  const double n = w.norm();
  return n > 0.0 ? Vec3(c + w * (r / n)) : p;
}

}  // namespace

void findLightBodies(const World& world, const Island& island, std::vector<LightBody>& scratch,
                     std::vector<LightBody>& bodies, std::vector<LightRun>& runs) {
  bodies.clear();
  runs.clear();
  // None where no body is that much lighter than another (most islands):
  // a light body's far ends are in its island.
  if (!island.light_possible) return;
  // Each plain span's two ends, one entry each (path[0], end[0]).
  std::vector<LightBody>& ends = scratch;
  ends.clear();
  int spans = 0;
  for (const int i : island.paths) {
    const PathConstraint& p = world.path(i);
    if (!plainSpan(p)) continue;
    ++spans;
    for (int end = 0; end < 2; ++end)
      if (p.points[end].body != kWorldBody) ends.push_back({p.points[end].body, {i, 0}, {end, 0}});
  }
  if (spans < 2) return;
  // The members a run may have: dynamic bodies at exactly two ends, tied
  // at one point, held by nothing else; into the back of `ends`, by body.
  std::sort(ends.begin(), ends.end(), [](const LightBody& x, const LightBody& y) {  // in place: no allocation
    return x.body != y.body ? x.body < y.body : x.path[0] != y.path[0] ? x.path[0] < y.path[0] : x.end[0] < y.end[0];
  });
  const std::size_t first_member = ends.size();
  for (std::size_t k = 0; k < first_member;) {
    std::size_t next = k + 1;
    while (next < first_member && ends[next].body == ends[k].body) ++next;
    const BodyId id = ends[k].body;
    const auto tie = [&](std::size_t e) -> const PathPoint& {
      return world.path(ends[e].path[0]).points[ends[e].end[0]];
    };
    if (next - k == 2 && dynamic(world, id) && tie(k).local == tie(k + 1).local && tie(k).roll_axis.isZero() &&
        tie(k + 1).roll_axis.isZero() && !heldOtherwise(world, island, id))
      ends.push_back({id, {ends[k].path[0], ends[k + 1].path[0]}, {ends[k].end[0], ends[k + 1].end[0]}});
    k = next;
  }
  const auto members = std::span<LightBody>(ends).subspan(first_member);
  const auto member = [&](BodyId id) -> LightBody* {  // by body: members are sorted
    const auto it = std::lower_bound(members.begin(), members.end(), id,
                                     [](const LightBody& m, BodyId b) { return m.body < b; });
    return it != members.end() && it->body == id ? &*it : nullptr;
  };
  const auto farEnd = [&](int path, int end) { return world.path(path).points[1 - end]; };
  // Runs: members joined span to span, from one end body that is not a
  // member to another. A member's end[0] + 2 marks it taken.
  for (LightBody& start : members) {
    if (start.end[0] >= 2) continue;
    // Back along its first span to the run's first member.
    LightBody* first = &start;
    int span = 0;  // the side of `first` that leads back
    bool loop = false;
    for (LightBody* m = &start;;) {
      const PathPoint far = farEnd(m->path[span], m->end[span]);
      LightBody* back = far.body == kWorldBody ? nullptr : member(far.body);
      if (back == nullptr) break;
      if (back == &start) {
        loop = true;  // a closed ring of light bodies: no end to place it from
        break;
      }
      span = back->path[0] == m->path[span] ? 1 : 0;  // its other span leads further back
      first = m = back;
    }
    // Forward: each member oriented, path[0] towards the run's first end.
    const std::size_t run_first = bodies.size();
    for (LightBody* m = first;;) {
      LightBody oriented = *m;
      if (span == 1) {
        std::swap(oriented.path[0], oriented.path[1]);
        std::swap(oriented.end[0], oriented.end[1]);
      }
      m->end[0] += 2;  // taken
      bodies.push_back(oriented);
      const PathPoint far = farEnd(oriented.path[1], oriented.end[1]);
      LightBody* next = far.body == kWorldBody ? nullptr : member(far.body);
      if (next == nullptr || next->end[0] >= 2) break;
      span = next->path[0] == oriented.path[1] ? 0 : 1;  // the side it is entered by
      m = next;
    }
    // Light against the lightest dynamic body at the run's two ends, or
    // with none, the lighter hinged wheel there (rotorMass), every member;
    // else no run. Both ends on one body (a loop of cable from a box back
    // to it) is none either: Gauss-Seidel's row between them would hold
    // one body to itself.
    const int count = static_cast<int>(bodies.size() - run_first);
    const PathPoint first_end = farEnd(bodies[run_first].path[0], bodies[run_first].end[0]);
    const PathPoint last_end = farEnd(bodies.back().path[1], bodies.back().end[1]);
    double lightest = std::numeric_limits<double>::infinity();
    for (const PathPoint& end : {first_end, last_end})
      if (dynamic(world, end.body)) lightest = std::min(lightest, 1.0 / world.body(end.body).inv_mass);
    if (!std::isfinite(lightest))  // between wheels, or a wheel and an anchor
      lightest = std::min(rotorMass(world, island, first_end, bodies[run_first].path[0]),
                          rotorMass(world, island, last_end, bodies.back().path[1]));
    bool light = !loop && std::isfinite(lightest) && first_end.body != last_end.body;
    for (std::size_t k = run_first; k < bodies.size() && light; ++k)
      light = 1.0 / world.body(bodies[k].body).inv_mass <= kMasslessShare * lightest;
    if (light) runs.push_back({static_cast<int>(run_first), count});
    else bodies.resize(run_first);
  }
}

namespace {

// Where a massless body tied between the points a and b by spans of rest
// lengths l0 and l1 lies, from where it is now: in place while both spans
// are within their lengths; onto the sphere of the one it overstretches,
// or onto their circle; on the line between a and b, the excess shared
// evenly, once they are further apart than l0 + l1.
Vec3 massless(const Vec3& now, const Vec3& a, const Vec3& b, double l0, double l1) {
  const double d = (b - a).norm();
  if (!(d > 0.0)) return now;
  const Vec3 u = (b - a) / d;
  if (d >= l0 + l1) return a + u * (l0 + 0.5 * (d - l0 - l1));  // taut and straight
  const bool in0 = (now - a).norm() <= l0, in1 = (now - b).norm() <= l1;
  if (in0 && in1) return now;  // slack or just taut: where the solve left it
  const Vec3 p0 = ontoSphere(now, a, l0), p1 = ontoSphere(now, b, l1);
  if (!in0 && (p0 - b).norm() <= l1) return p0;
  if (!in1 && (p1 - a).norm() <= l0) return p1;
  if (d <= std::abs(l0 - l1)) return l0 < l1 ? p0 : p1;  // one ball inside the other: onto the smaller
  // Both taut and bent: on the circle where the spheres meet, at its
  // centre c = a + u s, radius rho, nearest the body.
  const double s = (d * d + l0 * l0 - l1 * l1) / (2.0 * d);
  const double rho = std::sqrt(std::max(0.0, l0 * l0 - s * s));
  const Vec3 c = a + u * s;
  Vec3 w = (now - c) - (now - c).dot(u) * u;
  if (!(w.norm() > 0.0)) w = u.unitOrthogonal();
  return c + rho * w.normalized();
}

// Moves `body` so that its tie point `arm` (world, from its centre) is at
// p; its start pose with it (light_bodies.h).
void moveTo(BodyState& body, const Vec3& arm, const Vec3& p) {
  const Vec3 moved = p - (body.x + arm);
  body.x += moved;
  body.x_prev += moved;
}

// A member's tie point, from its centre (world, m), and where it is.
Vec3 tieArm(const World& world, const LightBody& light) {
  return world.body(light.body).q * world.path(light.path[0]).points[light.end[0]].local;
}
Vec3 tiePoint(const World& world, const LightBody& light) { return world.body(light.body).x + tieArm(world, light); }

// A run's end (light_bodies.h): where the solve holds the point on its
// end body, and the cable (m) its turn has paid into the span that leads
// to `near` (0 at a fixed point). A rolling end's tangent point is held
// where it was, turned back with its wheel, and the span is longer by
// what the turn wound off (path_constraint.h, SolvePoint): to second
// order the span's end is a fixed point there, an involute's centre of
// curvature being its tangent point.
struct RunEnd {
  Vec3 at = Vec3::Zero();
  double paid = 0.0;
};
RunEnd runEnd(const World& world, const PathPoint& end, const Vec3& near, bool stores) {
  const BodyState& body = world.body(end.body);
  if (end.roll_axis.isZero()) return {body.toWorld(end.local), 0.0};
  const SolvePoint solved = solvePoint(body, end, true, stores);
  const Vec3 at = body.x + solved.arm, g = at - near;  // the span's length grows with g
  const double n = g.norm();
  return {at, n > 0.0 ? -solved.payOut(g / n) : 0.0};
}

}  // namespace

void placeLightBodies(World& world, const std::vector<LightBody>& bodies, const std::vector<LightRun>& runs,
                      bool stores) {
  const auto point = [&](const PathPoint& p) { return world.body(p.body).toWorld(p.local); };
  for (const LightRun& run : runs) {
    const LightBody* m = bodies.data() + run.first;
    const LightBody& last = m[run.count - 1];
    const PathConstraint& first_span = world.path(m[0].path[0]);
    const PathConstraint& last_span = world.path(last.path[1]);
    const RunEnd a = runEnd(world, first_span.points[1 - m[0].end[0]], tiePoint(world, m[0]), stores);
    const RunEnd b = runEnd(world, last_span.points[1 - last.end[1]], tiePoint(world, last), stores);
    // Taut from end to end: every member on the straight line, each span
    // long by an even share of the excess.
    double total = first_span.rest_length + a.paid + b.paid;
    for (int k = 0; k < run.count; ++k) total += world.path(m[k].path[1]).rest_length;
    const double d = (b.at - a.at).norm();
    if (run.count > 1 && d > 0.0 && d >= total) {
      const Vec3 u = (b.at - a.at) / d;
      const double share = (d - total) / (run.count + 1);
      double along = a.paid;
      for (int k = 0; k < run.count; ++k) {
        along += world.path(m[k].path[0]).rest_length + share;
        moveTo(world.body(m[k].body), tieArm(world, m[k]), a.at + u * along);
      }
      continue;
    }
    // Else each member from its neighbours as they are, the run swept as
    // often as it has members (one sweep passes a move one member on).
    for (int sweep = 0; sweep < run.count; ++sweep)
      for (int k = 0; k < run.count; ++k) {
        const LightBody& light = m[k];
        const PathConstraint &span0 = world.path(light.path[0]), &span1 = world.path(light.path[1]);
        const BodyState& body = world.body(light.body);
        const Vec3 arm = tieArm(world, light);
        const bool first = k == 0, final = k + 1 == run.count;
        moveTo(world.body(light.body), arm,
               massless(body.x + arm, first ? a.at : point(span0.points[1 - light.end[0]]),
                        final ? b.at : point(span1.points[1 - light.end[1]]),
                        span0.rest_length + (first ? a.paid : 0.0), span1.rest_length + (final ? b.paid : 0.0)));
      }
  }
}

void setLightVelocities(World& world, const std::vector<LightBody>& bodies, const std::vector<LightRun>& runs,
                        bool stores) {
  for (const LightRun& run : runs) {
    const LightBody* m = bodies.data() + run.first;
    const LightBody& last = m[run.count - 1];
    const PathPoint& end_a = world.path(m[0].path[0]).points[1 - m[0].end[0]];
    const PathPoint& end_b = world.path(last.path[1]).points[1 - last.end[1]];
    // What the cable at each end moved this substep: a fixed end's point;
    // at a rolling end (its tangent point set on the integrated pose
    // q_pred) the cable leaves along the tangent by the arc the body
    // turned (a rim point's chord would pull the run towards the wheel's
    // centre, 2.5 % of the cable's speed at 0.15 rad a substep).
    const auto moved = [&](const PathPoint& end) {
      const BodyState& body = world.body(end.body);
      if (end.body == kWorldBody || (!body.moves() && !body.kinematic)) return Vec3(Vec3::Zero());
      if (end.roll_axis.isZero()) return Vec3(body.toWorld(end.local) - (body.x_prev + body.q_prev * end.local));
      Quat turn = body.q * body.q_prev.conjugate();
      if (turn.w() < 0.0) turn.coeffs() *= -1.0;  // the shorter way round
      const Eigen::AngleAxisd angle_axis(turn);
      return Vec3(body.x - body.x_prev + (angle_axis.angle() * angle_axis.axis()).cross(body.q_pred * end.local));
    };
    const Vec3 moved_a = moved(end_a), moved_b = moved(end_b);
    const Vec3 a = runEnd(world, end_a, tiePoint(world, m[0]), stores).at;
    const Vec3 b = runEnd(world, end_b, tiePoint(world, last), stores).at;
    // The span before member k.
    const auto gap = [&](int k) { return (tiePoint(world, m[k]) - (k == 0 ? a : tiePoint(world, m[k - 1]))).norm(); };
    double total = (b - tiePoint(world, last)).norm();
    for (int k = 0; k < run.count; ++k) total += gap(k);
    double along = 0.0;
    for (int k = 0; k < run.count; ++k) {
      along += gap(k);
      const double s = total > 0.0 ? along / total : 0.5;
      BodyState& body = world.body(m[k].body);
      body.x_prev = body.x - ((1.0 - s) * moved_a + s * moved_b);
    }
  }
}

}  // namespace reeve
