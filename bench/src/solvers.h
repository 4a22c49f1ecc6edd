// Solver names on the bench's command line (the scene format's).
#pragma once

#include <stdexcept>
#include <string>

#include "reeve/scene/scene.h"

namespace reeve::bench {

/// The solver called `name` ("direct" or "gauss-seidel"); throws
/// std::invalid_argument for another name.
inline SolverKind solverKind(const std::string& name) {
  if (const auto kind = solverMethodFromName(name)) return *kind;
  throw std::invalid_argument("unknown solver '" + name + "', expected direct or gauss-seidel");
}

}  // namespace reeve::bench
