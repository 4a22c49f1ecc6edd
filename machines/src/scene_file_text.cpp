#include <string>

#include "reeve/machines/scene_json.h"

namespace reeve::machines {
namespace {

void write(const nlohmann::ordered_json& value, int indent, std::string& text) {
  const std::string flat = value.dump();
  if (!value.is_structured() || value.empty() || indent + flat.size() <= 200) {
    text += flat;
    return;
  }
  const bool object = value.is_object();
  text += object ? "{\n" : "[\n";
  bool first = true;
  for (auto it = value.begin(); it != value.end(); ++it) {
    if (!first) text += ",\n";
    first = false;
    text.append(indent + 2, ' ');
    if (object) text += nlohmann::ordered_json(it.key()).dump() + ": ";
    write(*it, indent + 2, text);
  }
  text += '\n';
  text.append(indent, ' ');
  text += object ? '}' : ']';
}

}  // namespace

std::string sceneFileText(const nlohmann::ordered_json& doc) {
  std::string text;
  write(doc, 0, text);
  return text + "\n";
}

}  // namespace reeve::machines
