// Numbers too large to simulate in double precision.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace reeve::scene_detail {

/// Largest magnitude a number in a scene may have: a vector of three of
/// them still has a finite squared length (3 x 1e306 < 1.8e308), and so do
/// the energies and distances the engine squares.
inline constexpr double kMaxSceneMagnitude = 1e153;

/// Throws SceneError at the first number (in document order) whose
/// magnitude exceeds kMaxSceneMagnitude, naming its JSON path.
void refuseHugeNumbers(const nlohmann::json& document, const std::string& source);

}  // namespace reeve::scene_detail
