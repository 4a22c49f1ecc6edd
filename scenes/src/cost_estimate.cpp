// What stepping a scene costs, predicted from its size and settings
// (warnings.h, predictedSecondsPerSimulatedSecond).
#include "reeve/scene/warnings.h"

#include <cstddef>
#include <vector>

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
// The direct solver's matrix couples every two rows on one body: k rows
// on a body fill k^2 entries and factor like a dense k x k block (k^3 / 3
// multiply-adds). Negligible along a chain (k of 2 to 6); a body with more
// than kHubRows (the direct solver's, direct/direct_solver.cpp) is a hub instead,
// whose k rows couple to its 6 freedoms: 6 k entries, 36 k multiply-adds
// (before hubs, 7,000 rows on two bodies took 4 GB and over 10 s a
// substep, a fuzzer's find; issue 29). A body with more than three cables
// of its own is a hub too, which only makes it cheaper than this says.
constexpr double kDirectPairIteration_s = 20e-9;
constexpr double kDirectFlop_s = 1e-9;
constexpr double kHubRows = 24.0;

// The direct solver's work per iteration on the k rows of one body.
double coupledCost(double k) {
  if (k > kHubRows) return kDirectPairIteration_s * 6.0 * k + kDirectFlop_s * 36.0 * k;
  return kDirectPairIteration_s * k * k + kDirectFlop_s * k * k * k / 3.0;
}

// Rows of the direct solver per dynamic body: each joint's rows and each
// cable joint's one row count on both of its bodies.
std::vector<double> rowsPerBody(const Scene& scene) {
  const World& world = *scene.world;
  std::vector<double> rows(static_cast<std::size_t>(world.bodyCount()), 0.0);
  const auto add = [&](BodyId a, BodyId b, double count) {
    for (const BodyId id : {a, b})
      if (id != kWorldBody && world.bodyMass(id) > 0.0) rows[static_cast<std::size_t>(id)] += count;
  };
  for (const HingeJoint& j : world.hinges()) add(j.a, j.b, 5.0);
  for (const PrismaticJoint& j : world.prismatics()) add(j.a, j.b, 5.0);
  for (const SphericalJoint& j : world.sphericals()) add(j.a, j.b, 3.0);
  for (const FixedJoint& j : world.fixedJoints()) add(j.a, j.b, 6.0);
  for (const Cable& cable : scene.cables->cables())
    for (std::size_t j = 0; j < cable.joints.size(); ++j)
      add(cable.links[j].body, cable.links[static_cast<std::size_t>(cable.joints[j].to)].body, 1.0);
  return rows;
}

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
  const bool direct = settings.solver == SolverKind::Direct;
  double coupled = 0.0;  // the direct solver's work on rows that share a body
  if (direct)
    for (const double k : rowsPerBody(scene)) coupled += coupledCost(k);
  const double row_iteration = direct ? kDirectRowIteration_s : kGaussSeidelRowIteration_s;
  const double substep = kBodySubstep_s * world.bodyCount() + kCableJointSubstep_s * cable_joints +
                         static_cast<double>(settings.iterations) *
                             (row_iteration * rows + coupled + kContactBodyIteration_s * colliding);
  return scene.frame_rate_hz * static_cast<double>(settings.substeps) * substep;
}

}  // namespace reeve
