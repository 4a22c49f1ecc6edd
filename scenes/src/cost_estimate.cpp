// What stepping a scene costs, predicted from its size and settings
// (warnings.h, predictedSecondsPerSimulatedSecond).
#include "reeve/scene/warnings.h"

namespace reeve {
namespace {

// Seconds per item, fitted to the shipped scenes on the development
// machine (DESIGN.md, "Cost estimate"): per substep, a body's integration
// and a cable joint's geometry (tangents, rest lengths); per iteration, a
// constraint row (a cable joint is one, a hinge five) in each solver, and
// a colliding body's contacts (swept by both solvers).
constexpr double kBodySubstep_s = 0.3e-6;
constexpr double kCableJointSubstep_s = 0.9e-6;
constexpr double kDirectRowIteration_s = 50e-9;
constexpr double kGaussSeidelRowIteration_s = 160e-9;
constexpr double kContactBodyIteration_s = 1.2e-6;

}  // namespace

double predictedSecondsPerSimulatedSecond(const Scene& scene) {
  const World& world = *scene.world;
  const SolverSettings& settings = world.settings();
  double cable_joints = 0.0;
  for (const Cable& cable : scene.cables->cables()) cable_joints += static_cast<double>(cable.joints.size());
  const double rows = cable_joints + 5.0 * static_cast<double>(world.hinges().size() + world.prismatics().size()) +
                      3.0 * static_cast<double>(world.sphericals().size()) +
                      6.0 * static_cast<double>(world.fixedJoints().size());
  const double colliding = world.hasContacts() ? static_cast<double>(world.bodyCount()) : 0.0;
  const double row_iteration =
      settings.solver == SolverKind::Direct ? kDirectRowIteration_s : kGaussSeidelRowIteration_s;
  const double substep = kBodySubstep_s * world.bodyCount() + kCableJointSubstep_s * cable_joints +
                         static_cast<double>(settings.iterations) *
                             (row_iteration * rows + kContactBodyIteration_s * colliding);
  return scene.frame_rate_hz * static_cast<double>(settings.substeps) * substep;
}

}  // namespace reeve
