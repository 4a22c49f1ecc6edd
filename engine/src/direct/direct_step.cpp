// The direct method's solve of one substep (World::solveDirect): every
// joint row and cable path in one factorization per iteration
// (direct_solver.h), and what stays outside it swept after each
// iteration, Gauss-Seidel style: contacts (SCA 2020, sec. 3.5) and
// weighted paths (cable friction).
#include <algorithm>

#include "direct_solver.h"
#include "reeve/engine/world.h"

namespace reeve {

void World::solveDirect(double h, bool again) {
  const double inv_h2 = 1.0 / (h * h);
  const BodyTable table{bodies_.data(), &world_frame_};
  // Weighted paths (cable friction) pull along J_f, not along their
  // length's gradient J_c: a non-symmetric row the LDL^T solve cannot
  // take. They are swept after each direct iteration, as contacts are.
  bool weighted = false;
  for (const PathConstraint& p : paths_) weighted |= p.enabled && !p.weights.empty();
  direct_->prepare(*this, h, again);
  // A row that nothing moves (a cable between two static anchors) is not
  // in the direct system, but a compliant one still pulls: with w = 0 one
  // visit sets its tension to stretch / compliance (issue 28, item 8; it
  // read 0, and friction links beside it decided on that 0).
  for (PathConstraint& p : paths_)
    if (p.enabled && p.weights.empty() && p.compliance > 0.0 &&
        std::none_of(p.points.begin(), p.points.end(), [&](const PathPoint& q) { return body(q.body).moves(); }))
      solvePathConstraint(p, table, p.compliance * inv_h2, h);
  for (DistanceConstraint& c : distances_)
    if (c.enabled && c.compliance > 0.0 && !body(c.a).moves() && !body(c.b).moves())
      solveDistanceConstraint(c, body(c.a), body(c.b), c.compliance * inv_h2, h);
  for (int it = 0; it < settings_.iterations; ++it) {
    const bool moved = direct_->iterate(*this, h);
    if (!moved && manifolds_.empty() && !weighted) break;  // converged: the rest would do nothing
    ++last_iterations_;
    for (ContactManifold& m : manifolds_) {
      const Contact& c = contacts_[m.first];
      solveContactPositions(m, contacts_.data(), body(c.a), body(c.b));
    }
    if (weighted)
      for (PathConstraint& p : paths_)
        if (!p.weights.empty()) solvePathConstraint(p, table, p.compliance * inv_h2, h);
    if (it + 1 < settings_.iterations && interruptRequested()) {  // the substep ends here
      interrupted_ = true;
      break;
    }
  }
}

}  // namespace reeve
