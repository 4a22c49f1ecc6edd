#include "magnitudes.h"

#include <cmath>

#include "describe.h"
#include "reeve/scene/scene.h"

namespace reeve::scene_detail {
namespace {

void walk(const nlohmann::json& value, const std::string& pointer, const std::string& source) {
  if (value.is_number()) {
    if (std::abs(value.get<double>()) > kMaxSceneMagnitude)
      throw SceneError(source, pointer, "a number of magnitude at most 1e153 (its square must be finite)",
                       literal(value));
  } else if (value.is_object()) {
    for (const auto& item : value.items()) walk(item.value(), childPointer(pointer, item.key()), source);
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) walk(value[i], pointer + "/" + std::to_string(i), source);
  }
}

}  // namespace

void refuseHugeNumbers(const nlohmann::json& document, const std::string& source) { walk(document, "", source); }

}  // namespace reeve::scene_detail
