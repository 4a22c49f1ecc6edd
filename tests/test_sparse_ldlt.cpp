// The direct solver's factorization (engine/src/direct/sparse_ldlt.h, private
// to the engine, tested here white-box): L D L^T solves what a dense
// factorization solves, on the patterns the solver makes (J W J^T of rows
// that share bodies, and a long sparse chain); a dependent row is dropped,
// its pivot at rounding's level, and solveTransposed gives the dependency;
// a near-dependent row is kept; a quasi-definite matrix factors with its
// negative pivots where it says. Each test runs with both layouts (row by
// row, and by supernodes), which also agree with each other on random
// patterns of the solver's kind.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "../engine/src/direct/sparse_ldlt.h"

namespace reeve::test_sparse_ldlt {
namespace {

using Dense = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

// A = J W J^T + alpha I: `rows` constraint rows, row r on the degrees of
// freedom dofs_of_row[r] (J random there), W = diag(1 / masses of 0.5 to 2).
// Rows on a shared body couple, as in the solver's system.
Dense constraintSystem(int rows, int dofs, const std::vector<std::vector<int>>& dofs_of_row, double alpha,
                       std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), mass(0.5, 2.0);
  Dense J = Dense::Zero(rows, dofs);
  for (int r = 0; r < rows; ++r)
    for (const int d : dofs_of_row[r]) J(r, d) = u(rng);
  Vector w(dofs);
  for (int d = 0; d < dofs; ++d) w[d] = 1.0 / mass(rng);
  Dense A = J * w.asDiagonal() * J.transpose();
  A.diagonal().array() += alpha;
  return A;
}

using Layout = SparseLdlt::Layout;

// Loads the upper triangle's nonzeros of A into `ldlt` (its pattern: every
// structural entry, as the solver gives it, zero or not).
void load(SparseLdlt& ldlt, const Dense& A, Layout layout) {
  const int n = static_cast<int>(A.rows());
  std::vector<std::pair<int, int>> entries;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i <= k; ++i)
      if (i == k || A(i, k) != 0.0) entries.emplace_back(i, k);
  const std::vector<int> slot = ldlt.analyze(n, entries, layout);
  std::vector<double>& values = ldlt.values();
  std::fill(values.begin(), values.end(), 0.0);
  for (std::size_t e = 0; e < entries.size(); ++e) values[slot[e]] = A(entries[e].first, entries[e].second);
}

Vector solve(const SparseLdlt& ldlt, const Vector& b) {
  Vector x = b;
  ldlt.solve(x.data());
  return x;
}

class Factorization : public ::testing::TestWithParam<Layout> {};

// The hand's system (DESIGN, "Where the hand's frame goes"): fingers of
// hinged links, each link's five hinge rows on two bodies, tendons over
// every link of a finger; 48 unknowns, half of the triangle nonzero.
TEST_P(Factorization, SolvesAHandLikeSystemAsADenseFactorizationDoes) {
  std::mt19937 rng(7);
  std::vector<std::vector<int>> rows;
  int dofs = 0;
  for (int finger = 0; finger < 3; ++finger) {
    const int base = dofs;
    dofs += 3 * 6;  // three links
    for (int link = 0; link < 3; ++link)
      for (int r = 0; r < 5; ++r) {  // the hinge to the link before (the first's to the palm: none)
        std::vector<int> on;
        for (int d = 0; d < 6; ++d) on.push_back(base + 6 * link + d);
        if (link > 0)
          for (int d = 0; d < 6; ++d) on.push_back(base + 6 * (link - 1) + d);
        rows.push_back(on);
      }
    std::vector<int> tendon;  // through every link of the finger
    for (int d = base; d < dofs; ++d) tendon.push_back(d);
    rows.push_back(tendon);
  }
  const int n = static_cast<int>(rows.size());
  ASSERT_EQ(n, 48);
  const Dense A = constraintSystem(n, dofs, rows, 1e-9, rng);
  SparseLdlt ldlt;
  load(ldlt, A, GetParam());
  EXPECT_EQ(ldlt.factor(1e-13), 0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector b(n);
  for (int k = 0; k < n; ++k) b[k] = u(rng);
  const Vector x = solve(ldlt, b), reference = A.ldlt().solve(b);
  // Both backward stable: they agree to the condition number times rounding.
  const double condition = A.norm() * A.inverse().norm();
  EXPECT_LE((x - reference).norm(), 1e-15 * condition * reference.norm());
  EXPECT_LE((A * x - b).norm(), 1e-13 * A.norm() * x.norm());
}

// A long chain (Hilbert's wheels: each span's row shares a wheel with the
// next), 1000 rows: every row kept and solved, its condition near n^2.
TEST_P(Factorization, SolvesALongChain) {
  std::mt19937 rng(11);
  const int n = 1000;
  // A span between wheels r and r + 1 turns them opposite ways, by their
  // radii (0.5 to 1 m); the wheels' inertias 0.5 to 2.
  std::uniform_real_distribution<double> radius(0.5, 1.0), inertia(0.5, 2.0);
  Dense J = Dense::Zero(n, n + 1);
  for (int r = 0; r < n; ++r) J(r, r) = radius(rng), J(r, r + 1) = -radius(rng);
  Vector w(n + 1);
  for (int d = 0; d <= n; ++d) w[d] = 1.0 / inertia(rng);
  Dense A = Dense::Zero(n, n);  // J W J^T, tridiagonal (its dense product is slow under the sanitizers)
  for (int r = 0; r < n; ++r) {
    A(r, r) = J(r, r) * J(r, r) * w[r] + J(r, r + 1) * J(r, r + 1) * w[r + 1];
    if (r + 1 < n) A(r, r + 1) = A(r + 1, r) = J(r, r + 1) * w[r + 1] * J(r + 1, r + 1);
  }
  SparseLdlt ldlt;
  load(ldlt, A, GetParam());
  EXPECT_EQ(ldlt.factor(1e-13), 0);
  Vector b = Vector::LinSpaced(n, -1.0, 1.0);
  const Vector x = solve(ldlt, b);
  EXPECT_LE((A * x - b).norm(), 1e-13 * A.norm() * x.norm());
}

// Six rows on twelve unknowns, five random on overlapping pairs of bodies
// and the sixth row 1 less 2 times row 3 (a belt's last span repeating the
// others), off that by `off` in one entry.
Dense beltJacobian(unsigned seed, double off) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Dense J = Dense::Zero(6, 12);
  for (int r = 0; r < 5; ++r)
    for (int d = 2 * r; d < 2 * r + 4; ++d) J(r, d) = u(rng);
  J.row(5) = J.row(1) - 2.0 * J.row(3);
  J(5, 2) += off;
  return J;
}

// A belt's last span repeats the others (its row the sum of two): the pivot
// is rounding's, the row dropped and its unknown 0; the rest still meet a
// consistent right-hand side, and L^T z = e_k gives the dependency, A z = 0.
TEST_P(Factorization, DropsADependentRowAndGivesItsDependency) {
  const Dense J = beltJacobian(3, 0.0), A = J * J.transpose();
  SparseLdlt ldlt;
  load(ldlt, A, GetParam());
  ASSERT_EQ(ldlt.factor(1e-13), 1);
  int k = -1;
  for (int r = 0; r < 6; ++r)
    if (ldlt.dropped(r)) k = r;
  ASSERT_EQ(k, 5);  // the last of the dependent set, in elimination order
  EXPECT_LT(std::abs(ldlt.pivotRatio(k)), 1e-13);
  const Vector y = Vector::LinSpaced(6, 1.0, 2.0);
  const Vector b = A * y;  // in A's range
  const Vector x = solve(ldlt, b);
  EXPECT_EQ(x[k], 0.0);
  EXPECT_LE((A * x - b).norm(), 1e-13 * A.norm() * x.norm());
  Vector z = Vector::Unit(6, k);
  ldlt.solveTransposed(z.data());
  EXPECT_EQ(z[k], 1.0);
  EXPECT_LE((A * z).norm(), 1e-13 * A.norm() * z.norm());
  // Row 5 = row 1 - 2 row 3: J^T z = 0 for z = e_5 - e_1 + 2 e_3.
  const Vector dependency = (Vector(6) << 0.0, -1.0, 0.0, 2.0, 0.0, 1.0).finished();
  EXPECT_LE((z - dependency).norm(), 1e-12);
}

// Nearly dependent is not dependent: a row 1e-4 off the sum of two others
// leaves a pivot ratio near 1e-10, far above rounding's 1e-16, and is kept
// (the light wheel between heavy loads of active_set.cpp); `keep` keeps a
// row whose ratio the drop tolerance would have dropped.
TEST_P(Factorization, KeepsANearlyDependentRow) {
  const Dense J = beltJacobian(5, 1e-4), A = J * J.transpose();
  SparseLdlt ldlt;
  load(ldlt, A, GetParam());
  EXPECT_EQ(ldlt.factor(1e-13), 0);
  EXPECT_GT(ldlt.pivotRatio(5), 1e-12);
  EXPECT_LT(ldlt.pivotRatio(5), 1e-8);
  const Vector b = Vector::LinSpaced(6, -1.0, 1.0);
  const Vector x = solve(ldlt, b);
  EXPECT_LE((A * x - b).norm(), 1e-13 * A.norm() * x.norm());  // backward stable, however ill-conditioned
  // A drop tolerance above its ratio drops it; kept, the row stays.
  EXPECT_EQ(ldlt.factor(1e-6), 1);
  std::vector<char> keep(6, 0);
  keep[5] = 1;
  EXPECT_EQ(ldlt.factor(1e-6, keep, 1e-13), 0);
}

// [S B; B^T -M] (S, M positive definite: Vanderbei 1995) in an interleaved
// order: an LDL^T exists in any order, its pivots negative exactly at M's
// unknowns, which setNegativePivots names.
TEST_P(Factorization, FactorsAQuasiDefiniteMatrixWithItsNegativePivots) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 10;
  Dense A = Dense::Zero(n, n);
  std::vector<char> negative(n, 0);
  for (int k = 1; k < n; k += 3) negative[k] = 1;  // M's unknowns, among S's
  for (int i = 0; i < n; ++i)
    for (int k = i; k < n && k <= i + 3; ++k) A(i, k) = A(k, i) = (negative[i] == negative[k] ? 0.3 : 1.0) * u(rng);
  for (int i = 0; i < n; ++i) {  // S and M diagonally dominant
    double off = 0.0;
    for (int k = 0; k < n; ++k)
      if (k != i && negative[k] == negative[i]) off += std::abs(A(i, k));
    A(i, i) = (negative[i] ? -1.0 : 1.0) * (off + 0.5);
  }
  SparseLdlt ldlt;
  load(ldlt, A, GetParam());
  ldlt.setNegativePivots(negative);
  ASSERT_EQ(ldlt.factor(1e-13), 0);
  for (int k = 0; k < n; ++k) EXPECT_GT(ldlt.pivotRatio(k), 1e-3) << k;  // each pivot's sign as named
  const Vector b = Vector::LinSpaced(n, 1.0, -1.0);
  const Vector x = solve(ldlt, b), reference = A.fullPivLu().solve(b);
  EXPECT_LE((x - reference).norm(), 1e-12 * reference.norm());
  // Unnamed, M's pivots are negative where positive ones were expected:
  // dropped, as a dependent row's would be.
  ldlt.setNegativePivots(std::vector<char>(n, 0));
  EXPECT_GT(ldlt.factor(1e-13), 0);
}

INSTANTIATE_TEST_SUITE_P(Layouts, Factorization, ::testing::Values(Layout::Rows, Layout::Supernodes),
                         [](const ::testing::TestParamInfo<Layout>& info) {
                           return info.param == Layout::Rows ? std::string("Rows") : std::string("Supernodes");
                         });

// Random systems of the solver's kind, in random elimination orders: rows
// on one or two of a few bodies, some made identity rows (a row fixed or
// off in the active set: its entries 0, its diagonal 1), some the exact
// sum of two others (a belt's last span). Both layouts drop the same rows
// and solve alike, to rounding against the system's condition.
TEST(SparseLdlt, BothLayoutsDropTheSameRowsAndSolveAlike) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int bodies = 2 + trial % 7, n = 4 + trial % 45;
    Dense J = Dense::Zero(n, 6 * bodies);
    for (int r = 0; r < n; ++r) {
      const int a = static_cast<int>(unit(rng) * bodies), b = static_cast<int>(unit(rng) * bodies);
      for (const int body : {a, b})
        for (int d = 0; d < 6; ++d) J(r, 6 * body + d) = u(rng);
    }
    const bool dependent = trial % 3 == 0 && n > 4;
    if (dependent) J.row(n - 1) = J.row(0) + J.row(1);
    Dense A = J * J.transpose();
    if (!dependent) A.diagonal().array() += 1e-9;
    if (trial % 4 == 1)
      for (int k = 2; k < n - 1; k += 5) {
        A.row(k).setZero();
        A.col(k).setZero();
        A(k, k) = 1.0;
      }
    std::vector<int> order(n);
    for (int k = 0; k < n; ++k) order[k] = k;
    std::shuffle(order.begin(), order.end(), rng);
    Dense P = Dense::Zero(n, n);
    for (int k = 0; k < n; ++k) P(k, order[k]) = 1.0;
    const Dense B = P * A * P.transpose();
    SparseLdlt rows, supernodes;
    load(rows, B, Layout::Rows);
    load(supernodes, B, Layout::Supernodes);
    const int dropped = rows.factor(1e-13);
    ASSERT_EQ(dropped, supernodes.factor(1e-13)) << trial;
    for (int k = 0; k < n; ++k) ASSERT_EQ(rows.dropped(k), supernodes.dropped(k)) << trial << " " << k;
    Vector b(n);
    for (int k = 0; k < n; ++k) b[k] = u(rng);
    if (dependent) {  // a right-hand side in B's range, met by both
      b = B * b;
      EXPECT_GT(dropped, 0) << trial;  // the sum of two rows: rounding's pivot
      for (const SparseLdlt* ldlt : {&rows, &supernodes}) {
        const Vector x = solve(*ldlt, b);
        EXPECT_LE((B * x - b).norm(), 1e-12 * B.norm() * x.norm()) << trial;
      }
      continue;
    }
    const Vector x = solve(rows, b), y = solve(supernodes, b);
    const double condition = B.norm() * B.inverse().norm();
    EXPECT_LE((x - y).norm(), 1e-14 * condition * x.norm()) << trial;
    Vector z = b, w = b;
    rows.solveTransposed(z.data());
    supernodes.solveTransposed(w.data());
    EXPECT_LE((z - w).norm(), 1e-14 * condition * z.norm()) << trial;
  }
}

// Left to choose, a chain factors row by row (each column of L one entry:
// no block to gain) and a dense system, the rows of a finger that all share
// its bodies, by supernodes (one block of 24 columns; DESIGN, "Supernodes
// for the hand").
TEST(SparseLdlt, ChoosesSupernodesForADenseSystemAndRowsForAChain) {
  std::mt19937 rng(7);
  const int n = 24;
  std::vector<std::vector<int>> rows(n);
  for (int r = 0; r < n; ++r)
    for (int d = 0; d < 18; ++d) rows[r].push_back(d);  // three bodies, every row on all of them
  SparseLdlt ldlt;
  load(ldlt, constraintSystem(n, 18, rows, 1e-9, rng), Layout::Automatic);
  EXPECT_EQ(ldlt.layout(), Layout::Supernodes);
  Dense chain = Dense::Identity(100, 100) * 2.0;
  for (int r = 0; r + 1 < 100; ++r) chain(r, r + 1) = chain(r + 1, r) = -1.0;
  load(ldlt, chain, Layout::Automatic);
  EXPECT_EQ(ldlt.layout(), Layout::Rows);
}

}  // namespace
}  // namespace reeve::test_sparse_ldlt
