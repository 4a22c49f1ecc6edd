// What loads but will likely not run as its author meant (warnings.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "reeve/scene/warnings.h"

namespace reeve {
namespace {

// 1 / (kg m^2): a body's inverse inertia for turning about the hinge's
// axle (body-local unit `axis` through the body-local `anchor`), by the
// parallel axis theorem; 0 for a body that does not move.
double inverseInertiaAboutAxle(const World& world, BodyId id, const Vec3& axis, const Vec3& anchor) {
  if (id == kWorldBody || !world.body(id).moves()) return 0.0;
  const BodyState& b = world.body(id);
  const double about_centre = axis.dot(b.inertia * axis), off = anchor.cross(axis).squaredNorm();
  return 1.0 / (about_centre + world.bodyMass(id) * off);
}

// The largest omega h of the scene's trapezoidal springs at its substep,
// omega^2 = k (1 / I_a + 1 / I_b) for a hinge's (each body about the
// axle), k (1 / m_a + 1 / m_b) for a slider's; `worst` names its joint.
double stiffestTrapezoidalSpring(const Scene& scene, std::string& worst, int& count) {
  const World& world = *scene.world;
  const double h = 1.0 / (scene.frame_rate_hz * world.settings().substeps);
  const auto name = [&](BodyId id) { return id == kWorldBody ? std::string("the world") : "'" + world.bodyDef(id).name + "'"; };
  double most = 0.0;
  count = 0;
  const auto judge = [&](double omega_h, const char* kind, BodyId a, BodyId b, double k, const char* unit) {
    ++count;
    if (!(omega_h > most)) return;
    most = omega_h;
    char text[160];
    std::snprintf(text, sizeof text, " (the %s of %s and %s, %.3g %s)", kind, name(a).c_str(), name(b).c_str(), k, unit);
    worst = text;
  };
  for (const HingeJoint& j : world.hinges()) {
    if (!j.drive.isTrapezoidalSpring()) continue;
    const double w = inverseInertiaAboutAxle(world, j.a, j.frame.axis_a, j.frame.anchor_a) +
                     inverseInertiaAboutAxle(world, j.b, j.frame.axis_b, j.frame.anchor_b);
    judge(std::sqrt(j.drive.stiffness * w) * h, "hinge", j.a, j.b, j.drive.stiffness, "N m/rad");
  }
  for (const PrismaticJoint& j : world.prismatics()) {
    if (!j.drive.isTrapezoidalSpring()) continue;
    const auto inverse_mass = [&](BodyId id) { return id == kWorldBody ? 0.0 : world.body(id).inv_mass; };
    judge(std::sqrt(j.drive.stiffness * (inverse_mass(j.a) + inverse_mass(j.b))) * h, "slider", j.a, j.b,
          j.drive.stiffness, "N/m");
  }
  return most;
}

}  // namespace

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
  // Gauss-Seidel turns a trapezoidal spring's bodies by first-order
  // corrections, one joint at a time, and needs omega h below about 1
  // (hinge_joint.h): the bow's limbs at the paper's 10 x 10, omega h up to
  // 12, threw a cam 2e7 m in 0.26 s.
  const SolverSettings& settings = scene.world->settings();
  int springs = 0;
  std::string worst;
  const double omega_h = stiffestTrapezoidalSpring(scene, worst, springs);
  if (settings.solver == SolverKind::GaussSeidel && omega_h > kTrapezoidalOmegaH) {
    const int substeps = static_cast<int>(std::ceil(settings.substeps * omega_h / kTrapezoidalOmegaH));
    char text[512];
    std::snprintf(text, sizeof text,
                  "%d trapezoidal spring%s at %d substeps a frame: omega h up to %.2g%s, where Gauss-Seidel needs "
                  "it below %g or may blow up; use the direct solver (\"method\": \"direct\"), %d substeps or "
                  "more, or \"integration\": \"implicit\"",
                  springs, springs == 1 ? "" : "s", settings.substeps, omega_h, worst.c_str(), kTrapezoidalOmegaH,
                  substeps);
    warnings.push_back({"/solver", text});
  }
  return warnings;
}

}  // namespace reeve
