// The solver budgets the tests run at: both solvers, many substeps of one
// iteration and the paper's one step of ten iterations (winches, breaks);
// the energy ledger's four.
#pragma once

#include <string>
#include <vector>

#include "reeve/engine/world.h"

namespace reeve::test {

struct Budget {
  SolverKind solver;
  int substeps, iterations;
  Projection projection = Projection::End;  // the direct solver's
};
inline constexpr Budget kBudgets[] = {{SolverKind::Direct, 20, 1}, {SolverKind::Direct, 1, 10},
                                      {SolverKind::GaussSeidel, 20, 1}, {SolverKind::GaussSeidel, 1, 10}};
/// The energy ledger's budgets (issue 28): 1 x 1, 1 x 10, 10 x 2 and 32 x 32,
/// both solvers.
inline constexpr Budget kFourBudgets[] = {
    {SolverKind::Direct, 1, 1},       {SolverKind::Direct, 1, 10},       {SolverKind::Direct, 10, 2},
    {SolverKind::Direct, 32, 32},     {SolverKind::GaussSeidel, 1, 1},   {SolverKind::GaussSeidel, 1, 10},
    {SolverKind::GaussSeidel, 10, 2}, {SolverKind::GaussSeidel, 32, 32}};
/// kFourBudgets, and their direct ones again under the start projection.
inline std::vector<Budget> fourBudgetsBothProjections() {
  std::vector<Budget> all(std::begin(kFourBudgets), std::end(kFourBudgets));
  for (const Budget& b : kFourBudgets)
    if (b.solver == SolverKind::Direct) all.push_back({b.solver, b.substeps, b.iterations, Projection::Start});
  return all;
}
/// Default settings (gravity -9.81 m/s^2 along y) at budget `b`.
inline SolverSettings settings(const Budget& b) {
  SolverSettings s;
  s.solver = b.solver;
  s.substeps = b.substeps;
  s.iterations = b.iterations;
  s.projection = b.projection;
  return s;
}
inline std::string name(const Budget& b) {
  return std::string(b.solver == SolverKind::Direct ? "direct " : "gauss-seidel ") + std::to_string(b.substeps) +
         " x " + std::to_string(b.iterations) + (b.projection == Projection::Start ? ", start" : "");
}

}  // namespace reeve::test
