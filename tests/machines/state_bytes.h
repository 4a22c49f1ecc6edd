// The state a step leaves behind as bytes, to compare runs bit for bit
// (islands on any number of threads, whole steps against substep by
// substep).
#pragma once

#include <vector>

#include "reeve/scene/scene.h"

namespace reeve::test {

// Everything a step leaves behind: poses, velocities, tensions, hinge
// wrenches, the iterations run, the whole energy ledger (the flows are
// summed by island and by cable: energy(), frictionLoss(), winchWork()).
inline std::vector<unsigned char> stateBytes(const Scene& scene) {
  std::vector<unsigned char> bytes;
  const auto put = [&](const auto& value) {
    const auto* p = reinterpret_cast<const unsigned char*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof value);
  };
  const World& world = *scene.world;
  for (BodyId id = 0; id < world.bodyCount(); ++id) {
    const BodyState& b = world.body(id);
    put(b.x), put(b.q.coeffs()), put(b.v), put(b.omega);
  }
  for (const auto& cable : scene.cables->cables())
    for (const auto& joint : cable.joints) put(world.pathTension(joint.path));
  for (int h = 0; h < static_cast<int>(world.hinges().size()); ++h) put(world.hingeWrench(h).force);
  put(world.lastStepIterations());
  const WorldEnergy e = world.energy();
  for (const double v : {e.kinetic, e.gravity, e.elastic, e.drive_work, e.load_work, e.kinematic_work, e.damping_loss,
                         e.contact_loss, e.cable_damping_loss})
    put(v);
  put(scene.cables->frictionLoss());
  put(scene.cables->winchWork());
  put(scene.cables->storedElasticEnergy());
  return bytes;
}

// Cable events (CableSystem::takeEvents) in the order they are listed: by
// time, then cable.
inline std::vector<unsigned char> eventBytes(const std::vector<CableEvent>& events) {
  std::vector<unsigned char> bytes;
  for (const CableEvent& e : events) {
    const double fields[] = {static_cast<double>(e.kind), e.time_s, double(e.cable), double(e.link), e.tension};
    const auto* p = reinterpret_cast<const unsigned char*>(fields);
    bytes.insert(bytes.end(), p, p + sizeof fields);
  }
  return bytes;
}

}  // namespace reeve::test
