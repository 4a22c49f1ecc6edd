// A structure-aware libFuzzer mutator for scene files (issue 27): a
// mutation parses the input as JSON and changes its values and structure
// (numbers to edge values, strings to names and schema words, members and
// elements deleted, copied, repeated, moved and nested), so that most
// mutants are scenes that reach past the schema into building and
// stepping; inputs that are not JSON get libFuzzer's byte mutations.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace reeve::fuzz {

/// Rewrites `text` (a JSON document) by one to three structural mutations
/// drawn from `seed`; returns false, leaving `text` as it was, if it is not
/// JSON that the mutator walks (more than 256 levels deep, say) or the
/// result would be larger than `max_size` bytes.
bool mutateScene(std::string& text, std::size_t max_size, unsigned seed);

}  // namespace reeve::fuzz
