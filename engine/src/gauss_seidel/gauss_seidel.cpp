// Gauss-Seidel, the paper's method (SCA 2018 sec. 3; SCA 2020 Alg. 2):
// each iteration visits the constraints one after another, each moving
// its bodies at once, joints first (each as one block, joint_rows.h),
// then distance constraints and cable paths, then contacts. A correction
// travels one constraint per visit: right while the bodies in a chain
// are about as heavy as each other (README, "Substeps and iterations").
#include "reeve/engine/world.h"

namespace reeve {

void World::sweepGaussSeidel(double h) {
  const double inv_h2 = 1.0 / (h * h);
  const BodyTable table{bodies_.data(), &world_frame_};
  for (int it = 0; it < settings_.iterations; ++it) {
    ++last_iterations_;
    // Joints first (all types), then distances and paths (cables).
    for (HingeJoint& j : hinges_) solveHingeJoint(j, body(j.a), body(j.b), h);
    for (PrismaticJoint& j : prismatics_) solvePrismaticJoint(j, body(j.a), body(j.b), h);
    for (SphericalJoint& j : sphericals_) solveSphericalJoint(j, body(j.a), body(j.b), h);
    for (FixedJoint& j : fixeds_) solveFixedJoint(j, body(j.a), body(j.b), h);
    for (DistanceConstraint& c : distances_)
      solveDistanceConstraint(c, body(c.a), body(c.b), c.compliance * inv_h2, h);
    for (PathConstraint& p : paths_) solvePathConstraint(p, table, p.compliance * inv_h2, h);
    for (ContactManifold& m : manifolds_) {
      const Contact& c = contacts_[m.first];
      solveContactPositions(m, contacts_.data(), body(c.a), body(c.b));
    }
    if (it + 1 < settings_.iterations && interruptRequested()) {  // the substep ends here
      interrupted_ = true;
      break;
    }
  }
}

}  // namespace reeve
