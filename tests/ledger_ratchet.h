// The energy ledger's invariant tests (test_energy_scenes.cpp,
// test_energy_generated.cpp): a list of the cells that create energy
// today, each with its defect, held both ways, so that a fix must take its
// cell off the list and no other cell may start creating energy.
#pragma once

#include <gtest/gtest.h>

#include <cctype>
#include <set>
#include <string>

namespace reeve::test {

/// Fails when `cell` creates energy (`creates`, with `why`) and is not on
/// `known`, or is on it and no longer does.
inline void expectAsListed(const std::set<std::string>& known, const std::string& cell, bool creates,
                           const std::string& why) {
  if (known.count(cell) > 0)
    EXPECT_TRUE(creates) << cell << " no longer creates energy: take it off the list";
  else
    EXPECT_FALSE(creates) << cell << ": " << why;
}

/// `cell` as a gtest parameter name: letters and digits, the rest '_'.
inline std::string parameterName(std::string cell) {
  for (char& ch : cell)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return cell;
}

}  // namespace reeve::test
