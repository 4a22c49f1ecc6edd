#include <utility>

#include "reeve/scene/scene.h"

namespace reeve {

namespace {

std::string message(const std::string& file, const std::string& json_path,
                    const std::string& expected, const std::string& found) {
  return file + ": " + (json_path.empty() ? "(root)" : json_path) + ": expected " + expected +
         ", got " + found;
}

}  // namespace

SceneError::SceneError(std::string file, std::string json_path, std::string expected,
                       std::string found)
    : std::runtime_error(message(file, json_path, expected, found)),
      file_(std::move(file)),
      json_path_(std::move(json_path)),
      expected_(std::move(expected)),
      found_(std::move(found)) {}

SceneError SceneError::syntax(std::string file, int line, int column, std::string reason) {
  const std::string what = file + ":" + std::to_string(line) + ":" + std::to_string(column) +
                           ": invalid JSON: " + reason;
  return SceneError(what, std::move(file), "", "valid JSON", std::move(reason), line, column);
}

SceneError SceneError::unreadable(std::string file, std::string reason) {
  const std::string what = file + ": cannot read: " + reason;
  return SceneError(what, std::move(file), "", "a readable file", std::move(reason), 0, 0);
}

SceneError SceneError::atLine(std::string file, int line, std::string element, std::string expected,
                              std::string found) {
  const std::string what =
      file + ":" + std::to_string(line) + ": " + element + ": expected " + expected + ", got " + found;
  return SceneError(what, std::move(file), std::move(element), std::move(expected), std::move(found), line, 0);
}

SceneError::SceneError(const std::string& what, std::string file, std::string json_path,
                       std::string expected, std::string found, int line, int column)
    : std::runtime_error(what),
      file_(std::move(file)),
      json_path_(std::move(json_path)),
      expected_(std::move(expected)),
      found_(std::move(found)),
      line_(line),
      column_(column) {}

}  // namespace reeve
