#include "describe.h"

#include <charconv>

namespace reeve::scene_detail {
namespace {

constexpr std::size_t kMaxLiteral = 60;  // characters of a value quoted in a message

std::string shortened(std::string text) {
  if (text.size() <= kMaxLiteral) return text;
  return text.substr(0, kMaxLiteral - 3) + "...";
}

}  // namespace

std::string describe(const nlohmann::json& value) {
  using Type = nlohmann::json::value_t;
  switch (value.type()) {
    case Type::null:
      return "null";
    case Type::boolean:
      return value.get<bool>() ? "true" : "false";
    case Type::string:
      return "a string (" + literal(value) + ")";
    case Type::number_integer:
    case Type::number_unsigned:
      return "an integer (" + literal(value) + ")";
    case Type::number_float:
      return "a number (" + literal(value) + ")";
    case Type::object:
      return "an object";
    case Type::array:
      return "an array of " + std::to_string(value.size()) +
             (value.size() == 1 ? " item" : " items");
    default:
      return "a value of an unexpected kind";
  }
}

std::string literal(const nlohmann::json& value) {
  return shortened(value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

std::string quote(const std::string& text) { return literal(nlohmann::json(text)); }

std::string number(double value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

std::string nameList(const std::vector<std::string>& names, std::size_t max) {
  std::string list;
  for (std::size_t i = 0; i < names.size() && i < max; ++i) list += (i ? ", " : "") + names[i];
  if (names.size() > max) list += ", ...";
  return list;
}

std::string childPointer(const std::string& pointer, const std::string& token) {
  std::string escaped;
  for (const char c : token) {
    if (c == '~')
      escaped += "~0";
    else if (c == '/')
      escaped += "~1";
    else
      escaped += c;
  }
  return pointer + "/" + escaped;
}

}  // namespace reeve::scene_detail
