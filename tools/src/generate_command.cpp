#include "generate_command.h"

#include <fstream>
#include <iostream>

#include "commands.h"
#include "reeve/machines/scene_json.h"

namespace reeve {

int generateHilbertCommand(const GenerateHilbertOptions& options) {
  namespace fs = std::filesystem;
  machines::HilbertSpec spec = machines::hilbertSceneSpec(options.level, options.slack_m);
  if (options.end == "brake") spec.brake_torque_Nm = 10.0;
  if (options.end == "load") spec.brake_torque_Nm = 0.0;
  if (options.wheel_kg > 0.0) spec.wheel_kg = options.wheel_kg;
  const nlohmann::ordered_json doc = machines::hilbertSceneJson(spec);
  const fs::path out = options.output.empty() ? fs::path(doc["name"].get<std::string>() + ".json") : options.output;
  if (fs::exists(out) && !options.force) {
    std::cerr << "reeve: " << out.string() << " exists; pass --force to replace it\n";
    return kExitWouldOverwrite;
  }
  std::ofstream file(out);
  file << machines::sceneFileText(doc);
  file.close();
  if (!file) {
    std::cerr << "reeve: cannot write " << out.string() << '\n';
    return kExitFailure;
  }
  const std::size_t wheels = doc["hinges"].size(), links = doc["cables"][0]["links"].size();
  std::cout << "wrote " << out.string() << " (" << wheels << " wheels, " << links - 1 << " cable joints)\n";
  return 0;
}

}  // namespace reeve
