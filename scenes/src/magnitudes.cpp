#include "magnitudes.h"

#include <cmath>
#include <cstdint>

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

void integralNumbersAsIntegers(nlohmann::json& document) {
  if (document.is_number_float()) {
    const double x = document.get<double>();
    if (std::trunc(x) == x && std::abs(x) <= 9007199254740992.0) document = static_cast<std::int64_t>(x);
  } else if (document.is_structured()) {
    for (nlohmann::json& item : document) integralNumbersAsIntegers(item);
  }
}

void refuseHugeNumbers(const nlohmann::json& document, const std::string& source) { walk(document, "", source); }

}  // namespace reeve::scene_detail
