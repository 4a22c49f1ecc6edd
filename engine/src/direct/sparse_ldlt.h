// Sparse LDL^T factorization of a symmetric positive semi-definite matrix
// whose pattern is fixed between factorizations (Davis, "Algorithm 849: a
// concise sparse Cholesky factorization package", ACM TOMS 31(4), 2005:
// elimination tree, up-looking numeric factorization). Private to
// reeve_engine; the direct solver (direct_solver.h) factors its constraint
// matrix with it once or twice per iteration, so nothing here allocates
// after analyze().
#pragma once

#include <utility>
#include <vector>

namespace reeve {

class SparseLdlt {
 public:
  /// Sets the pattern of an n x n symmetric matrix from its upper triangle:
  /// `entries` are (row, column) pairs with row <= column, in the order the
  /// rows and columns are eliminated (permute before calling); duplicates
  /// share a value. Every diagonal entry must be present. Returns, for each
  /// pair, the index of its value in values().
  std::vector<int> analyze(int n, const std::vector<std::pair<int, int>>& entries);

  int size() const { return n_; }
  /// The matrix's upper-triangle values, as laid out by analyze(); the
  /// caller fills them before factor().
  std::vector<double>& values() { return Ax_; }
  /// Index in values() of diagonal entry k.
  int diagonalSlot(int k) const { return diagonal_[k]; }
  /// Marks the positions whose pivot is negative (a quasi-definite matrix
  /// [S B; B^T -M], S and M positive definite: Vanderbei, SIAM J. Optim.
  /// 5(1), 1995, has an LDL^T in any elimination order, its pivots positive
  /// in S and negative in -M); empty, or all 0: every pivot positive.
  /// Kept until changed.
  void setNegativePivots(std::vector<char> negative) { negative_ = std::move(negative); }

  /// Factors the matrix in values() as L D L^T. A pivot d_k = A_kk -
  /// sum_i L_ki^2 d_i (negated where setNegativePivots says it is
  /// negative) that falls to `drop_tolerance` times the size of
  /// what it is the difference of (A_kk + sum_i |L_ki^2 d_i|) or below is
  /// what rounding leaves of zero: its row depends on earlier ones (a
  /// redundant constraint) and is dropped, its unknown set to 0 by
  /// solve(). A small pivot that is a true difference (a very light body
  /// between heavy ones) stays. Returns the number of rows dropped.
  /// Rows with `keep`[k] set are dropped only at `keep_tolerance` instead
  /// (`keep` empty: none).
  int factor(double drop_tolerance, const std::vector<char>& keep = {}, double keep_tolerance = 0.0);
  /// Whether row k was dropped by the last factor().
  bool dropped(int k) const { return inv_d_[k] == 0.0; }
  /// Row k's pivot over the size of the terms it is the difference of, in
  /// the last factor(): near 1e-16 (or below 0) when rounding made it.
  double pivotRatio(int k) const { return pivot_ratio_[k]; }
  /// Solves L D L^T x = b in place (b in, x out; size n), dropped rows 0.
  void solve(double* x) const;
  /// Solves L^T z = b in place. With b = e_k for a dropped row k this is
  /// the dependency it was dropped for: A z = L D e_k = 0, z_k = 1.
  void solveTransposed(double* x) const;

 private:
  int n_ = 0;
  std::vector<int> Ap_, Ai_, diagonal_;  // upper triangle, column by column
  std::vector<double> Ax_;
  std::vector<int> parent_, Lp_, Lnz_, Li_, flag_;  // L, column by column
  std::vector<int> row_start_, row_column_, row_slot_;  // each row's pattern in L
  std::vector<double> Lx_, inv_d_, y_, pivot_ratio_;
  std::vector<char> negative_;
};

}  // namespace reeve
