#include "links.h"

namespace reeve {

int nextActive(const Cable& cable, int k) {
  const int n = static_cast<int>(cable.links.size());
  for (int i = k + 1; i < k + n; ++i)
    if ((cable.closed || i < n) && cable.links[i % n].active) return i % n;
  return k;
}

int previousActive(const Cable& cable, int k) {
  const int n = static_cast<int>(cable.links.size());
  for (int i = k - 1; i > k - n; --i)
    if ((cable.closed || i >= 0) && cable.links[(i + n) % n].active) return (i + n) % n;
  return 0;
}

}  // namespace reeve
