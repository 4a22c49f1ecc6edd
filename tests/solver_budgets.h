// The solver budgets the winch and break tests run at: both solvers, many
// substeps of one iteration and the paper's one step of ten iterations.
#pragma once

#include <string>

#include "reeve/engine/world.h"

namespace reeve::test {

struct Budget {
  SolverKind solver;
  int substeps, iterations;
};
inline constexpr Budget kBudgets[] = {{SolverKind::Direct, 20, 1}, {SolverKind::Direct, 1, 10},
                                      {SolverKind::GaussSeidel, 20, 1}, {SolverKind::GaussSeidel, 1, 10}};
inline std::string name(const Budget& b) {
  return std::string(b.solver == SolverKind::Direct ? "direct " : "gauss-seidel ") + std::to_string(b.substeps) +
         " x " + std::to_string(b.iterations);
}

}  // namespace reeve::test
