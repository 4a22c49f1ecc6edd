#include "segment_command.h"

#include <fstream>
#include <iostream>

#include "commands.h"
#include "reeve/scene/scene_file.h"

namespace reeve {

int segmentCommand(const SegmentCommandOptions& options) {
  namespace fs = std::filesystem;
  const fs::path in = options.scene;
  fs::path out = options.output;
  if (out.empty()) out = in.parent_path() / (in.stem().string() + "_segments.json");
  if (fs::exists(out) && !options.force) {
    std::cerr << "reeve: " << out.string() << " exists; pass --force to replace it\n";
    return kExitWouldOverwrite;
  }
  nlohmann::ordered_json doc;
  try {
    Scene scene = loadScene(in);
    doc = nlohmann::ordered_json::parse(sceneJsonOf(in));  // a MuJoCo model's scene, too
    doc = segmentScene(doc, scene, options.segment);
    // The result must be a valid scene itself.
    parseScene(doc.dump(), out.string());
  } catch (const SceneError& e) {
    std::cerr << "reeve: " << e.what() << '\n';
    return kExitBadScene;
  } catch (const SegmentError& e) {
    std::cerr << "reeve: segment: " << e.what() << '\n';
    return kExitUsage;
  }
  std::ofstream file(out);
  file << doc.dump(2) << '\n';
  file.close();
  if (!file) {
    std::cerr << "reeve: cannot write " << out.string() << '\n';
    return kExitFailure;
  }
  std::cout << "wrote " << out.string() << " (" << options.segment.segments << " segments)\n";
  return 0;
}

}  // namespace reeve
