// Where link markers go and what they show (paper Fig. 7, 10: rolling red,
// attachment green, pinhole blue, hybrid red-green).
#pragma once

#include <vector>

#include "reeve/cable/cable.h"

namespace reeve {

enum class MarkerKind {
  Rolling,         ///< red ball at each tangent point
  Attachment,      ///< green ball at the tie point
  Pinhole,         ///< blue ball at the hole
  HybridRolling,   ///< a hybrid that still has cable: red ball, green ring
  HybridAttached,  ///< a hybrid that ran out, tied: green ball, red ring
};

struct Marker {
  Vec3 at;  // m, world
  MarkerKind kind;
};

/// The kind of marker `link` shows now.
MarkerKind markerKind(const Link& link);

/// Markers of every cable: at both ends of every enabled joint, in the kind
/// of the link there. Inactive links (no enabled joint touches them) get
/// none.
std::vector<Marker> linkMarkers(const CableSystem& cables);

}  // namespace reeve
