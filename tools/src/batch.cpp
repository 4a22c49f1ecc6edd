#include "batch.h"

#include <algorithm>
#include <stdexcept>

#include "run_scene.h"

namespace reeve {

std::vector<BatchOutcome> stepBatch(const std::vector<BatchItem>& items, int frames, ThreadPool& pool) {
  if (frames < 0) throw std::invalid_argument("batch: expected frames >= 0, got " + std::to_string(frames));
  std::vector<const Scene*> scenes;
  for (const BatchItem& item : items) {
    if (!item.scene) throw std::invalid_argument("batch: a scene is missing");
    scenes.push_back(item.scene);
  }
  std::sort(scenes.begin(), scenes.end());
  if (std::adjacent_find(scenes.begin(), scenes.end()) != scenes.end())
    throw std::invalid_argument("batch: a scene is listed twice (each is stepped by one thread)");
  std::vector<BatchOutcome> outcomes(items.size());
  pool.run(static_cast<int>(items.size()), [&](int i) {
    Scene& scene = *items[i].scene;
    BatchOutcome& out = outcomes[i];
    const double dt = 1.0 / scene.frame_rate_hz;
    for (int f = 0; f < frames; ++f) {
      scene.world->step(dt);
      if ((out.stopped = stopReason(scene))) return;
      if (scene.world->stepInterrupted()) return;
      ++out.frames_done;
      if (items[i].energy)
        if (auto created = items[i].energy->check(scene)) out.energy_created.push_back(*created);
    }
  });
  return outcomes;
}

}  // namespace reeve
