// MuJoCo models (MJCF XML) read as Reeve scenes: bodies, joints and
// spatial tendons, the tendons' wrap cylinders as pulleys that may turn
// (scenes/README.md, "MuJoCo models", has the mapping element by element).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace reeve {

/// What a tendon's wrap cylinder becomes. Fixed: a pulley welded to its
/// body that the tendon slides over without friction (mu 0), as MuJoCo's
/// wrap is. Turning: a wheel hinged on the cylinder's axis, with the
/// geom's mass, that the tendon turns without slipping.
enum class MjcfWheels { Fixed, Turning };

struct MjcfOptions {
  MjcfWheels wheels = MjcfWheels::Fixed;
  /// Actuator name -> its control (MuJoCo's ctrl), held constant while the
  /// scene runs (clamped to its ctrlrange); an actuator not named here has
  /// control 0, as MuJoCo's at rest.
  std::map<std::string, double> controls;
};

/// A model read: the scene (scene.schema.json) as JSON text, and one line
/// for each element or attribute of the model that the scene does not
/// carry ("FILE:LINE: <tag name="...">: what and why"), never dropped
/// silently.
struct MjcfImport {
  std::string scene_json;
  std::vector<std::string> unmapped;
};

/// Reads the MJCF file at `path` (and the files its <include>s name,
/// relative to it). Throws SceneError (scene.h) as "FILE:LINE: <tag>:
/// expected EXPECTED, got FOUND" for a malformed file (or one not in
/// UTF-8), a reference to an element that does not exist, or a model Reeve
/// cannot build (a jointed body without mass or moments of inertia), and as
/// loadScene does for a file it cannot read.
MjcfImport importMjcf(const std::filesystem::path& path, const MjcfOptions& options = {});

/// Whether `path` names an MJCF model: its extension is .xml (any case).
/// loadScene() imports such a file with the default options.
bool isMjcfPath(const std::filesystem::path& path);

}  // namespace reeve
