// Words for error messages: how a JSON value, a name or a path reads in a
// SceneError's "expected ..., got ..." (scenes/README.md, Errors).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace reeve::scene_detail {

/// The value with its kind, for type errors: `a string ("abc")`,
/// `a number (2.5)`, `an integer (3)`, `true`, `null`, `an object`,
/// `an array of 2 items`.
std::string describe(const nlohmann::json& value);

/// The value as written, for values whose kind is right: `-0.5`, `"wheell"`,
/// `[0,0,0]`; long text is shortened with "...".
std::string literal(const nlohmann::json& value);

/// `text` as a JSON string literal: `"wheel_left"`.
std::string quote(const std::string& text);

/// Shortest text that reads back as `value`: 0.1 -> "0.1", 60.0 -> "60".
std::string number(double value);

/// "a, b, c" (at most `max` names, then ", ...").
std::string nameList(const std::vector<std::string>& names, std::size_t max = 8);

/// `pointer` extended by one reference token, escaped per RFC 6901
/// ("~" -> "~0", "/" -> "~1").
std::string childPointer(const std::string& pointer, const std::string& token);

}  // namespace reeve::scene_detail
