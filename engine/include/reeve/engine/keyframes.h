// Schedules of keyframes (drive targets, kinematic bodies' motions):
// values linear in time between keyframes, held before the first and after
// the last.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace reeve {

/// Whether `keys`' times are finite and strictly increasing.
template <class Key>
bool timesIncrease(const std::vector<Key>& keys) {
  for (std::size_t k = 0; k < keys.size(); ++k)
    if (!std::isfinite(keys[k].time) || (k > 0 && !(keys[k].time > keys[k - 1].time))) return false;
  return true;
}

/// Where time `t` (s) falls among `keys` (non-empty, each with a `time`,
/// strictly increasing): {i, s} with the value key[i] + s (key[i + 1] -
/// key[i]); s = 0 before the first keyframe and from the last on.
template <class Key>
std::pair<std::size_t, double> keyframeAt(const std::vector<Key>& keys, double t) {
  const auto after =
      std::upper_bound(keys.begin(), keys.end(), t, [](double time, const Key& k) { return time < k.time; });
  if (after == keys.begin()) return {0, 0.0};
  const auto i = static_cast<std::size_t>(after - keys.begin()) - 1;
  if (after == keys.end()) return {i, 0.0};
  return {i, (t - keys[i].time) / (after->time - keys[i].time)};
}

}  // namespace reeve
