#include "parse_json.h"

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include "describe.h"
#include "reeve/engine/fp_exceptions.h"
#include "reeve/scene/scene.h"

namespace reeve::scene_detail {
namespace {

using nlohmann::json;

// A limit of scene.h (kMaxSceneDepth ...) passed at `pointer`.
struct LimitPassed {
  std::string pointer, expected, found;
};

// SAX handler (nlohmann::json::sax_parse) that builds the document like the
// standard parser but stops at the first repeated key or passed limit
// (kMaxSceneDepth, ...: so that no later walk over the document, nor its
// destructor, can meet a million nested arrays), and keeps the byte
// position of a syntax error.
class DocumentBuilder {
 public:
  bool null() { return add(nullptr); }
  bool boolean(bool b) { return add(b); }
  bool number_integer(json::number_integer_t n) { return add(n); }
  bool number_unsigned(json::number_unsigned_t n) { return add(n); }
  bool number_float(json::number_float_t n, const std::string&) { return add(n); }
  bool string(std::string& s) {
    if (s.size() > kMaxSceneStringBytes) return refuse(nextPointer(), stringLimit(), bytes(s.size()));
    return add(std::move(s));
  }
  bool binary(json::binary_t& b) { return add(json::binary(std::move(b))); }
  bool start_object(std::size_t) { return open(json::object()); }
  bool end_object() { return close(); }
  bool start_array(std::size_t) { return open(json::array()); }
  bool end_array() { return close(); }

  bool key(std::string& k) {
    if (k.size() > kMaxSceneStringBytes)
      return refuse(openPointer(), stringLimit() + " (keys too)", "a key of " + bytes(k.size()));
    if (open_.back()->contains(k)) {
      repeated_key_ = k;
      return false;
    }
    if (open_.back()->size() == kMaxSceneObjectMembers)
      return refuse(openPointer(), "at most " + std::to_string(kMaxSceneObjectMembers) + " keys in an object",
                    "more");
    key_ = std::move(k);
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const json::exception& e) {
    error_position_ = position;
    error_ = e.what();
    return false;
  }

  json& document() { return root_; }
  const std::optional<std::string>& repeatedKey() const { return repeated_key_; }
  const std::optional<LimitPassed>& limitPassed() const { return limit_passed_; }
  std::size_t errorPosition() const { return error_position_; }
  const std::string& error() const { return error_; }

  /// JSON pointer of the innermost open container.
  std::string openPointer() const {
    std::string pointer;
    for (const std::string& token : tokens_) pointer = childPointer(pointer, token);
    return pointer;
  }

 private:
  // Where the next value goes: the root, the end of the open array, or the
  // open object under the last key.
  json* place(json value) {
    if (open_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    json& parent = *open_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(value));
      return &parent.back();
    }
    json& slot = parent[key_];
    slot = std::move(value);
    return &slot;
  }
  bool add(json value) {
    if (!roomInArray()) return false;
    place(std::move(value));
    return true;
  }
  bool open(json container) {
    if (!roomInArray()) return false;
    if (open_.size() == static_cast<std::size_t>(kMaxSceneDepth))
      return refuse(nextPointer(),
                    "arrays and objects nested at most " + std::to_string(kMaxSceneDepth) + " deep",
                    "one more level");
    if (!open_.empty())
      tokens_.push_back(open_.back()->is_array() ? std::to_string(open_.back()->size()) : key_);
    open_.push_back(place(std::move(container)));
    return true;
  }
  // Whether the open array, if one is open, may take another element.
  bool roomInArray() {
    if (open_.empty() || !open_.back()->is_array() || open_.back()->size() < kMaxSceneArrayLength) return true;
    return refuse(nextPointer(), "at most " + std::to_string(kMaxSceneArrayLength) + " elements in an array",
                  "more");
  }
  // JSON pointer of the value about to be placed.
  std::string nextPointer() const {
    if (open_.empty()) return "";
    const json& parent = *open_.back();
    return childPointer(openPointer(), parent.is_array() ? std::to_string(parent.size()) : key_);
  }
  bool refuse(std::string pointer, std::string expected, std::string found) {
    limit_passed_ = LimitPassed{std::move(pointer), std::move(expected), std::move(found)};
    return false;
  }
  static std::string stringLimit() {
    return "a string of at most " + std::to_string(kMaxSceneStringBytes) + " bytes";
  }
  static std::string bytes(std::size_t n) { return std::to_string(n) + " bytes"; }
  bool close() {
    open_.pop_back();
    if (!tokens_.empty() && open_.size() == tokens_.size()) tokens_.pop_back();
    return true;
  }

  json root_;
  std::vector<json*> open_;          // containers being filled, outermost first
  std::vector<std::string> tokens_;  // pointer tokens of open_[1..] in their parents
  std::string key_;
  std::optional<std::string> repeated_key_;
  std::optional<LimitPassed> limit_passed_;
  std::size_t error_position_ = 0;
  std::string error_;
};

// "[json.exception.parse_error.101] parse error at line 1, column 8: syntax
// error while parsing ..." -> "syntax error while parsing ...".
std::string reasonOf(const std::string& what) {
  std::string reason = what;
  if (reason.rfind("[json.exception.", 0) == 0) reason.erase(0, reason.find("] ") + 2);
  if (reason.rfind("parse error at line ", 0) == 0) reason.erase(0, reason.find(": ") + 2);
  return reason;
}

// Syntax error at 1-based byte `position` (the last byte read): the line,
// and the column counted in UTF-8 characters.
SceneError syntaxError(const std::string& text, std::size_t position, const std::string& reason,
                       const std::string& source) {
  const std::size_t at = std::min(position > 0 ? position - 1 : 0, text.size());
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < at; ++i)
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  int column = 1;
  for (std::size_t i = line_start; i < at; ++i)
    if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++column;
  return SceneError::syntax(source, line, column, reason);
}

}  // namespace

nlohmann::json parseJson(const std::string& text, const std::string& source) {
  DocumentBuilder builder;
  const FloatingPointExceptionsMasked overflow_is_tested;  // strtod overflows on 1e999, an error below
  if (json::sax_parse(text, &builder, json::input_format_t::json, true, false))
    return std::move(builder.document());
  if (const auto& limit = builder.limitPassed())
    throw SceneError(source, limit->pointer, limit->expected, limit->found);
  if (builder.repeatedKey())
    throw SceneError(source, childPointer(builder.openPointer(), *builder.repeatedKey()),
                     "each key at most once in an object",
                     quote(*builder.repeatedKey()) + " a second time");
  throw syntaxError(text, builder.errorPosition(), reasonOf(builder.error()), source);
}

}  // namespace reeve::scene_detail
