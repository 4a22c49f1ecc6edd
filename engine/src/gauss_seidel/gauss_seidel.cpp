// Gauss-Seidel, the paper's method (SCA 2018 sec. 3; SCA 2020 Alg. 2):
// each iteration visits the constraints one after another, each moving
// its bodies at once, joints first (each as one block, joint_rows.h),
// then distance constraints and cable paths, then contacts. A correction
// travels one constraint per visit: right while the bodies in a chain
// are about as heavy as each other (README, "Substeps and iterations").
#include "../island.h"
#include "span_ends.h"
#include "reeve/engine/world.h"

namespace reeve {

void World::sweepGaussSeidel(Island& island, double h) {
  const double inv_h2 = 1.0 / (h * h);
  const BodyTable table{bodies_.data(), &world_frame_};
  // The island's joints of one type, each by its kernel.
  const auto visit = [&](const std::vector<int>& list, auto& joints, auto solve) {
    for (const int i : list) solve(joints[i], body(joints[i].a), body(joints[i].b), h);
  };
  prepareSpanEnds(island.paths, paths_, table, island.span_ends);
  // A rotor's free hinge has no row: its visits, one a joint and iteration
  // (Hilbert3: every hinge), would do nothing.
  island.swept_hinges.clear();
  for (const int i : island.hinges)
    if (!hingeSolvesNothing(hinges_[i], body(hinges_[i].a), body(hinges_[i].b))) island.swept_hinges.push_back(i);
  for (int it = 0; it < settings_.iterations; ++it) {
    ++island.iterations;
    // Joints first (all types), then distances and paths (cables).
    visit(island.swept_hinges, hinges_, solveHingeJoint);
    visit(island.prismatics, prismatics_, solvePrismaticJoint);
    visit(island.sphericals, sphericals_, solveSphericalJoint);
    visit(island.fixeds, fixeds_, solveFixedJoint);
    for (const int i : island.distances) {
      DistanceConstraint& c = distances_[i];
      solveDistanceConstraint(c, body(c.a), body(c.b), c.compliance * inv_h2, h);
    }
    for (std::size_t k = 0; k < island.paths.size(); ++k) {
      PathConstraint& p = paths_[island.paths[k]];
      solvePathConstraint(p, table, p.compliance * inv_h2, h, island.span_ends[k]);
    }
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
