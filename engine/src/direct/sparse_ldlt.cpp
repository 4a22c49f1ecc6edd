#include "sparse_ldlt.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace reeve {
namespace {

constexpr double kSupernodalWidth = 6.0;  // columns a supernode, on average (analyze())

}  // namespace

std::vector<int> SparseLdlt::analyze(int n, const std::vector<std::pair<int, int>>& entries, Layout layout) {
  n_ = n;
  // Columns of the upper triangle, each sorted by row, duplicates merged.
  std::vector<std::vector<int>> column_rows(n);
  for (const auto& [i, k] : entries) {
    assert(0 <= i && i <= k && k < n);
    column_rows[k].push_back(i);
  }
  Ap_.assign(n + 1, 0);
  Ai_.clear();
  diagonal_.assign(n, -1);
  for (int k = 0; k < n; ++k) {
    std::sort(column_rows[k].begin(), column_rows[k].end());
    column_rows[k].erase(std::unique(column_rows[k].begin(), column_rows[k].end()), column_rows[k].end());
    for (const int i : column_rows[k]) {
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
  std::vector<int> parent(n, -1), flag(n, -1), count(n, 0);
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    for (int p = Ap_[k]; p < Ap_[k + 1]; ++p)
      for (int i = Ai_[p]; flag[i] != k; i = parent[i]) {
        if (parent[i] == -1) parent[i] = k;
        ++count[i];
        flag[i] = k;
      }
  }
  Lp_.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) Lp_[k + 1] = Lp_[k] + count[k];
  Li_.assign(Lp_[n], 0);
  inv_d_.assign(n, 0.0);
  pivot_ratio_.assign(n, 0.0);
  // The pattern of each row of L, in the order the numeric factorization
  // visits it (the reach of the row's column in the tree, topologically),
  // with where each L(k, i) goes; each column's rows ascending in Li_.
  std::vector<int> pattern(n), filled(n, 0);
  row_start_.assign(n + 1, 0);
  row_column_.clear();
  row_slot_.clear();
  std::fill(flag.begin(), flag.end(), -1);
  for (int k = 0; k < n; ++k) {
    int top = n;
    flag[k] = k;
    for (int p = Ap_[k]; p < Ap_[k + 1]; ++p) {
      int len = 0;
      for (int i = Ai_[p]; flag[i] != k; i = parent[i]) {
        pattern[len++] = i;
        flag[i] = k;
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
  // Supernodes: column j + 1 joins j's where it is j's parent and L's
  // pattern below it is j's (the column counts then differ by one).
  begin_.assign(1, 0);
  for (int j = 0; j + 1 < n; ++j)
    if (!(parent[j] == j + 1 && count[j] == count[j + 1] + 1)) begin_.push_back(j + 1);
  if (n > 0) begin_.push_back(n);
  const int supernodes = static_cast<int>(begin_.size()) - 1;
  // By supernodes where their dense kernels pay: where the supernodes are
  // on average kSupernodalWidth columns wide or more, so that a block's
  // multiply-adds run down whole columns rather than over scattered
  // entries. Measured on the shipped scenes' systems (instructions in
  // factor() and the solves over a run, by supernodes against row by row;
  // mean width, then multiply-adds per entry of L): the hand's fingers and
  // thumb (10 and 11; 6.2 and 5.6) -37 %, as they were with welded knuckle
  // wheels (6.9; 7.9) -36 %, the crane (6.75; 6.6) -20 %, the bow (5.8;
  // 4.9) +12 %, the gym (3.7; 4.0) +1 %, the pulley (3.6; 6.3) +3 %,
  // rope_segments (3.0; 2.6) +61 %, chains (1; 1) +182 %; and, taken to
  // supernodes by this rule, joints.json's and springs.json's small dense
  // systems (8 to 10, 7.2 wide; 3.0 to 4.8) -6 and -14 %. The work per
  // entry (CHOLMOD's switch) put the pulley above the hand.
  supernodal_ = layout == Layout::Supernodes ||
                (layout == Layout::Automatic && Lp_[n] > 0 && n >= kSupernodalWidth * supernodes);
  if (!supernodal_) {
    Lx_.assign(Lp_[n], 0.0);
    y_.assign(n, 0.0);
    block_values_.clear();
    return slots;
  }
  Lx_.clear();
  std::vector<int> supernode_of(n);
  row_begin_.assign(supernodes + 1, 0);
  block_.assign(supernodes + 1, 0);
  rows_.clear();
  for (int s = 0; s < supernodes; ++s) {
    const int first = begin_[s], last = begin_[s + 1] - 1;
    for (int j = first; j <= last; ++j) {
      supernode_of[j] = s;
      rows_.push_back(j);
    }
    rows_.insert(rows_.end(), Li_.begin() + Lp_[last], Li_.begin() + Lp_[last + 1]);
    row_begin_[s + 1] = static_cast<int>(rows_.size());
    block_[s + 1] = block_[s] + (row_begin_[s + 1] - row_begin_[s]) * (last + 1 - first);
  }
  block_values_.assign(block_[supernodes], 0.0);
  // Each supernode's updates: the descendants whose rows below reach its
  // columns, in order (a descendant's rows in one supernode are
  // consecutive, its rows ascending).
  std::vector<std::vector<Update>> pending(supernodes);
  for (int s = 0; s < supernodes; ++s) {
    const int width = begin_[s + 1] - begin_[s], end = row_begin_[s + 1];
    for (int t = row_begin_[s] + width; t < end;) {
      const int to = supernode_of[rows_[t]];
      const int first = t;
      while (t < end && supernode_of[rows_[t]] == to) ++t;
      pending[to].push_back({s, first - row_begin_[s], t - first, 0});
    }
  }
  // Where each value of A, and each update's rows, land in a supernode's
  // block (its local row numbers).
  std::vector<int> by_row_begin(n + 1, 0), by_row(Ai_.size()), column_of(Ai_.size());  // A's upper triangle, row by row
  for (const int i : Ai_) ++by_row_begin[i + 1];
  for (int i = 0; i < n; ++i) by_row_begin[i + 1] += by_row_begin[i];
  std::vector<int> next(by_row_begin.begin(), by_row_begin.end() - 1);
  for (int k = 0; k < n; ++k)
    for (int p = Ap_[k]; p < Ap_[k + 1]; ++p) {
      by_row[next[Ai_[p]]++] = p;
      column_of[p] = k;
    }
  std::vector<int> local(n, -1);
  std::vector<char> from_a(n, 0);  // per local row of a column: a value of A lands there
  scatter_.clear();
  zeros_.clear();
  update_begin_.assign(supernodes + 1, 0);
  updates_.clear();
  rel_.clear();
  std::size_t longest = 0;  // update, for work_
  for (int s = 0; s < supernodes; ++s) {
    const int first = begin_[s], ld = row_begin_[s + 1] - row_begin_[s];
    for (int t = 0; t < ld; ++t) local[rows_[row_begin_[s] + t]] = t;
    // A(i, k), i <= k, is L's column i, row k; the block's other entries
    // on and below its diagonal start at 0.
    for (int j = first; j < begin_[s + 1]; ++j) {
      const int column = block_[s] + (j - first) * ld;
      std::fill(from_a.begin(), from_a.begin() + ld, 0);
      for (int q = by_row_begin[j]; q < by_row_begin[j + 1]; ++q) {
        const int p = by_row[q];
        assert(local[column_of[p]] >= j - first);
        scatter_.emplace_back(p, column + local[column_of[p]]);
        from_a[local[column_of[p]]] = 1;
      }
      for (int t = j - first; t < ld; ++t)
        if (!from_a[t]) zeros_.push_back(column + t);
    }
    for (Update u : pending[s]) {
      const int from_rows = row_begin_[u.from], from_ld = row_begin_[u.from + 1] - from_rows;
      u.rel = static_cast<int>(rel_.size());
      for (int t = u.first; t < from_ld; ++t) {
        assert(local[rows_[from_rows + t]] >= 0);  // a descendant's pattern below lies in its ancestor's
        rel_.push_back(local[rows_[from_rows + t]]);
      }
      longest = std::max(longest, static_cast<std::size_t>(from_ld - u.first));
      updates_.push_back(u);
    }
    update_begin_[s + 1] = static_cast<int>(updates_.size());
    for (int t = 0; t < ld; ++t) local[rows_[row_begin_[s] + t]] = -1;
  }
  work_.assign(longest, 0.0);
  size_.assign(n, 0.0);
  return slots;
}

inline bool SparseLdlt::judgePivot(int k, double d, double size, double tolerance) {
  const double sign = !negative_.empty() && negative_[k] ? -1.0 : 1.0;
  pivot_ratio_[k] = size > 0.0 ? sign * d / size : 0.0;
  inv_d_[k] = sign * d > tolerance * size ? 1.0 / d : 0.0;
  return inv_d_[k] != 0.0;
}

int SparseLdlt::factor(double drop_tolerance, const std::vector<char>& keep, double keep_tolerance) {
  return supernodal_ ? factorSupernodes(drop_tolerance, keep, keep_tolerance)
                     : factorRows(drop_tolerance, keep, keep_tolerance);
}

int SparseLdlt::factorRows(double drop_tolerance, const std::vector<char>& keep, double keep_tolerance) {
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
    if (!judgePivot(k, d, size, !keep.empty() && keep[k] ? keep_tolerance : drop_tolerance)) ++dropped;
  }
  return dropped;
}

int SparseLdlt::factorSupernodes(double drop_tolerance, const std::vector<char>& keep, double keep_tolerance) {
  // Left-looking by supernodes: each supernode's block starts as A's
  // columns, takes every descendant's update L_D D_D L_D^T (summed over the
  // descendant's columns in work_, then added by local rows), and is
  // factored as a dense block, column by column. The blocks hold L D (a
  // column of L times its pivot: what the updates read, unscaled), and
  // each use takes L_kj = (L D)_kj / d_j. A column's terms L_kj^2 d_j also
  // sum, as magnitudes, into the size its pivot is judged against. A zero
  // L_kj (a row fixed or off: its values zero in A; or a dropped row's,
  // 1 / d_j taken as 0) adds nothing, and is skipped.
  for (const int z : zeros_) block_values_[z] = 0.0;
  for (const auto& [p, place] : scatter_) block_values_[place] = Ax_[p];
  int dropped = 0;
  const int supernodes = static_cast<int>(begin_.size()) - 1;
  for (int s = 0; s < supernodes; ++s) {
    const int first = begin_[s], width = begin_[s + 1] - first, ld = row_begin_[s + 1] - row_begin_[s];
    double* L = block_values_.data() + block_[s];
    for (int c = 0; c < width; ++c) size_[first + c] = std::abs(L[c * ld + c]);
    for (int u = update_begin_[s]; u < update_begin_[s + 1]; ++u) {
      const Update& up = updates_[u];
      const int from_first = begin_[up.from], from_width = begin_[up.from + 1] - from_first;
      const int from_ld = row_begin_[up.from + 1] - row_begin_[up.from], m = from_ld - up.first;
      const double* from = block_values_.data() + block_[up.from] + up.first;
      const int* rel = rel_.data() + up.rel;
      for (int j = 0; j < up.width; ++j) {  // column rel[j] of this block -= sum_c (L D)(:, c) L_jc
        double* target = L + rel[j] * ld;
        double* w = work_.data();
        bool any = false;
        for (int c = 0; c < from_width; ++c) {
          const double* column = from + c * from_ld;
          const double f = column[j] * inv_d_[from_first + c];
          if (f == 0.0) continue;
          size_[first + rel[j]] += std::abs(column[j] * f);
          if (from_width == 1) {
            for (int i = j; i < m; ++i) target[rel[i]] -= column[i] * f;
          } else if (any) {
            for (int i = j; i < m; ++i) w[i] += column[i] * f;
          } else {
            for (int i = j; i < m; ++i) w[i] = column[i] * f;
            any = true;
          }
        }
        if (any)
          for (int i = j; i < m; ++i) target[rel[i]] -= w[i];
      }
    }
    for (int c = 0; c < width; ++c) {
      double* column = L + c * ld;
      for (int before = 0; before < c; ++before) {
        const double* other = L + before * ld;
        const double f = other[c] * inv_d_[first + before];
        if (f == 0.0) continue;
        size_[first + c] += std::abs(other[c] * f);
        for (int t = c; t < ld; ++t) column[t] -= other[t] * f;
      }
      const int k = first + c;
      if (!judgePivot(k, column[c], size_[k], !keep.empty() && keep[k] ? keep_tolerance : drop_tolerance)) ++dropped;
    }
  }
  return dropped;
}

void SparseLdlt::solve(double* x) const {
  if (supernodal_) {
    const int supernodes = static_cast<int>(begin_.size()) - 1;
    for (int s = 0; s < supernodes; ++s) {
      const int first = begin_[s], width = begin_[s + 1] - first, ld = row_begin_[s + 1] - row_begin_[s];
      const double* L = block_values_.data() + block_[s];
      const int* rows = rows_.data() + row_begin_[s];
      for (int c = 0; c < width; ++c) {
        const double* column = L + c * ld;
        const double xc = x[first + c] * inv_d_[first + c];  // L(:, c) x_c = (L D)(:, c) x_c / d_c
        for (int t = c + 1; t < width; ++t) x[first + t] -= column[t] * xc;
        for (int t = width; t < ld; ++t) x[rows[t]] -= column[t] * xc;
      }
    }
  } else {
    for (int j = 0; j < n_; ++j)
      for (int p = Lp_[j]; p < Lp_[j + 1]; ++p) x[Li_[p]] -= Lx_[p] * x[j];
  }
  for (int j = 0; j < n_; ++j) x[j] *= inv_d_[j];
  solveTransposed(x);
}

void SparseLdlt::solveTransposed(double* x) const {
  if (!supernodal_) {
    for (int j = n_ - 1; j >= 0; --j)
      for (int p = Lp_[j]; p < Lp_[j + 1]; ++p) x[j] -= Lx_[p] * x[Li_[p]];
    return;
  }
  for (int s = static_cast<int>(begin_.size()) - 2; s >= 0; --s) {
    const int first = begin_[s], width = begin_[s + 1] - first, ld = row_begin_[s + 1] - row_begin_[s];
    const double* L = block_values_.data() + block_[s];
    const int* rows = rows_.data() + row_begin_[s];
    for (int c = width - 1; c >= 0; --c) {
      const double* column = L + c * ld;
      double sum = 0.0;
      for (int t = c + 1; t < ld; ++t) sum += column[t] * x[rows[t]];
      x[first + c] -= sum * inv_d_[first + c];
    }
  }
}

}  // namespace reeve
