// Gauss-Seidel, the paper's method (SCA 2018 sec. 3; SCA 2020 Alg. 2):
// each iteration visits the constraints one after another, each moving
// its bodies at once, joints first (each as one block, joint_rows.h),
// then distance constraints and cable paths, then contacts. A correction
// travels one constraint per visit: right while the bodies in a chain
// are about as heavy as each other (README, "Substeps and iterations").
#include "../island.h"
#include "reeve/engine/world.h"

namespace reeve {

void World::sweepGaussSeidel(Island& island, double h) {
  const double inv_h2 = 1.0 / (h * h);
  const BodyTable table{bodies_.data(), &world_frame_};
  for (int it = 0; it < settings_.iterations; ++it) {
    ++island.iterations;
    // Joints first (all types), then distances and paths (cables).
    for (const int i : island.hinges) {
      HingeJoint& j = hinges_[i];
      solveHingeJoint(j, body(j.a), body(j.b), h);
    }
    for (const int i : island.prismatics) {
      PrismaticJoint& j = prismatics_[i];
      solvePrismaticJoint(j, body(j.a), body(j.b), h);
    }
    for (const int i : island.sphericals) {
      SphericalJoint& j = sphericals_[i];
      solveSphericalJoint(j, body(j.a), body(j.b), h);
    }
    for (const int i : island.fixeds) {
      FixedJoint& j = fixeds_[i];
      solveFixedJoint(j, body(j.a), body(j.b), h);
    }
    for (const int i : island.distances) {
      DistanceConstraint& c = distances_[i];
      solveDistanceConstraint(c, body(c.a), body(c.b), c.compliance * inv_h2, h);
    }
    for (const int i : island.paths) solvePathConstraint(paths_[i], table, paths_[i].compliance * inv_h2, h);
    for (const int i : island.manifolds) {
      ContactManifold& m = manifolds_[i];
      const Contact& c = contacts_[m.first];
      solveContactPositions(m, contacts_.data(), body(c.a), body(c.b));
    }
    if (it + 1 < settings_.iterations && interruptRequested()) {  // the substep ends here
      island.interrupted = true;
      break;
    }
  }
}

}  // namespace reeve
