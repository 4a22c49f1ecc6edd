// What the viewer's pages (viewer/: the replay of `reeve run --html` and
// the live page of `reeve view`) are made from: their files, found where
// the program is installed or was built, and a scene's fixed part as the
// pages draw it (viewer/view3d.js).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reeve/scene/scene.h"

namespace reeve {

/// The viewer's files are not where viewerDir() says (not installed).
struct ViewerMissing : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The folder of the viewer's files: $REEVE_VIEWER_DIR if set, else
/// share/reeve/viewer beside an installed program's bin/, else the source
/// tree's viewer/ this program was built from.
std::filesystem::path viewerDir();

/// The bytes of viewerDir() / `name` (e.g. "replay.html",
/// "node_modules/three/build/three.module.min.js"). Throws ViewerMissing,
/// naming the file, `option` (the option that needs it: "--html", "reeve
/// view") and how to install the viewer.
std::string readViewerFile(const std::string& name, const char* option);

/// The viewer's three.js files (from npm; tools/setup.sh installs them),
/// as readViewerFile names them.
inline constexpr const char* kThreeModule = "node_modules/three/build/three.module.min.js";
inline constexpr const char* kOrbitControls = "node_modules/three/examples/jsm/controls/OrbitControls.js";

/// Wrap points on circles at most this far apart (rad) in the pages'
/// cable paths, as in the PNGs.
inline constexpr double kViewerArcStepRad = 0.1;

/// The coils of stored cable on the end spools of cable `c` as the pages
/// draw them (spoolCoil: turns a fiftieth of the spool's radius apart, a
/// full coil at most a fifth of it thick), world points (m).
std::vector<std::vector<Vec3>> viewerSpoolCoils(const CableSystem& cables, int c);

/// A scene's fixed part as viewer/view3d.js draws it: name, description,
/// frame_rate_hz, gravity (m/s^2), camera (or null), bodies (name, shape
/// in metres, dynamic, outlines: the sections its rolling links wrap that
/// its shape does not show, body-local polylines flat x, y, z), cables
/// (name, joints, winch), hinges (the bodies' names, drive: "none",
/// "angle" or "velocity").
nlohmann::json sceneHead(const Scene& scene);

}  // namespace reeve
