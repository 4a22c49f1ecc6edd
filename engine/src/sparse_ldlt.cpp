#include "sparse_ldlt.h"

#include <algorithm>
#include <cassert>

namespace reeve {

std::vector<int> SparseLdlt::analyze(int n, const std::vector<std::pair<int, int>>& entries) {
  n_ = n;
  // Columns of the upper triangle, each sorted by row, duplicates merged.
  std::vector<std::vector<int>> rows(n);
  for (const auto& [i, k] : entries) {
    assert(0 <= i && i <= k && k < n);
    rows[k].push_back(i);
  }
  Ap_.assign(n + 1, 0);
  Ai_.clear();
  diagonal_.assign(n, -1);
  for (int k = 0; k < n; ++k) {
    std::sort(rows[k].begin(), rows[k].end());
    rows[k].erase(std::unique(rows[k].begin(), rows[k].end()), rows[k].end());
    for (const int i : rows[k]) {
      if (i == k) diagonal_[k] = static_cast<int>(Ai_.size());
      Ai_.push_back(i);
    }
    Ap_[k + 1] = static_cast<int>(Ai_.size());
    assert(diagonal_[k] >= 0);
  }
  Ax_.assign(Ai_.size(), 0.0);
  std::vector<int> slots;
  slots.reserve(entries.size());
  for (const auto& [i, k] : entries) {
    const auto first = Ai_.begin() + Ap_[k], last = Ai_.begin() + Ap_[k + 1];
    slots.push_back(static_cast<int>(std::lower_bound(first, last, i) - Ai_.begin()));
  }
  // Elimination tree and column counts of L (Davis, ldl_symbolic).
  parent_.assign(n, -1);
  flag_.assign(n, -1);
  Lnz_.assign(n, 0);
  for (int k = 0; k < n; ++k) {
    flag_[k] = k;
    for (int p = Ap_[k]; p < Ap_[k + 1]; ++p) {
      for (int i = Ai_[p]; flag_[i] != k; i = parent_[i]) {
        if (parent_[i] == -1) parent_[i] = k;
        ++Lnz_[i];
        flag_[i] = k;
      }
    }
  }
  Lp_.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) Lp_[k + 1] = Lp_[k] + Lnz_[k];
  Li_.assign(Lp_[n], 0);
  Lx_.assign(Lp_[n], 0.0);
  inv_d_.assign(n, 0.0);
  y_.assign(n, 0.0);
  pattern_.assign(n, 0);
  return slots;
}

int SparseLdlt::factor(double drop_tolerance) {
  // Davis, ldl_numeric: row k of L from a sparse triangular solve with the
  // rows above it, whose pattern is the reach of column k in the tree.
  int dropped = 0;
  for (int k = 0; k < n_; ++k) {
    y_[k] = 0.0;
    int top = n_;
    flag_[k] = k;
    Lnz_[k] = 0;
    for (int p = Ap_[k]; p < Ap_[k + 1]; ++p) {
      int i = Ai_[p];
      y_[i] += Ax_[p];
      int len = 0;
      for (; flag_[i] != k; i = parent_[i]) {
        pattern_[len++] = i;
        flag_[i] = k;
      }
      while (len > 0) pattern_[--top] = pattern_[--len];
    }
    double d = y_[k];
    y_[k] = 0.0;
    for (; top < n_; ++top) {
      const int i = pattern_[top];
      const double yi = y_[i];
      y_[i] = 0.0;
      const int end = Lp_[i] + Lnz_[i];
      for (int p = Lp_[i]; p < end; ++p) y_[Li_[p]] -= Lx_[p] * yi;
      const double l_ki = yi * inv_d_[i];
      d -= l_ki * yi;
      Li_[end] = k;
      Lx_[end] = l_ki;
      ++Lnz_[i];
    }
    if (d > drop_tolerance * Ax_[diagonal_[k]]) {
      inv_d_[k] = 1.0 / d;
    } else {
      inv_d_[k] = 0.0;
      ++dropped;
    }
  }
  return dropped;
}

void SparseLdlt::solve(double* x) const {
  for (int j = 0; j < n_; ++j)
    for (int p = Lp_[j]; p < Lp_[j] + Lnz_[j]; ++p) x[Li_[p]] -= Lx_[p] * x[j];
  for (int j = 0; j < n_; ++j) x[j] *= inv_d_[j];
  for (int j = n_ - 1; j >= 0; --j)
    for (int p = Lp_[j]; p < Lp_[j] + Lnz_[j]; ++p) x[j] -= Lx_[p] * x[Li_[p]];
}

}  // namespace reeve
