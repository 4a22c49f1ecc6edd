// Numbers in a scene: integers written with a fraction ("10.0"), and
// numbers too large to simulate in double precision.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace reeve::scene_detail {

/// Largest magnitude a number in a scene may have: a vector of three of
/// them still has a finite squared length (3 x 1e306 < 1.8e308), and so do
/// the energies and distances the engine squares.
inline constexpr double kMaxSceneMagnitude = 1e153;

/// Turns every number with no fractional part written as a float ("10.0",
/// "1e3") into an integer, as JSON Schema (draft 6 on) counts it, so that
/// integer settings accept it; only up to 2^53, where doubles are exact.
void integralNumbersAsIntegers(nlohmann::json& document);

/// Throws SceneError at the first number (in document order) whose
/// magnitude exceeds kMaxSceneMagnitude, naming its JSON path.
void refuseHugeNumbers(const nlohmann::json& document, const std::string& source);

}  // namespace reeve::scene_detail
