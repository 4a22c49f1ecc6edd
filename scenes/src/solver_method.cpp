// Names of the solver methods in scene files and on the command line.
#include "reeve/scene/scene.h"

namespace reeve {

const char* solverMethodName(SolverKind method) {
  return method == SolverKind::Direct ? "direct" : "gauss-seidel";
}

std::optional<SolverKind> solverMethodFromName(std::string_view name) {
  if (name == "direct") return SolverKind::Direct;
  if (name == "gauss-seidel") return SolverKind::GaussSeidel;
  return std::nullopt;
}

}  // namespace reeve
