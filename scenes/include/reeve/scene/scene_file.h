// Reading a scene file's text, with loadScene's checks, for programs that
// keep the text (`reeve view` reloads and resets from it).
#pragma once

#include <filesystem>
#include <string>

namespace reeve {

/// The text of the scene file at `path`. Throws SceneError (scene.h) as
/// loadScene does: not a regular file (refused before it is opened, so a
/// FIFO cannot block), larger than kMaxSceneFileBytes (also if it grows
/// while read), or unreadable.
std::string readSceneFile(const std::filesystem::path& path);

/// The scene JSON of the file at `path`: its text, or for a MuJoCo model
/// (mjcf.h: isMjcfPath) the scene importMjcf makes of it with the default
/// options. Throws SceneError as loadScene does.
std::string sceneJsonOf(const std::filesystem::path& path);

}  // namespace reeve
