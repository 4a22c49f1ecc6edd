// Sparse LDL^T factorization of a symmetric positive semi-definite matrix
// whose pattern is fixed between factorizations: elimination tree, column
// counts and a row-by-row numeric factorization as in Davis, "Algorithm
// 849: a concise sparse Cholesky factorization package" (ACM TOMS 31(4),
// 2005); where those blocks are wide, left-looking by supernodes instead
// (Ng and Peyton, "Block sparse Cholesky algorithms on advanced
// uniprocessor computers", SIAM J. Sci. Comput. 14(5), 1993): consecutive
// columns of L with one pattern below them are stored and updated as one
// dense block (CHOLMOD chooses between its simplicial and supernodal forms
// likewise, by the work per entry of L). Private to reeve_engine; the
// direct solver (direct_solver.h) factors its constraint matrix with it
// once or twice per iteration, so nothing here allocates after analyze().
#pragma once

#include <utility>
#include <vector>

namespace reeve {

class SparseLdlt {
 public:
  /// How factor() works: row by row, by supernodes, or whichever the
  /// pattern's mean supernode width favours (analyze()).
  enum class Layout { Automatic, Rows, Supernodes };
  /// Sets the pattern of an n x n symmetric matrix from its upper triangle:
  /// `entries` are (row, column) pairs with row <= column, in the order the
  /// rows and columns are eliminated (permute before calling); duplicates
  /// share a value. Every diagonal entry must be present. Returns, for each
  /// pair, the index of its value in values(). Either layout gives the
  /// same factorization to rounding (tests/test_sparse_ldlt.cpp).
  std::vector<int> analyze(int n, const std::vector<std::pair<int, int>>& entries,
                           Layout layout = Layout::Automatic);

  int size() const { return n_; }
  /// The layout analyze() chose: Rows or Supernodes.
  Layout layout() const { return supernodal_ ? Layout::Supernodes : Layout::Rows; }
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
  int factorRows(double drop_tolerance, const std::vector<char>& keep, double keep_tolerance);
  int factorSupernodes(double drop_tolerance, const std::vector<char>& keep, double keep_tolerance);
  // Pivot k: its ratio to its size, kept (1 / d) or dropped (0).
  bool judgePivot(int k, double d, double size, double tolerance);

  int n_ = 0;
  std::vector<int> diagonal_;
  std::vector<double> Ax_, inv_d_, pivot_ratio_;
  std::vector<char> negative_;
  // Where L's supernodes are wide (the hand's fingers), by supernodes;
  // else (chains, stars) row by row.
  bool supernodal_ = false;

  // Row by row (Davis, ldl_numeric): A's upper triangle and L, column by
  // column; each row of L's pattern in the order it is computed.
  std::vector<int> Ap_, Ai_, Lp_, Li_;
  std::vector<int> row_start_, row_column_, row_slot_;
  std::vector<double> Lx_, y_;

  // By supernodes. One supernode's update from a descendant: the
  // descendant's rows [first, first + width) are columns of this
  // supernode, and its rows from `first` on land at the local rows listed
  // from rel_[rel].
  struct Update {
    int from, first, width, rel;
  };
  // Supernode s: columns [begin_[s], begin_[s + 1]); its rows (its columns,
  // then the pattern below them, ascending) rows_[row_begin_[s] ...
  // row_begin_[s + 1]); L D (L's columns times their pivots) stored from
  // block_[s] in block_values_, column by column, each column as long as
  // the row list (the entries above the diagonal unused).
  std::vector<int> begin_, row_begin_, rows_, block_;
  // Where A's values go in the blocks (index in Ax_, in block_values_),
  // and the blocks' other entries on and below their diagonals (0).
  std::vector<std::pair<int, int>> scatter_;
  std::vector<int> zeros_;
  std::vector<int> update_begin_;  // per supernode: its updates in updates_
  std::vector<Update> updates_;
  std::vector<int> rel_;
  std::vector<double> block_values_, size_, work_;
};

}  // namespace reeve
