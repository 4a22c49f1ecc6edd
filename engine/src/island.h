// Islands (issue 30): the moving bodies that constraints join, each solved
// on its own, and on its own thread when the World has several
// (World::setThreads). The solve of one island reads and writes only its
// own bodies, its own constraints and the static bodies it hangs from
// (which no kernel writes: BodyState::takesImpulses), so islands solved
// side by side end on the same bits as solved one after another. So do
// the other passes of a substep (World::step): each island's
// integration, velocities and ledger flows are its own.
#pragma once

#include <optional>
#include <vector>

#include "direct/direct_solver.h"
#include "gauss_seidel/span_ends.h"
#include "light_bodies.h"
#include "reeve/engine/body.h"
#include "reeve/engine/energy.h"
#include "reeve/engine/world.h"

namespace reeve {

/// One island: the bodies joined, directly or through others, by joints,
/// distance constraints, paths, the couplings substep hooks declare
/// (World::coupleBodies: every link of a cable, as its spans move from
/// link to link) and contacts between colliders (every moving collider is
/// in one island: which pairs touch changes within a step). Static bodies
/// join nothing, so machines hung from one anchor are islands of their
/// own. A kinematic body joins the islands it touches: their constraints
/// write its impulses (the work it does).
struct Island {
  std::vector<BodyId> bodies;  // moving and kinematic, increasing
  // The constraints on them, by type, each increasing.
  std::vector<int> hinges, prismatics, sphericals, fixeds, distances, paths;
  std::vector<int> manifolds;  // this substep's contact manifolds on them (World::contactManifolds)
  DirectSolver direct;
  // Runs of massless bodies this substep, and their scratch
  // (light_bodies.h); under Gauss-Seidel each run's one row between its
  // ends (the first light_runs.size() rows), and which of the paths are
  // its spans.
  std::vector<LightBody> light_bodies, light_scratch;
  std::vector<LightRun> light_runs;
  std::vector<PathConstraint> light_rows;
  std::vector<char> light_span;  // by island.paths' order
  bool light_possible = false;   // a body of it at most kMasslessShare of another's mass (World::buildIslands)
  std::vector<int> swept_hinges;      // Gauss-Seidel's: the hinges with a row (hingeSolvesNothing), for one solve
  std::vector<SpanEnds> span_ends;  // Gauss-Seidel's, by paths' order, for one solve (World::sweepGaussSeidel)
  int iterations = 0;        // the last solve's
  int contact_layouts = 0;   // this step's: DirectSolver::prepare built its layout again for a contact
  bool interrupted = false;  // the last solve stopped for the interrupt flag
  bool driven = false;       // a joint of it has a drive this substep (World::beginSolve)
  bool moved = false;        // the hooks moved a row of it onto other bodies' island (World::rowsMoved)
  bool news = false;         // the hooks' island parts left news this substep (World::IslandHook)
  // Where it is in the step: the substep it is at (done with those
  // before), and whether that one's first pass has run (World::
  // startIsland). Islands running whole steps are at different substeps.
  int at = 0;
  bool started = false;
  bool cut = false;  // the interrupt flag cut one of its solves or substeps short this step
  std::optional<NonFiniteFind> non_finite;  // the first this step
  std::vector<int> substep_iterations;      // per substep of a whole step: its solve's iterations
  // Its share of the time of the threads that ran it (their time over the
  // islands each ran), since the last World::balanceIslandRuns.
  double ns = 0.0;
  // Its work and losses since the islands were built (the flows of
  // WorldEnergy): World::energy adds them to the World's in island order,
  // and buildIslands folds them in, so the sums are the same on any number
  // of threads, and read by the caller's thread only when asked for.
  WorldEnergy flows;
};

/// Adds the flows of `from` (the work and losses; the rest of WorldEnergy
/// is state) to `to`.
void addFlows(WorldEnergy& to, const WorldEnergy& from);

}  // namespace reeve
