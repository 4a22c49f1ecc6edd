// Walking a cable's links: which link a span reaches, which span arrives.
#pragma once

#include "reeve/cable/cable.h"

namespace reeve {

/// Index of the next active link after link k (cyclic for closed cables).
int nextActive(const Cable& cable, int k);

/// Index of the active link whose span arrives at link k: the previous
/// active link (cyclic for closed cables). For the first link of an open
/// cable, which no span reaches, returns 0.
int previousActive(const Cable& cable, int k);

/// Whether link k ends an open cable.
inline bool isEnd(const Cable& cable, int k) {
  return !cable.closed && (k == 0 || k + 1 == static_cast<int>(cable.links.size()));
}

/// The most wound layers a link keeps (Link::layers): past this many the
/// two deepest are one.
constexpr std::size_t kMostLayers = 1024;
/// Wound layers an elastic cable's rolling link has room for when built,
/// so that winding allocates only when its layers pass their most so far
/// beyond this (the hand's knuckles pass 64 after about a second).
/// Reserving all kMostLayers (16 KiB a link) slowed the hand's direct
/// step by 25 % and Servin's, which has none, by 30 % in the same
/// `reeve bench table1` process, the same instructions: the heap's
/// layout, not measured further.
constexpr std::size_t kReservedLayers = 64;

/// Length (m) of `path` as the last solve left it: its points at the poses
/// before this substep's integration (x_prev, q_prev).
double solvedLength(const World& world, const PathConstraint& path);

/// The in-plane part (m) of a body-local anchor on a rolling link.
inline Vec2 planePoint(const Vec3& local) { return Vec2(local.x(), local.y()); }

}  // namespace reeve
