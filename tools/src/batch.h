// Scenes stepped side by side on a thread pool (issue 30: reeve.Batch and
// `reeve bench batch`): a controller search, a learning loop or a design
// sweep steps many copies of a machine at once. Scenes share nothing, so
// each one's state after a step is the same bit for bit whatever the
// number of threads, and the same as stepping it alone.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "reeve/engine/thread_pool.h"
#include "reeve/scene/energy.h"
#include "reeve/scene/scene.h"

namespace reeve {

/// A scene of a batch and the energy watch that checks it frame by frame.
/// No scene may appear twice in one batch (two threads would step it).
struct BatchItem {
  Scene* scene = nullptr;
  EnergyWatch* energy = nullptr;  ///< may be null: not checked
};

/// How one scene's step went.
struct BatchOutcome {
  int frames_done = 0;
  /// Why it stopped early (stopReason: a non-finite state, a broken cable
  /// bookkeeping); it is not stepped on after that frame. Fewer frames
  /// done without a reason: a signal ended a substep
  /// (World::setInterruptFlag), after the whole frames counted.
  std::optional<std::string> stopped;
  /// The frames whose energy ledger showed energy created (EnergyWatch).
  std::vector<EnergyCreated> energy_created;
};

/// Steps every item's scene by `frames` frames of 1 / frame_rate_hz, one
/// scene per thread of `pool` at a time, and returns one outcome per item,
/// in order. A scene that stops is left where it stopped; the others go
/// on. Cable events stay in each scene's CableSystem for the caller.
/// std::invalid_argument for frames < 0, a null scene or one listed twice.
std::vector<BatchOutcome> stepBatch(const std::vector<BatchItem>& items, int frames, ThreadPool& pool);

}  // namespace reeve
