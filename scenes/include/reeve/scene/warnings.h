// Warnings for scenes that load but will likely not run as their author
// meant. `reeve validate` and `reeve run` print them; they never change an
// exit status.
#pragma once

#include <string>
#include <vector>

#include "reeve/scene/scene.h"

namespace reeve {

/// Something a scene that loads may not mean: `json_path` (RFC 6901) and
/// what is odd there.
struct SceneWarning {
  std::string json_path;
  std::string message;
};

/// A span may start past its rest length (a pretensioned cable), but not by
/// more than this fraction of it, and at least kStartStretchWarningMin_m.
inline constexpr double kStartStretchWarning = 0.1;
inline constexpr double kStartStretchWarningMin_m = 0.01;

/// Warnings for a loaded, not yet stepped scene: cable spans that start
/// more than kStartStretchWarning of their rest length (and 1 cm) longer
/// than it. The first solve pulls such a span in at once, and a direct
/// solve that must turn wheels radians to do it can diverge
/// (CableSystem::firstBreach). The fuzzer's first finding was one.
std::vector<SceneWarning> sceneWarnings(const Scene& scene);

}  // namespace reeve
