#include <cerrno>
#include <cstdio>
#include <memory>
#include <system_error>

#include "reeve/scene/mjcf.h"
#include "reeve/scene/scene.h"
#include "reeve/scene/scene_file.h"

namespace reeve {

std::string readSceneFile(const std::filesystem::path& path) {
  const std::string name = path.string();
  const auto unreadable = [&] {
    return SceneError::unreadable(name, std::generic_category().message(errno));
  };
  // Looked at before opening: opening a FIFO with no writer blocks, and
  // /dev/zero never ends.
  std::error_code status_error;
  const std::filesystem::file_status status = std::filesystem::status(path, status_error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    using std::filesystem::file_type;
    const file_type t = status.type();
    const char* what = t == file_type::directory ? "a folder"
                       : t == file_type::fifo    ? "a FIFO (named pipe)"
                       : t == file_type::character || t == file_type::block ? "a device"
                       : t == file_type::socket ? "a socket"
                                                : "not a file";
    throw SceneError::unreadable(name, std::string(what) + ", not a regular file");
  }
  const auto too_large = [&](std::uintmax_t bytes) {
    return SceneError::unreadable(name, std::to_string(bytes) + " bytes, more than a scene may have (" +
                                            std::to_string(kMaxSceneFileBytes) + ")");
  };
  if (std::filesystem::exists(status)) {
    const std::uintmax_t bytes = std::filesystem::file_size(path, status_error);
    if (!status_error && bytes > kMaxSceneFileBytes) throw too_large(bytes);
  }
  errno = 0;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(name.c_str(), "rb"),
                                                             &std::fclose);
  if (!file) throw unreadable();
  std::string text;
  char buffer[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) {
    text.append(buffer, n);
    if (text.size() > kMaxSceneFileBytes) throw too_large(text.size());  // it grew while read
  }
  if (std::ferror(file.get())) throw unreadable();
  return text;
}

std::string sceneJsonOf(const std::filesystem::path& path) {
  return isMjcfPath(path) ? importMjcf(path).scene_json : readSceneFile(path);
}

Scene loadScene(const std::filesystem::path& path) {
  if (!isMjcfPath(path)) return parseScene(readSceneFile(path), path.string());
  MjcfImport model = importMjcf(path);
  Scene scene = parseScene(model.scene_json, path.string());
  scene.not_imported = std::move(model.unmapped);
  return scene;
}

}  // namespace reeve
