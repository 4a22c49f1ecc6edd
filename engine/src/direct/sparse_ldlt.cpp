#include "sparse_ldlt.h"

#include <algorithm>
#include <cassert>
#include <cmath>

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
  pivot_ratio_.assign(n, 0.0);
  y_.assign(n, 0.0);
  // The pattern of each row of L, in the order the numeric factorization
  // visits it (the reach of the row's column in the tree, topologically),
  // with where each L(k, i) goes: computed once, so factor() only does
  // arithmetic.
  std::vector<int> pattern(n), filled(n, 0);
  row_start_.assign(n + 1, 0);
  row_column_.clear();
  row_slot_.clear();
  std::fill(flag_.begin(), flag_.end(), -1);
  for (int k = 0; k < n; ++k) {
    int top = n;
    flag_[k] = k;
    for (int p = Ap_[k]; p < Ap_[k + 1]; ++p) {
      int len = 0;
      for (int i = Ai_[p]; flag_[i] != k; i = parent_[i]) {
        pattern[len++] = i;
        flag_[i] = k;
      }
      while (len > 0) pattern[--top] = pattern[--len];
    }
    for (; top < n; ++top) {
      const int i = pattern[top];
      const int slot = Lp_[i] + filled[i]++;
      Li_[slot] = k;
      row_column_.push_back(i);
      row_slot_.push_back(slot);
    }
    row_start_[k + 1] = static_cast<int>(row_column_.size());
  }
  return slots;
}

int SparseLdlt::factor(double drop_tolerance, const std::vector<char>& keep, double keep_tolerance) {
  // Davis, ldl_numeric, on the pattern analyze() found: row k of L from a
  // sparse triangular solve with the rows above it.
  int dropped = 0;
  for (int k = 0; k < n_; ++k) {
    for (int p = Ap_[k]; p < Ap_[k + 1]; ++p) y_[Ai_[p]] += Ax_[p];
    double d = y_[k];
    double size = std::abs(d);  // of what d is the difference of
    y_[k] = 0.0;
    for (int t = row_start_[k]; t < row_start_[k + 1]; ++t) {
      const int i = row_column_[t], slot = row_slot_[t];
      const double yi = y_[i];
      y_[i] = 0.0;
      for (int p = Lp_[i]; p < slot; ++p) y_[Li_[p]] -= Lx_[p] * yi;
      const double l_ki = yi * inv_d_[i];
      d -= l_ki * yi;
      size += std::abs(l_ki * yi);
      Lx_[slot] = l_ki;
    }
    const double sign = !negative_.empty() && negative_[k] ? -1.0 : 1.0;
    pivot_ratio_[k] = size > 0.0 ? sign * d / size : 0.0;
    if (sign * d > (!keep.empty() && keep[k] ? keep_tolerance : drop_tolerance) * size) {
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
    for (int p = Lp_[j]; p < Lp_[j + 1]; ++p) x[Li_[p]] -= Lx_[p] * x[j];
  for (int j = 0; j < n_; ++j) x[j] *= inv_d_[j];
  for (int j = n_ - 1; j >= 0; --j)
    for (int p = Lp_[j]; p < Lp_[j + 1]; ++p) x[j] -= Lx_[p] * x[Li_[p]];
}

void SparseLdlt::solveTransposed(double* x) const {
  for (int j = n_ - 1; j >= 0; --j)
    for (int p = Lp_[j]; p < Lp_[j + 1]; ++p) x[j] -= Lx_[p] * x[Li_[p]];
}

}  // namespace reeve
