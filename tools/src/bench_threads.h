// The thread counts a thread bench runs (reeve bench batch, islands).
#pragma once

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "reeve/engine/thread_pool.h"

namespace reeve {

/// `asked` (empty: 1, 2 and the cores), increasing, each once, with 1
/// first as the speed-up's baseline. Throws std::invalid_argument for a
/// count below 1.
inline std::vector<int> threadCounts(std::vector<int> asked) {
  if (asked.empty()) asked = {1, 2, ThreadPool::cores()};
  std::sort(asked.begin(), asked.end());
  asked.erase(std::unique(asked.begin(), asked.end()), asked.end());
  if (asked.front() < 1) throw std::invalid_argument("--threads: expected counts of at least 1");
  if (asked.front() != 1) asked.insert(asked.begin(), 1);
  return asked;
}

}  // namespace reeve
