// Friction pools and support groups (contact.h, FrictionPool,
// SupportGroup): which of a substep's manifolds share their static
// friction.
#include <algorithm>
#include <cmath>

#include "reeve/engine/world.h"

namespace reeve {

namespace {

/// Whether bodies p and q, which constraints do not move, move as one
/// rigid body this substep: two static ones, or kinematic ones whose
/// velocities are one rigid motion's (q's velocity is p's carried to q).
bool moveAsOne(const BodyState& p, const BodyState& q) {
  const double scale = p.v.norm() + q.v.norm() + p.omega.norm() * (1.0 + (q.x - p.x).norm());
  const double alike = 1e-12 + 1e-9 * scale;  // m/s, rad/s: rounding of one schedule's velocities
  return (q.omega - p.omega).norm() <= alike && ((q.v - p.v) - p.omega.cross(q.x - p.x)).norm() <= alike;
}

}  // namespace

void World::poolFriction() {
  friction_pools_.clear();
  pool_order_.clear();
  pool_hull_.clear();
  support_groups_.clear();
  group_members_.clear();
  // Room for every manifold up front: a step allocates nothing once the
  // first frame ran, beyond a new high-water mark.
  if (pool_order_.capacity() < manifolds_.capacity()) pool_order_.reserve(manifolds_.capacity());
  if (friction_pools_.capacity() < manifolds_.capacity() / 2) friction_pools_.reserve(manifolds_.capacity() / 2);
  if (pool_points_.capacity() < contacts_.capacity()) pool_points_.reserve(contacts_.capacity());
  if (pool_hull_.capacity() < contacts_.capacity()) pool_hull_.reserve(contacts_.capacity());
  if (group_members_.capacity() < manifolds_.capacity()) group_members_.reserve(manifolds_.capacity());
  if (support_groups_.capacity() < manifolds_.capacity() / 2) support_groups_.reserve(manifolds_.capacity() / 2);
  // A manifold between a moving body and one that constraints do not move.
  const auto moving = [&](int i) { return body(manifolds_[i].a).moves() ? manifolds_[i].a : manifolds_[i].b; };
  const auto support = [&](int i) -> const BodyState& {
    return body(body(manifolds_[i].a).moves() ? manifolds_[i].b : manifolds_[i].a);
  };
  for (int i = 0; i < static_cast<int>(manifolds_.size()); ++i)
    if (body(manifolds_[i].a).moves() != body(manifolds_[i].b).moves()) pool_order_.push_back(i);
  // Normal into the moving body (a contact's runs from a into b).
  const auto normal = [&](int i) {
    const Vec3& n = contacts_[manifolds_[i].first].normal;
    return body(manifolds_[i].b).moves() ? n : Vec3(-n);
  };
  std::sort(pool_order_.begin(), pool_order_.end(),
            [&](int i, int j) { return std::pair(moving(i), i) < std::pair(moving(j), j); });
  const double alike = std::cos(kPoolAngle);
  for (std::size_t first = 0; first < pool_order_.size();) {
    std::size_t end = first + 1;
    while (end < pool_order_.size() && moving(pool_order_[end]) == moving(pool_order_[first])) ++end;
    // Each manifold not yet pooled gathers the later ones like it: one
    // pass over a body's supports when their normals agree (a plank on
    // posts, a box on a bed of balls).
    for (std::size_t k = first; k < end; ++k) {
      const int lead = pool_order_[k];
      if (manifolds_[lead].pool >= 0) continue;
      const int pool = static_cast<int>(friction_pools_.size());
      for (std::size_t j = k + 1; j < end; ++j) {
        const int other = pool_order_[j];
        if (manifolds_[other].pool >= 0 || normal(lead).dot(normal(other)) < alike ||
            !moveAsOne(support(lead), support(other)))
          continue;
        manifolds_[other].pool = manifolds_[lead].pool = pool;
      }
      if (manifolds_[lead].pool != pool) continue;
      // Its compound patch, from all its points on the moving body.
      const BodyState& body_moving = body(moving(lead));
      pool_points_.clear();
      for (std::size_t j = k; j < end; ++j) {
        const ContactManifold& m = manifolds_[pool_order_[j]];
        if (m.pool != pool) continue;
        for (int c = m.first; c < m.first + m.count; ++c)
          pool_points_.push_back(m.b == moving(lead) ? contacts_[c].local_b : contacts_[c].local_a);
      }
      describePool(friction_pools_.emplace_back(), pool_points_, body_moving.q.conjugate() * normal(lead),
                   pool_hull_);
    }
    // The group of the body's supports that move as one, where they are
    // not all one pool: each manifold not yet gathered gathers the later
    // ones (once each, so one pass over a body on one kind of support).
    constexpr int kGathered = -2;  // in no group, but gathered: led by none
    for (std::size_t k = first; k < end; ++k) {
      const int lead = pool_order_[k];
      if (manifolds_[lead].group != -1) continue;
      const int group = static_cast<int>(support_groups_.size()), start = static_cast<int>(group_members_.size());
      bool mixed = false;  // members of more than one pool, or of none
      group_members_.push_back(lead);
      for (std::size_t j = k + 1; j < end; ++j) {
        const int other = pool_order_[j];
        if (manifolds_[other].group != -1 || !moveAsOne(support(lead), support(other))) continue;
        mixed |= manifolds_[other].pool < 0 || manifolds_[other].pool != manifolds_[lead].pool;
        group_members_.push_back(other);
      }
      for (int g = start; g < static_cast<int>(group_members_.size()); ++g)
        manifolds_[group_members_[g]].group = mixed ? group : kGathered;
      if (mixed) support_groups_.push_back({nullptr, nullptr, static_cast<int>(group_members_.size()) - start});
      else group_members_.resize(static_cast<std::size_t>(start));
    }
    for (std::size_t k = first; k < end; ++k)
      if (manifolds_[pool_order_[k]].group == kGathered) manifolds_[pool_order_[k]].group = -1;
    first = end;
  }
  // A pool that held its body in the last substep (a member stuck: the
  // pool's holds are all or nothing for the body's whole slip, so one
  // member's hold held it) keeps each member's pressure then as a floor
  // under its bound: a curved point's anchor is never kept, and with it
  // its pressure, where a patch's is (anchorFriction).
  for (const int i : pool_order_)
    if (manifolds_[i].pool >= 0 && manifolds_[i].last_stuck) friction_pools_[manifolds_[i].pool].held_before = true;
  for (const int i : pool_order_)
    if (ContactManifold& m = manifolds_[i]; m.pool >= 0 && friction_pools_[m.pool].held_before)
      m.kept_pressure = m.last_pressure;
  // The groups' members, and the hulls' storage, grow no more this
  // substep.
  const int* member = group_members_.data();
  for (SupportGroup& g : support_groups_) {
    g.manifolds = manifolds_.data();
    g.members = member;
    member += g.count;
  }
  const Vec3* hull = pool_hull_.data();
  for (FrictionPool& p : friction_pools_) {
    p.hull = hull;
    hull += p.hull_count;
  }
}

}  // namespace reeve
