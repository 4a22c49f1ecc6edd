// What a capped angle or position drive must stop: the bodies its joint
// turns or slides, joined to either side by other joints, as one rigid
// body, and the loads hung from them by pulling cables (prepareCoordinate
// brakes in time for max_effort over it).
#include <algorithm>
#include <cmath>
#include <vector>

#include "island.h"
#include "joint_rows.h"
#include "reeve/engine/world.h"

namespace reeve {

void World::buildJointGraph() {
  joint_graph_.assign(bodies_.size(), {});
  int edge = 0;
  const auto join = [&](BodyId a, BodyId b) {
    if (a != kWorldBody && b != kWorldBody) {
      joint_graph_[a].push_back({b, edge});
      joint_graph_[b].push_back({a, edge});
    }
    ++edge;
  };
  for (const HingeJoint& j : hinges_) join(j.a, j.b);
  for (const PrismaticJoint& j : prismatics_) join(j.a, j.b);
  for (const SphericalJoint& j : sphericals_) join(j.a, j.b);
  for (const FixedJoint& j : fixeds_) join(j.a, j.b);
}

bool World::driveAssembly(BodyId start, BodyId other, int skip_edge) const {
  // Static and kinematic bodies are ground: the assembly stops at them.
  // Scratch kept between calls: no allocation per substep once warm, and
  // only the last assembly's marks cleared, so that a drive costs its own
  // bodies, not the world's. (Clearing every body's, and reading every
  // cable below, 1024 braked Atwood machines in one scene stepped in 478
  // ms a frame; undriven, 21.)
  const auto grounded = [&](BodyId id) { return id == kWorldBody || mass_[id] == 0.0; };
  if (assembly_member_.size() != bodies_.size()) assembly_member_.assign(bodies_.size(), 0);
  for (const BodyId id : assembly_) assembly_member_[id] = 0;
  assembly_.clear();
  if (grounded(start)) return true;
  assembly_member_[start] = 1;
  assembly_.push_back(start);
  for (std::size_t i = 0; i < assembly_.size(); ++i) {
    for (const auto& [next, edge] : joint_graph_[assembly_[i]]) {
      if (edge == skip_edge || assembly_member_[next] || grounded(next)) continue;
      if (next == other) return false;  // a closed loop: the two sides do not turn apart
      assembly_member_[next] = 1;
      assembly_.push_back(next);
    }
  }
  return true;
}

double World::assemblyInverseInertia(const Island& island, BodyId start, BodyId other, int skip_edge,
                                     const Vec3& anchor, const Vec3& u) const {
  if (!driveAssembly(start, other, skip_edge)) return -1.0;
  const auto lever2 = [&](const Vec3& p) {  // squared distance of p from the axis
    const Vec3 r = p - anchor;
    return r.squaredNorm() - r.dot(u) * r.dot(u);
  };
  double inertia = 0.0;
  for (const BodyId id : assembly_) {
    const BodyState& b = body(id);
    const Vec3 u_local = b.q.conjugate() * u;
    inertia += u_local.dot(b.inertia * u_local) + mass_[id] * lever2(b.x);
  }
  // A body hung from the assembly by a pulling cable (the last substep's
  // lambda) swings behind it, but over a slew it follows: its mass counts
  // at the lever of the point it hangs from (a crane's load at its boom
  // tip, a winch's load at its drum's radius), the largest if several.
  // A cable from the assembly to a load joins them: the island's own
  // cables are all there are to look at.
  if (hung_lever2_.size() != bodies_.size()) hung_lever2_.assign(bodies_.size(), 0.0);
  hung_.clear();
  const auto hang = [&](const BodyId from, const Vec3& at, const BodyId load) {
    if (from == kWorldBody || load == kWorldBody || !assembly_member_[from] || assembly_member_[load] ||
        mass_[load] == 0.0)
      return;
    hung_lever2_[load] = std::max(hung_lever2_[load], lever2(at));
    hung_.push_back(load);
  };
  for (const int i : island.distances) {
    const DistanceConstraint& c = distances_[i];
    if (!c.enabled || !(c.lambda < 0.0)) continue;
    hang(c.a, body(c.a).toWorld(c.local_a), c.b);
    hang(c.b, body(c.b).toWorld(c.local_b), c.a);
  }
  for (const int i : island.paths) {
    const PathConstraint& p = paths_[i];
    if (!p.enabled || !(p.lambda < 0.0)) continue;
    for (std::size_t i = 0; i + 1 < p.points.size(); ++i) {
      if (segmentScale(p, i) == 0.0) continue;  // no cable between two joined cables
      const PathPoint &s = p.points[i], &e = p.points[i + 1];
      hang(s.body, body(s.body).toWorld(s.local), e.body);
      hang(e.body, body(e.body).toWorld(e.local), s.body);
    }
  }
  // In body order, as a sum over every body was (the others add 0).
  std::sort(hung_.begin(), hung_.end());
  hung_.erase(std::unique(hung_.begin(), hung_.end()), hung_.end());
  for (const BodyId id : hung_) {
    inertia += mass_[id] * hung_lever2_[id];
    hung_lever2_[id] = 0.0;
  }
  return inertia > 0.0 ? 1.0 / inertia : 0.0;
}

double World::assemblyInverseMass(BodyId start, BodyId other, int skip_edge) const {
  if (!driveAssembly(start, other, skip_edge)) return -1.0;
  double mass = 0.0;
  for (const BodyId id : assembly_) mass += mass_[id];
  return mass > 0.0 ? 1.0 / mass : 0.0;
}

double World::brakingInverseInertia(const Island& island, int hinge) const {
  const HingeJoint& j = hinges_[hinge];
  const BodyState &a = body(j.a), &b = body(j.b);
  const Vec3 u = a.q * j.frame.axis_a;
  const bool braked = j.drive.mode == HingeDrive::Mode::Angle && j.drive.stiffness == 0.0 &&
                      j.drive.max_torque > 0.0 && std::isfinite(j.drive.max_torque);
  if (braked) {
    const double w_a = assemblyInverseInertia(island, j.a, j.b, hinge, a.toWorld(j.frame.anchor_a), u);
    const double w_b = assemblyInverseInertia(island, j.b, j.a, hinge, b.toWorld(j.frame.anchor_b), u);
    if (w_a >= 0.0 && w_b >= 0.0) return w_a + w_b;
  }
  // Unused, or a closed loop: the two bodies alone (exact for one body on
  // a world hinge).
  return joint_rows::inverseInertiaAbout(a, j.frame.anchor_a, u) +
         joint_rows::inverseInertiaAbout(b, j.frame.anchor_b, u);
}

double World::brakingInverseMass(int prismatic) const {
  const PrismaticJoint& j = prismatics_[prismatic];
  const BodyState &a = body(j.a), &b = body(j.b);
  const int edge = static_cast<int>(hinges_.size()) + prismatic;
  const bool braked = j.drive.mode == PrismaticDrive::Mode::Position && j.drive.stiffness == 0.0 &&
                      j.drive.max_force > 0.0 && std::isfinite(j.drive.max_force);
  if (braked) {
    const double w_a = assemblyInverseMass(j.a, j.b, edge), w_b = assemblyInverseMass(j.b, j.a, edge);
    if (w_a >= 0.0 && w_b >= 0.0) return w_a + w_b;
  }
  return a.inv_mass + b.inv_mass;
}

}  // namespace reeve
