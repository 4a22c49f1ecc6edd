// The direct method's solve of one substep (World::solveDirect): every
// joint row and cable path in one factorization per iteration
// (direct_solver.h), and what stays outside it swept after each
// iteration, Gauss-Seidel style: contacts (SCA 2020, sec. 3.5; but a
// cable-held body's resting ones on static bodies are rows of the solve:
// direct_solver.h) and weighted paths (cable friction).
#include <algorithm>
#include <cmath>

#include "../island.h"
#include "direct_solver.h"
#include "reeve/engine/world.h"

namespace reeve {

void World::solveDirect(Island& island, double h, bool again) {
  const double inv_h2 = 1.0 / (h * h);
  const BodyTable table{bodies_.data(), &world_frame_};
  // Weighted paths (cable friction) pull along J_f, not along their
  // length's gradient J_c: a non-symmetric row the LDL^T solve cannot
  // take. They are swept after each direct iteration, as contacts are.
  bool weighted = false;
  for (const int i : island.paths) weighted |= paths_[i].enabled && !paths_[i].weights.empty();
  island.contact_layouts += island.direct.prepare(*this, island, h, again) ? 1 : 0;
  // Bodies too light to carry their own motion against their cables'
  // loads, placed where massless ones would lie before each iteration
  // linearizes the rows and after the last (light_bodies.h).
  findLightBodies(*this, island, island.light_scratch, island.light_bodies, island.light_runs);
  // A row that nothing moves (a cable from a kinematic body to a static
  // one) is not in the direct system, but a compliant one still pulls: with
  // w = 0 one visit sets its tension to stretch / compliance (issue 28,
  // item 8; it read 0, and friction links beside it decided on that 0).
  for (const int i : island.paths) {
    PathConstraint& p = paths_[i];
    if (p.enabled && p.weights.empty() && p.compliance > 0.0 &&
        std::none_of(p.points.begin(), p.points.end(), [&](const PathPoint& q) { return body(q.body).moves(); }))
      solvePathConstraint(p, table, p.compliance * inv_h2, h);
  }
  for (const int i : island.distances) {
    DistanceConstraint& c = distances_[i];
    if (c.enabled && c.compliance > 0.0 && !body(c.a).moves() && !body(c.b).moves())
      solveDistanceConstraint(c, body(c.a), body(c.b), c.compliance * inv_h2, h);
  }
  for (int it = 0; it < settings_.iterations; ++it) {
    if (!island.light_runs.empty()) placeLightBodies(*this, island.light_bodies, island.light_runs, true);
    const bool moved = island.direct.iterate(*this, h);
    if (!moved && island.manifolds.empty() && !weighted) break;  // converged: the rest would do nothing
    ++island.iterations;
    island.direct.pressContacts(contacts_, manifolds_);
    bool contacts_moved = false;
    for (const int i : island.manifolds) {
      ContactManifold& m = manifolds_[i];
      const Contact& c = contacts_[m.first];
      contacts_moved |= solveContactPositions(m, contacts_.data(), body(c.a), body(c.b), frictionPool(m), supportGroup(m));
    }
    // A weighted path's visit moved a point of it by at most |dlambda| (1 /
    // m + r^2 |I^-1|), r the point's distance from its body's centre (|I^-1|
    // the Frobenius norm, at least the largest inverse moment): below the
    // rows' tolerance it settled. Counting 1 / m alone, a slipping belt
    // over two hinged wheels (rotors: 1 / m = 0) settled at its first visit
    // and its driven wheel spun at 2.7 rad/s at 1 x 50 where every
    // iteration run gives 11.5. (A bound relative to lambda, 1e-12 of it,
    // was passed by rounding: the capstan at 32 x 32, its heavy load on one
    // side, flipped lambda by 1.7e-10 of itself each visit and ran its
    // whole budget in 141 of 960 substeps.) Tolerance 0 times every
    // iteration: nothing settles.
    const double settled = direct::substepTolerance(settings_.tolerance, h);
    bool weighted_moved = !(settled > 0.0);
    if (weighted)
      for (const int i : island.paths)
        if (PathConstraint& p = paths_[i]; !p.weights.empty()) {
          const double before = p.lambda;
          solvePathConstraint(p, table, p.compliance * inv_h2, h);
          double reach = 0.0;  // m per unit of lambda
          for (const PathPoint& q : p.points) {
            const BodyState& s = body(q.body);
            reach = std::max(reach, s.inv_mass + q.local.squaredNorm() * s.inv_inertia.norm());
          }
          weighted_moved |= !(std::abs(p.lambda - before) * reach <= settled);
        }
    // Neither the rows nor the contacts nor the weighted paths moved a
    // body: the next iteration would start where this one did, and do the
    // same.
    if (!moved && !contacts_moved && !weighted_moved) break;
    if (it + 1 < settings_.iterations && interruptRequested()) {  // the substep ends here
      island.interrupted = true;
      break;
    }
  }
  if (!island.light_runs.empty()) {
    placeLightBodies(*this, island.light_bodies, island.light_runs, true);
    setLightVelocities(*this, island.light_bodies, island.light_runs, true);
  }
}

}  // namespace reeve
