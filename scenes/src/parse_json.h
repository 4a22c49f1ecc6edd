// Strict JSON text -> document, with positions for syntax errors.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace reeve::scene_detail {

/// Parses RFC 8259 JSON (no comments, no trailing commas). Throws
/// SceneError::syntax with the 1-based line and column (in characters) for
/// a syntax error or a number too large for a double, and a SceneError at
/// the key's JSON pointer for a key repeated in one object (which a plain
/// parse would silently resolve to the last value).
nlohmann::json parseJson(const std::string& text, const std::string& source);

}  // namespace reeve::scene_detail
