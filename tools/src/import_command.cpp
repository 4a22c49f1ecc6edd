#include "import_command.h"

#include <cstdio>
#include <iostream>

#include "commands.h"
#include "output_file.h"
#include "reeve/scene/scene.h"
#include "reeve/scene/warnings.h"

namespace reeve {

int importCommand(const ImportCommandOptions& options) {
  namespace fs = std::filesystem;
  const fs::path& out = options.output;
  if (!out.empty() && fs::exists(out) && !options.force && !isStream(out)) {
    std::cerr << "reeve: " << out.string() << " exists; pass --force to replace it\n";
    return kExitWouldOverwrite;
  }
  MjcfImport model;
  try {
    model = importMjcf(options.model, options.mjcf);
    Scene scene = parseScene(model.scene_json, options.model.string());  // what `reeve run` will build
    scene.not_imported = model.unmapped;
    for (const SceneWarning& w : sceneWarnings(scene))
      std::fprintf(stderr, "reeve: warning: %s: %s: %s\n", options.model.string().c_str(), w.json_path.c_str(),
                   w.message.c_str());
  } catch (const SceneError& e) {
    std::cerr << "reeve: " << e.what() << '\n';
    return kExitBadScene;
  }
  if (out.empty()) {
    std::cout << model.scene_json << '\n';
    return std::cout.flush() ? 0 : kExitFailure;
  }
  try {
    OutputFile file(out, options.force);
    file.write(model.scene_json + "\n");
    file.close();
    file.commit();
  } catch (const std::runtime_error& e) {
    std::cerr << "reeve: " << e.what() << '\n';
    return kExitFailure;
  }
  std::cerr << "reeve: wrote " << out.string() << '\n';
  return 0;
}

}  // namespace reeve
