// Hubs (direct_solver.h): bodies with many rows, whose motion is solved
// for beside the rows. Their mass blocks and couplings, the rows' delta,
// the refinement against the system without it, and the rule by which
// redundant rigid cables on one hub share its load.
#include "direct_solver.h"

#include <algorithm>

#include <Eigen/Eigenvalues>

namespace reeve {
namespace {

// delta (direct_solver.h) of a row on a hub, relative to its hub part of
// J W J^T, and for a leaf times its hub's leaf count (K leaves share its
// load). It only has to lift pivots above rounding; the refinement takes
// the error from delta to delta^2 a step, slowly where the system's own
// scale is below delta: at 1e-5 the hand's 3 g knuckles under a kilonewton
// tendon were not converged after four steps, at 2e-6 and below they
// are. Rounding in a rigid redundant row's value (1e-16 m) becomes a
// tension of 1e-16 m / (delta h^2); leastNormLeaves removes it from a
// hub's leaves (a rigid star of 4096 cables: 8e-6 of the closed form at
// 10 x 2 at any delta from 1e-6 to 1e-5, where before it grew with K).
constexpr double kHubRegularization = 1e-6;

}  // namespace

void DirectSolver::assembleHubs() {
  // J_h, -M_h, and each row's delta from its hub part of J W J^T.
  for (std::size_t h = 0; h < hubs_.size(); ++h) {
    const BodyFrame& f = frames_[hubs_[h].body];
    hub_inertia_[h] = f.R * f.state->inertia * f.R.transpose() / f.turn_scale;
  }
  for (const Coupling& c : couplings_) full_[c.slot] = hubGradient(entries_[c.entry], c.dof);
  for (const MassSlot& m : mass_slots_) full_[m.slot] = -hubMass(m.hub, m.i, m.j);
  std::fill(delta_.begin(), delta_.end(), 0.0);
  for (const Entry& e : entries_)
    if (hub_of_[e.body] >= 0) delta_[e.row] += kHubRegularization * (e.lin.dot(e.wlin) + e.ang.dot(e.wang));
  for (const Hub& hub : hubs_)  // a leaf's share of its hub's load
    for (int l = hub.first_leaf; l < hub.first_leaf + hub.leaves; ++l) delta_[entries_[leaf_entries_[l]].row] *= hub.leaves;
  for (std::size_t r = 0; r < rows_.size(); ++r) delta_[r] = std::max(0.0, delta_[r] - alpha_[r]);
}

double DirectSolver::hubMass(int h, int i, int j) const {
  const Hub& hub = hubs_[h];
  const BodyFrame& f = frames_[hub.body];
  if (hub.dofs == 1) return 1.0 / f.inv_axial;
  if (i < 3) return i == j ? 1.0 / f.inv_mass : 0.0;
  return j < 3 ? 0.0 : hub_inertia_[h](i - 3, j - 3);
}

double DirectSolver::hubGradient(const Entry& e, int dof) const {
  const Hub& hub = hubs_[hub_of_[e.body]];
  if (hub.dofs == 1) return e.ang.dot(frames_[hub.body].axle);
  return dof < 3 ? e.lin[dof] : e.ang[dof - 3];
}

double DirectSolver::refine() {
  // The factor solved the rows with delta on their diagonal; the residual
  // of the system without it, solved with the same factor, corrects the
  // solution (iterative refinement): the error falls from delta / (J W J^T)
  // to its square. The hubs' equations held already.
  const int n = static_cast<int>(rows_.size());
  std::fill(x_.begin(), x_.end(), 0.0);
  double largest = 0.0;
  for (int r = 0; r < n; ++r) {
    if (state_[r] != State::Free || delta_[r] == 0.0) continue;
    double residual = -C_[r] - alpha_[r] * (lambda_[r] + dlambda_[r]);
    for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e)
      residual -= entries_[e].lin.dot(dx_[entries_[e].body]) + entries_[e].ang.dot(dphi_[entries_[e].body]);
    x_[rows_[r].position] = residual;
    largest = std::max(largest, std::abs(residual));
  }
  if (largest == 0.0) return 0.0;
  ldlt_.solve(x_.data());
  for (int r = 0; r < n; ++r) dlambda_[r] += x_[rows_[r].position];
  for (std::size_t u = 0; u < hub_motion_.size(); ++u) hub_motion_[u] += x_[position_[n + u]];
  bodyMotion();
  return largest;
}

void DirectSolver::leastNormLeaves(const Hub& hub) {
  // Rigid cables that move the hub alone and are more than it has
  // freedoms for share its load as equal elastic cables would, stiffened
  // without bound: compliance in proportion to length L_k, so their
  // tensions minimize sum L_k dlambda_k^2 with the same wrench on the hub,
  // g = sum g_k dlambda_k (g_k = J_h of cable k):
  //   G = sum g_k g_k^T / L_k,   dlambda_k = g_k^T G^+ g / L_k.
  // The hub's motion stays as solved. What goes is the part of dlambda
  // that moves nothing: the solve's choice among equal answers, and
  // rounding in redundant rows divided by delta.
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  const auto gradient = [&](const Entry& e) {
    Vec6 g = Vec6::Zero();
    for (int d = 0; d < hub.dofs; ++d) g[d] = hubGradient(e, d);
    return g;
  };
  const auto shared = [&](int r) {
    return (rows_[r].source == Source::Path || rows_[r].source == Source::Distance) && state_[r] == State::Free &&
           alpha_[r] == 0.0 && length_[r] > 0.0;
  };
  Mat6 G = Mat6::Zero();
  Vec6 wrench = Vec6::Zero();
  int count = 0;
  for (int l = hub.first_leaf; l < hub.first_leaf + hub.leaves; ++l) {
    const Entry& e = entries_[leaf_entries_[l]];
    if (!shared(e.row)) continue;
    const Vec6 g = gradient(e);
    G += g * g.transpose() / length_[e.row];
    wrench += g * dlambda_[e.row];
    ++count;
  }
  if (count < 2) return;
  const Eigen::SelfAdjointEigenSolver<Mat6> eigen(G);
  const Vec6& values = eigen.eigenvalues();
  const double floor = 1e-12 * values.cwiseAbs().maxCoeff();
  Vec6 y = eigen.eigenvectors().transpose() * wrench;
  for (int i = 0; i < 6; ++i) y[i] = values[i] > floor ? y[i] / values[i] : 0.0;
  y = eigen.eigenvectors() * y;
  for (int l = hub.first_leaf; l < hub.first_leaf + hub.leaves; ++l) {
    const Entry& e = entries_[leaf_entries_[l]];
    if (shared(e.row)) dlambda_[e.row] = gradient(e).dot(y) / length_[e.row];
  }
}

}  // namespace reeve
