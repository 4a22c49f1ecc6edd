// `reeve bench peers` where MuJoCo was not found at configure time.
#include <cstdio>

#include "reeve/bench/bench.h"

namespace reeve::bench {

bool peersAvailable() { return false; }

int peers(const PeersOptions&) {
  std::fprintf(stderr,
               "reeve bench peers: not built: Debian's libmujoco-dev was not found when Reeve was configured "
               "(apt-get install libmujoco-dev, then re-run cmake)\n");
  return 1;
}

}  // namespace reeve::bench
