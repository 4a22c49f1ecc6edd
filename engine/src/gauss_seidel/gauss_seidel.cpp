// Gauss-Seidel, the paper's method (SCA 2018 sec. 3; SCA 2020 Alg. 2):
// each iteration visits the constraints one after another, each moving
// its bodies at once, joints first (each as one block, joint_rows.h),
// then distance constraints and cable paths, then contacts. A correction
// travels one constraint per visit: right while the bodies in a chain
// are about as heavy as each other (README, "Substeps and iterations").
#include <algorithm>

#include "../island.h"
#include "span_ends.h"
#include "reeve/engine/world.h"

namespace reeve {

namespace {

// A run's row (light_bodies.h): a rigid cable from the run's end on its
// first end body to the one on its last, each end as its span has it (a
// rolling end rolls), its rest length its spans' sum; and its spans
// marked, by island.paths' order. Rows are kept when runs come and go
// (never shrunk: a row's points are its own storage), so that the
// substeps allocate nothing once the most runs have been seen.
void prepareLightRows(const World& world, Island& island) {
  if (island.light_rows.size() < island.light_runs.size()) island.light_rows.resize(island.light_runs.size());
  island.light_span.assign(island.paths.size(), 0);
  for (std::size_t r = 0; r < island.light_runs.size(); ++r) {
    const LightRun& run = island.light_runs[r];
    const LightBody* m = island.light_bodies.data() + run.first;
    const LightBody& last = m[run.count - 1];
    PathConstraint& row = island.light_rows[r];
    row.points.assign(
        {world.path(m[0].path[0]).points[1 - m[0].end[0]], world.path(last.path[1]).points[1 - last.end[1]]});
    row.rest_length = world.path(m[0].path[0]).rest_length;
    for (int k = 0; k < run.count; ++k) row.rest_length += world.path(m[k].path[1]).rest_length;
    row.lambda = 0.0;
    for (int k = 0; k < run.count; ++k)
      for (const int path : m[k].path)
        island.light_span[std::lower_bound(island.paths.begin(), island.paths.end(), path) - island.paths.begin()] = 1;
  }
}

}  // namespace

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
  // Massless bodies (light_bodies.h): a visit of one of their spans moves
  // the light body, not the load it carries, and the sweeps stall. A run's
  // spans pull alike, and taut their ends lie the sum of their lengths
  // apart: one row between its ends stands for them, and the run is placed
  // on its spans after each sweep.
  findLightBodies(*this, island, island.light_scratch, island.light_bodies, island.light_runs);
  const bool light = !island.light_runs.empty();
  if (light) prepareLightRows(*this, island);
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
      if (light && island.light_span[k]) continue;  // its run's row, below
      PathConstraint& p = paths_[island.paths[k]];
      solvePathConstraint(p, table, p.compliance * inv_h2, h, island.span_ends[k]);
    }
    if (light) {
      for (std::size_t r = 0; r < island.light_runs.size(); ++r)
        solvePathConstraint(island.light_rows[r], table, 0.0, h);
      placeLightBodies(*this, island.light_bodies, island.light_runs, false);
    }
    for (const int i : island.manifolds) {
      ContactManifold& m = manifolds_[i];
      const Contact& c = contacts_[m.first];
      solveContactPositions(m, contacts_.data(), body(c.a), body(c.b), frictionPool(m), supportGroup(m));
    }
    if (it + 1 < settings_.iterations && interruptRequested()) {  // the substep ends here
      island.interrupted = true;
      break;
    }
  }
  if (light) setLightVelocities(*this, island.light_bodies, island.light_runs, false);
  // Each of a run's spans pulls with its row's tension.
  for (std::size_t r = 0; r < island.light_runs.size() && light; ++r) {
    const LightRun& run = island.light_runs[r];
    for (int k = 0; k < run.count; ++k)
      for (const int path : island.light_bodies[run.first + k].path) paths_[path].lambda = island.light_rows[r].lambda;
  }
}

}  // namespace reeve
