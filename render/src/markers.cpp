#include "reeve/render/markers.h"

namespace reeve {

MarkerKind markerKind(const Link& link) {
  switch (link.type) {
    case LinkType::Rolling: return MarkerKind::Rolling;
    case LinkType::Attachment: return MarkerKind::Attachment;
    case LinkType::Pinhole: return MarkerKind::Pinhole;
    case LinkType::Hybrid:
      return link.attached ? MarkerKind::HybridAttached : MarkerKind::HybridRolling;
  }
  return MarkerKind::Attachment;
}

std::vector<Marker> linkMarkers(const CableSystem& cables) {
  std::vector<Marker> markers;
  for (int c = 0; c < static_cast<int>(cables.cables().size()); ++c) {
    const Cable& cable = cables.cables()[c];
    for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
      if (!cables.jointEnabled(c, j)) continue;
      const Link& from = cable.links[j];
      const Link& to = cable.links[cable.joints[j].to];
      // A pinhole's two spans meet at the hole: one marker there.
      if (from.type != LinkType::Pinhole) markers.push_back({cables.startPoint(c, j), markerKind(from)});
      markers.push_back({cables.endPoint(c, j), markerKind(to)});
    }
  }
  return markers;
}

}  // namespace reeve
