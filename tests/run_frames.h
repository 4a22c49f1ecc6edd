// Stepping a World frame by frame in tests.
#pragma once

#include <cmath>

#include "reeve/engine/world.h"

namespace reeve::test {

/// Runs `world` for `seconds` in frames of `dt` s, calling `each(t)`
/// (t the world's time, s) after each.
template <class Each>
void run(World& world, double seconds, double dt, Each each) {
  const int frames = static_cast<int>(std::lround(seconds / dt));
  for (int f = 0; f < frames; ++f) {
    world.step(dt);
    each(world.time());
  }
}

}  // namespace reeve::test
