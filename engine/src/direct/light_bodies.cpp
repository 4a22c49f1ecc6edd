// Light bodies placed on their spans (light_bodies.h).
#include "light_bodies.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../island.h"
#include "reeve/engine/world.h"

namespace reeve::direct {
namespace {

// A span the placement can take: a rigid two-point path between two
// bodies, both of its ends fixed points (a rolling end winds cable as its
// body turns, which a place on the span does not say).
inline bool plainSpan(const PathConstraint& p) {
  // The rolling ends first (a fixed point's axis is exactly zero): most
  // spans of most machines have one, and most islands no plain span.
  return p.points.size() == 2 && p.points[0].roll_axis.squaredNorm() == 0.0 &&
         p.points[1].roll_axis.squaredNorm() == 0.0 && p.enabled && p.weights.empty() && p.compliance == 0.0 &&
         p.points[0].body != p.points[1].body;
}

bool dynamic(const World& world, BodyId id) {
  if (id == kWorldBody) return false;
  const BodyState& b = world.body(id);
  return b.inv_mass > 0.0 && !b.isRotor() && !b.kinematic;
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

void findLightBodies(const World& world, const Island& island, std::vector<LightBody>& ends,
                     std::vector<LightBody>& out) {
  out.clear();
  // None where no body is that much lighter than another (most islands):
  // a light body's far ends are in its island.
  double least_w = std::numeric_limits<double>::infinity(), most_w = 0.0;  // inverse masses
  for (const BodyId id : island.bodies) {
    const BodyState& b = world.body(id);
    if (!(b.inv_mass > 0.0) || b.kinematic) continue;
    least_w = std::min(least_w, b.inv_mass);
    most_w = std::max(most_w, b.inv_mass);
  }
  if (!(least_w <= kMasslessShare * most_w)) return;
  // Each plain span's two ends, one entry each (path[0], end[0]).
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
  // Bodies at exactly two ends: their spans, in path order.
  std::sort(ends.begin(), ends.end(), [](const LightBody& x, const LightBody& y) {  // in place: no allocation
    return x.body != y.body ? x.body < y.body : x.path[0] != y.path[0] ? x.path[0] < y.path[0] : x.end[0] < y.end[0];
  });
  for (std::size_t k = 0; k < ends.size();) {
    std::size_t next = k + 1;
    while (next < ends.size() && ends[next].body == ends[k].body) ++next;
    if (next - k == 2) out.push_back({ends[k].body, {ends[k].path[0], ends[k + 1].path[0]}, {ends[k].end[0], ends[k + 1].end[0]}});
    k = next;
  }
  const auto heavy = [&](const LightBody& light) {
    if (!dynamic(world, light.body)) return true;
    double lightest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 2; ++k) {
      const BodyId far = world.path(light.path[k]).points[1 - light.end[k]].body;
      if (dynamic(world, far)) lightest = std::min(lightest, 1.0 / world.body(far).inv_mass);
    }
    const PathPoint& a = world.path(light.path[0]).points[light.end[0]];
    const PathPoint& b = world.path(light.path[1]).points[light.end[1]];
    return std::isinf(lightest) || !(1.0 / world.body(light.body).inv_mass <= kMasslessShare * lightest) ||
           a.local != b.local || heldOtherwise(world, island, light.body);
  };
  out.erase(std::remove_if(out.begin(), out.end(), heavy), out.end());
}

void placeLightBodies(World& world, const std::vector<LightBody>& bodies) {
  for (const LightBody& light : bodies) {
    BodyState& body = world.body(light.body);
    const PathConstraint &span0 = world.path(light.path[0]), &span1 = world.path(light.path[1]);
    const Vec3 arm = body.q * span0.points[light.end[0]].local;
    const PathPoint &far0 = span0.points[1 - light.end[0]], &far1 = span1.points[1 - light.end[1]];
    const Vec3 a = world.body(far0.body).toWorld(far0.local), b = world.body(far1.body).toWorld(far1.local);
    const double l0 = span0.rest_length, l1 = span1.rest_length;
    const Vec3 now = body.x + arm;
    const double d = (b - a).norm();
    if (!(d > 0.0)) continue;
    const Vec3 u = (b - a) / d;
    const bool in0 = (now - a).norm() <= l0, in1 = (now - b).norm() <= l1;
    Vec3 p = now;
    if (d >= l0 + l1) {
      p = a + u * (l0 + 0.5 * (d - l0 - l1));  // taut and straight, each span long by half the excess
    } else if (in0 && in1) {
      continue;  // slack or just taut: where the solve left it
    } else if (const Vec3 p0 = ontoSphere(now, a, l0); !in0 && (p0 - b).norm() <= l1) {
      p = p0;
    } else if (const Vec3 p1 = ontoSphere(now, b, l1); !in1 && (p1 - a).norm() <= l0) {
      p = p1;
    } else if (d <= std::abs(l0 - l1)) {  // one ball inside the other: onto the smaller
      p = l0 < l1 ? p0 : p1;
    } else {
      // Both taut and bent: on the circle where the spheres meet, at its
      // centre c = a + u s, radius rho, nearest the body.
      const double s = (d * d + l0 * l0 - l1 * l1) / (2.0 * d);
      const double rho = std::sqrt(std::max(0.0, l0 * l0 - s * s));
      const Vec3 c = a + u * s;
      Vec3 w = (now - c) - (now - c).dot(u) * u;
      if (!(w.norm() > 0.0)) w = u.unitOrthogonal();
      p = c + rho * w.normalized();
    }
    const Vec3 moved = p - now;
    body.x += moved;
    body.x_prev += moved;
  }
}

}  // namespace reeve::direct
