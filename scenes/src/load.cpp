#include <cerrno>
#include <cstdio>
#include <memory>
#include <system_error>

#include "reeve/scene/scene.h"

namespace reeve {

Scene loadScene(const std::filesystem::path& path) {
  const std::string name = path.string();
  const auto unreadable = [&] {
    return SceneError::unreadable(name, std::generic_category().message(errno));
  };
  errno = 0;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(name.c_str(), "rb"),
                                                             &std::fclose);
  if (!file) throw unreadable();
  std::string text;
  char buffer[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, n);
  if (std::ferror(file.get())) throw unreadable();  // e.g. EISDIR for a folder
  return parseScene(text, name);
}

}  // namespace reeve
