// The direct solver's active set: the free rows' system solved, rows that
// leave their bounds fixed at them, slack rows the motion would stretch
// joined in, rows dependent on others dropped or kept, and a dependent row
// left unmet letting a one-sided row go.
#include "direct_solver.h"

#include <algorithm>
#include <cmath>

namespace reeve {
namespace {

using joint_rows::kInf;

// A pivot this small against the terms it is the difference of marks a row
// that depends on earlier ones (sparse_ldlt.h): rounding leaves such a
// pivot near 1e-16 of them (the last span of a belt over rotors, however
// uneven their masses). A light wheel between heavy loads leaves the ratio
// of their masses: 1e-6 for a 1e-6 kg wheel under 1 kg loads, 5e-13 for a
// 1e-9 kg wheel under 1000 kg, both kept.
constexpr double kDropTolerance = 1e-13;
constexpr double kRoundingPivot = 1e-15;
// Active-set passes per iteration; almost always one or two are enough.
constexpr int kMaxPasses = 8;
// Refinement steps at most per solve (factorAndSolve).
constexpr int kMaxRefinements = 4;

}  // namespace

void DirectSolver::bodyMotion() {
  // dx = W J^T dlambda, but for hubs: their own unknowns.
  std::fill(dx_.begin(), dx_.end(), Vec3::Zero());
  std::fill(dphi_.begin(), dphi_.end(), Vec3::Zero());
  for (const Entry& e : entries_) {
    if (hub_of_[e.body] >= 0) continue;
    const double dl = dlambda_[e.row];
    dx_[e.body] += dl * e.wlin;
    dphi_[e.body] += dl * e.wang;
  }
  const int n = static_cast<int>(rows_.size());
  for (const Hub& hub : hubs_) {
    const double* m = &hub_motion_[hub.first - n];
    if (hub.dofs == 1) {
      dphi_[hub.body] = frames_[hub.body].axle * m[0];
      continue;
    }
    dx_[hub.body] = Vec3(m[0], m[1], m[2]);
    dphi_[hub.body] = Vec3(m[3], m[4], m[5]);
  }
}

double DirectSolver::predictedValue(int r) const {
  double value = C_[r];
  for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e)
    value += entries_[e].lin.dot(dx_[entries_[e].body]) + entries_[e].ang.dot(dphi_[entries_[e].body]);
  return value;
}

void DirectSolver::readSolution() {
  const int n = static_cast<int>(rows_.size());
  for (int r = 0; r < n; ++r) dlambda_[r] = x_[rows_[r].position];
  for (std::size_t u = 0; u < hub_motion_.size(); ++u) hub_motion_[u] = x_[position_[n + u]];
  bodyMotion();
}

void DirectSolver::warmStartCaps() {
  // A motor stalled against a brake through a rigid chain: both drive rows
  // free make the first pass's system dependent and inconsistent (the
  // motor's speed and the brake's are tied), and whether rounding shows
  // the dependency decides the pass: dropped, the drives' lambdas of 1e8
  // are capped in the next pass; not dropped (once in a second with
  // hilbert3's 10 g wheels), the brake held the far drum still while the
  // motor wound on, and the next substep kicked every wheel to 105 rad/s.
  // A row that ended the last iteration at its cap starts this one there,
  // as active-set methods warm-start (Nocedal and Wright, sec. 16.5): the
  // system is then consistent from the first pass. solveActiveSet lets it
  // off its cap again if the solve asks for less.
  std::fill(warm_.begin(), warm_.end(), 0);
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    if (at_cap_[r] == 0 || state_[r] != State::Free) continue;
    const double cap = at_cap_[r] > 0 ? hi_[r] : lo_[r];
    if (!std::isfinite(cap) || cap == 0.0) continue;
    state_[r] = State::Fixed;
    dlambda_[r] = cap - lambda_[r];
    warm_[r] = 1;
  }
}

void DirectSolver::solveActiveSet(double tolerance) {
  const int n = static_cast<int>(rows_.size());
  std::fill(full_.begin(), full_.end(), 0.0);
  // J_e1 W J_e2^T = (lin_x wlin_x + ang_x wang_x) + (the same in y) + (in
  // z): x and y as one pair of doubles.
  using Pair2 = Eigen::Map<const Eigen::Vector2d>;
  for (const Pair& p : pairs_) {
    const Entry &e1 = entries_[p.e1], &e2 = entries_[p.e2];
    const Eigen::Vector2d xy = Pair2(e1.lin.data()).cwiseProduct(Pair2(e2.wlin.data())) +
                               Pair2(e1.ang.data()).cwiseProduct(Pair2(e2.wang.data()));
    full_[p.slot] += (xy.x() + xy.y()) + (e1.lin.z() * e2.wlin.z() + e1.ang.z() * e2.wang.z());
  }
  assembleHubs();
  std::vector<double>& A = ldlt_.values();
  released_ = -1;
  may_release_ = true;
  settled_ = false;
  bool held = false;  // held_ keeps a settled solve
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    const int let_go = released_;  // by the last pass: this one solves without it
    released_ = -1;
    // The free rows' system: fixed rows move to the right-hand side, and
    // fixed and off rows become identity rows (x = their known dlambda).
    std::copy(full_.begin(), full_.end(), A.begin());
    bool all_free = true;
    for (int r = 0; r < n; ++r) {
      const Row& row = rows_[r];
      if (state_[r] == State::Free) {
        A[row.diagonal] += alpha_[r] + delta_[r];
        x_[row.position] = -C_[r] - alpha_[r] * lambda_[r];
        continue;
      }
      all_free = false;
      for (int s = row.slots_begin; s < row.slots_end; ++s) A[slots_[s].value] = 0.0;
      A[row.diagonal] = 1.0;
      if (state_[r] == State::Off) dlambda_[r] = 0.0;
      x_[row.position] = dlambda_[r];
    }
    for (std::size_t u = n; u < position_.size(); ++u) x_[position_[u]] = 0.0;  // a hub's: M dx_h = J_h^T dlambda
    if (!all_free)
      for (int r = 0; r < n; ++r) {
        if (state_[r] != State::Fixed) continue;
        for (int s = rows_[r].slots_begin; s < rows_[r].slots_end; ++s) {
          const int other = slots_[s].other_row;
          if (other >= n || state_[other] == State::Free)
            x_[position_[other]] -= full_[slots_[s].value] * dlambda_[r];
        }
      }
    const bool released = factorAndSolve(tolerance);
    if (pass + 1 == kMaxPasses) {  // out of passes: every lambda within its bounds all the same
      for (int r = 0; r < n; ++r)
        dlambda_[r] = std::clamp(lambda_[r] + dlambda_[r], lo_[r], hi_[r]) - lambda_[r];
      bodyMotion();
      break;
    }
    bool changed = released;
    // A row let go along a dependency that this solve, without it, now
    // violates was needed after all: the dependent row it was let go for
    // cannot be met, and the others stay as they were (a stack landing on
    // its stop while the cable it hangs from is tight over a handle on its
    // own stop: letting the stop go sank the stack into it, at every
    // landing of the gym at 1 x 2).
    if (let_go >= 0) {
      const double predicted = predictedValue(let_go);
      if ((lo_[let_go] == 0.0 && predicted < -tolerance) || (hi_[let_go] == 0.0 && predicted > tolerance)) {
        state_[let_go] = State::Free;
        may_release_ = false;
        continue;
      }
    }
    // A row this pass let go or capped along a dependency: the motion of a
    // solve that could not meet the dependent row says nothing about the
    // others (judged by it, the spans of a chain between a motor and a
    // brake that disagreed were all let go as pushing: hilbert2 at 1 x 1).
    if (released) continue;
    // A row held at its cap by warmStartCaps is freed again (once) if the
    // solve asks for less: the residual C + J dx + alpha lambda grows with
    // lambda, so at the upper cap a positive one asks for less. The motion
    // the cap made then says nothing about the other rows (a drive reversed
    // at its limit pushed on into it): solve again before judging them.
    bool uncapped = false;
    for (int r = 0; r < n; ++r) {
      if (!warm_[r] || state_[r] != State::Fixed) continue;
      const double total = lambda_[r] + dlambda_[r];
      const double residual = predictedValue(r) + alpha_[r] * total;
      if ((total >= hi_[r] && residual > tolerance) || (total <= lo_[r] && residual < -tolerance)) {
        state_[r] = State::Free;
        warm_[r] = 0;
        uncapped = true;
      }
    }
    if (uncapped) continue;
    for (int r = 0; r < n; ++r) {
      if (state_[r] == State::Free) {
        const double total = lambda_[r] + dlambda_[r];
        if (total > hi_[r] || total < lo_[r]) {
          state_[r] = State::Fixed;
          dlambda_[r] = std::clamp(total, lo_[r], hi_[r]) - lambda_[r];
          changed = true;
        }
      } else if (state_[r] == State::Off) {
        // Would the others' motion violate this one-sided row?
        const double predicted = predictedValue(r);
        if ((hi_[r] == 0.0 && predicted > 0.0) || (lo_[r] == 0.0 && predicted < 0.0)) {
          state_[r] = State::Free;
          changed = true;
          // A limit its drive could not keep to: the drive asked past it,
          // so it pushes with all it has toward it (an unlimited one with
          // what it did this pass) and the limit takes the rest, as in
          // driveAgainstLimit. What it did this pass was the push to its
          // target with the limit away (a stalled motor pushed 2.7 of its
          // 5 N m at one substep a frame).
          if (const int d = drive_of_[r]; d >= 0 && state_[d] == State::Free) {
            state_[d] = State::Fixed;
            const double toward = lo_[r] == 0.0 ? lo_[d] : hi_[d];  // a lower limit's row pushes up: lo_ 0
            dlambda_[d] = std::isfinite(toward)
                              ? toward - lambda_[d]
                              : std::clamp(lambda_[d] + dlambda_[d], lo_[d], hi_[d]) - lambda_[d];
          }
        }
      }
    }
    // The other half of block principal pivoting (Judice and Pires 1994):
    // rows held at a bound (fixed there, or off) that the settled motion
    // leaves wanting to come off it are solved again, free. The first pass
    // solves every row in the set to C = 0, slack ones too (pulled_);
    // where a slack span and a taut one share a wheel (the crane's hoist
    // either side of its sheave, paying out) both came out pushing and
    // were held at 0 together, the taut one stayed stretched, the next
    // substep pulled twice as hard, and the ropes went slack and taut on
    // alternate substeps (50 J made in a frame at 100 x 1). And a catch
    // held at a winch's pull (the hoist and luffing ropes both at 30 kN)
    // left the rope slack after the motion, the load falling free for the
    // next three to six substeps. Freed again only while each settled
    // solve leaves the held rows less violated than the last, which cannot
    // cycle; else the least violated one stands: a row no motion can meet
    // (the gym's lat bar on its stop, the handle cable taut) only comes
    // back pushing, and passes spent on it threw the bar about.
    if (!changed) {
      const double violation = heldViolation(tolerance, false);
      if (violation > 0.0 && (!held || violation < held_.violation - tolerance)) {
        held_.dlambda = dlambda_;
        held_.hub_motion = hub_motion_;
        held_.state = state_;
        held_.violation = violation;
        held = true;
        heldViolation(tolerance, true);
        continue;
      }
      if (held && violation >= held_.violation - tolerance) restoreHeld();
      settled_ = true;
      break;
    }
  }
  if (!settled_ && held) {  // out of passes: the last settled solve stands
    restoreHeld();
    settled_ = true;
  }
}

void DirectSolver::restoreHeld() {
  dlambda_ = held_.dlambda;
  hub_motion_ = held_.hub_motion;
  state_ = held_.state;
  bodyMotion();
}

double DirectSolver::heldViolation(double tolerance, bool free_them) {
  double worst = 0.0;
  for (int r = 0; r < static_cast<int>(rows_.size()); ++r) {
    if (state_[r] == State::Free) continue;
    const double total = lambda_[r] + dlambda_[r];
    const bool at_hi = total == hi_[r], at_lo = total == lo_[r];
    if (!at_hi && !at_lo) continue;
    // The residual grows with lambda (J W J^T + alpha~ > 0): held at hi, a
    // positive one asks for less (a cable held slack at 0 but stretched);
    // at lo, a negative one for more (one held at its winch's pull but
    // slack).
    const double residual = predictedValue(r) + alpha_[r] * total;
    const double violation = at_hi ? residual : -residual;
    if (!(violation > tolerance)) continue;
    worst = std::max(worst, violation);
    if (free_them && state_[r] == State::Fixed) state_[r] = State::Free;
  }
  return worst;
}

bool DirectSolver::factorAndSolve(double tolerance) {
  // A row dropped as dependent that the solution leaves unmet may not be
  // dependent, only very light (a pivot of 1e-13 of its terms can be
  // either): solve again with it kept, unless its pivot is at the level of
  // rounding (1e-15 of its terms), which no very light body comes near
  // (1e-12 times lighter gives 5e-13); kept, it is still dropped there,
  // as another row may now be the dependent one. A truly dependent row is
  // met by the others' motion (a belt's last span) or cannot be (then no
  // solve can).
  const int n = static_cast<int>(rows_.size());
  std::copy(x_.begin(), x_.end(), rhs_.begin());
  std::fill(keep_.begin(), keep_.end(), 0);
  int unmet = -1;  // a row truly dependent and left unmet
  double unmet_residual = 0.0;
  for (int round = 0;; ++round) {
    const int dropped = ldlt_.factor(kDropTolerance, keep_, kRoundingPivot);
    ldlt_.solve(x_.data());
    readSolution();
    if (dropped == 0 || round == 2) break;
    bool rescued = false;
    unmet = -1;
    for (int r = 0; r < n; ++r) {
      const int k = rows_[r].position;
      if (state_[r] != State::Free || !ldlt_.dropped(k)) continue;
      const bool rounding = !(ldlt_.pivotRatio(k) > kRoundingPivot);
      const double residual = predictedValue(r) + alpha_[r] * lambda_[r];
      if (std::abs(residual) > std::max(tolerance, 1e-6 * std::abs(C_[r]))) {
        if (rounding) {
          if (unmet < 0) unmet = r, unmet_residual = residual;
          continue;
        }
        keep_[k] = 1;
        rescued = true;
      }
    }
    if (!rescued) break;
    std::copy(rhs_.begin(), rhs_.end(), x_.begin());
  }
  // Refinement converges as delta / (delta + the system's own scale) a
  // step: fast where the rows are stiff, slowly along a light hub between
  // heavy loads (a 3 g knuckle under a kilonewton tendon).
  if (!hubs_.empty()) {
    for (int step = 0; step < kMaxRefinements; ++step)
      if (!(refine() > tolerance)) break;
    for (const Hub& hub : hubs_) leastNormLeaves(hub);
  }
  return unmet >= 0 && may_release_ && releaseAlongDependency(unmet, unmet_residual);
}

bool DirectSolver::releaseAlongDependency(int r, double residual) {
  // Row r depends on others (rounding's pivot) and they leave it unmet:
  // no motion can meet it with these rows held. Along the dependency z
  // (A z = 0, z_r = 1) the lambdas shift with no motion at all; pulling
  // row r its way, t z with t = -sign(residual), brings some one-sided
  // rows to their bound 0 (a stop that would have to pull, a cable that
  // would have to push), or a capped row to its cap (a brake that must
  // slip). The first to get there is not needed as it was: it is fixed at
  // that bound and the next pass solves without it (the ratio test of a
  // pivoting method). Without this a stack on its stop, a cable tight over
  // it and a drive pulling that cable made a dependent set that kept the
  // stop and dropped the cable, for ever (the gym's press at one substep);
  // and a motor winding a rigid chain onto a braked drum, both drives'
  // rows free, held the drum still while the motor wound on, wherever
  // rounding hid the dependency (hilbert3 braked with 10 g wheels).
  std::fill(x_.begin(), x_.end(), 0.0);
  x_[rows_[r].position] = 1.0;
  ldlt_.solveTransposed(x_.data());
  const double t = residual > 0.0 ? -1.0 : 1.0;
  int best = -1;
  double best_ratio = kInf, best_bound = 0.0;
  for (int j = 0; j < static_cast<int>(rows_.size()); ++j) {
    if (state_[j] != State::Free) continue;
    const double total = lambda_[j] + dlambda_[j], shift = t * x_[rows_[j].position];
    double ratio, bound;
    if (shift < 0.0 && std::isfinite(lo_[j]) && total > lo_[j]) ratio = (total - lo_[j]) / -shift, bound = lo_[j];
    else if (shift > 0.0 && std::isfinite(hi_[j]) && total < hi_[j]) ratio = (hi_[j] - total) / shift, bound = hi_[j];
    else continue;
    if (j == r && bound == 0.0) continue;  // the unmet row itself may reach its cap, not let go
    if (ratio < best_ratio) best_ratio = ratio, best = j, best_bound = bound;
  }
  if (best < 0) return false;
  state_[best] = State::Fixed;
  dlambda_[best] = best_bound - lambda_[best];
  released_ = best_bound == 0.0 ? best : -1;  // a cap is kept: only a row let go is checked again
  return true;
}

}  // namespace reeve
