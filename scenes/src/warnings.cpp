// What loads but will likely not run as its author meant (warnings.h).
#include <algorithm>
#include <cstdio>
#include <string>

#include "reeve/scene/warnings.h"

namespace reeve {

std::vector<SceneWarning> sceneWarnings(const Scene& scene) {
  std::vector<SceneWarning> warnings;
  if (!scene.not_imported.empty()) {
    std::string lines = std::to_string(scene.not_imported.size()) + " part" +
                        (scene.not_imported.size() == 1 ? " of the model is" : "s of the model are") + " not imported:";
    for (const std::string& line : scene.not_imported) lines += "\n  " + line;
    warnings.push_back({"(MJCF import)", lines});
  }
  const CableSystem& cables = *scene.cables;
  for (int c = 0; c < static_cast<int>(cables.cables().size()); ++c) {
    const Cable& cable = cables.cables()[c];
    for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
      if (!cables.jointEnabled(c, j)) continue;
      const double rest = cables.restLength(c, j), stretch = cables.length(c, j) - rest;
      if (!(stretch > std::max(kStartStretchWarning * rest, kStartStretchWarningMin_m))) continue;
      char text[256];
      std::snprintf(text, sizeof text,
                    "cable '%s' span %d starts %.3g m longer than its rest length of %.3g m: the first solve "
                    "pulls it in at once, a jerk that puts in energy nothing paid for",
                    cable.name.c_str(), j, stretch, rest);
      warnings.push_back({"/cables/" + std::to_string(c) + "/rest_length_m/" + std::to_string(j), text});
    }
  }
  for (int c = 0; c < static_cast<int>(cables.cables().size()); ++c) {
    const Cable& cable = cables.cables()[c];
    if (cable.given_rest_lengths.empty()) continue;
    // Spans joined through a frictionless pinhole or wrap share one rest
    // length: only its sum holds, in proportion to their lengths.
    std::string given, read;
    double sum = 0.0;
    for (std::size_t j = 0; j < cable.joints.size(); ++j) {
      char a[32], b[32];
      std::snprintf(a, sizeof a, "%s%.6g", j ? ", " : "", cable.given_rest_lengths[j]);
      std::snprintf(b, sizeof b, "%s%.6g", j ? ", " : "", cable.joints[j].rest_length);
      given += a;
      read += b;
      sum += cable.joints[j].rest_length;
    }
    char text[512];
    std::snprintf(text, sizeof text,
                  "cable '%s' slides through its frictionless pinholes or wraps, so the spans joined there share "
                  "one rest length in proportion to their lengths: [%s] is read as [%s] (the sum, %.6g m, kept); "
                  "give \"mu\" to hold a split",
                  cable.name.c_str(), given.c_str(), read.c_str(), sum);
    warnings.push_back({"/cables/" + std::to_string(c) + "/rest_length_m", text});
  }
  const double cost = predictedSecondsPerSimulatedSecond(scene);
  if (cost > kSlowSceneWarning_s) {
    const SolverSettings& settings = scene.world->settings();
    char text[384];
    std::snprintf(text, sizeof text,
                  "%d substeps x %d iterations a frame at %g Hz (%s) predict about %.2g s of computing per simulated "
                  "second (%.2g h for the scene's %g s): lower substeps or iterations, or expect to wait",
                  settings.substeps, settings.iterations, scene.frame_rate_hz, solverMethodName(settings.solver),
                  cost, cost * scene.duration_s / 3600.0, scene.duration_s);
    warnings.push_back({"/solver", text});
  }
  return warnings;
}

}  // namespace reeve
