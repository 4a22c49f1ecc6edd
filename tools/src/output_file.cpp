#include "output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>

namespace reeve {

namespace fs = std::filesystem;

bool isStream(const fs::path& path) {
  std::error_code ec;
  const fs::file_status s = fs::status(path, ec);
  return !ec && (s.type() == fs::file_type::character || s.type() == fs::file_type::fifo);
}

fs::path temporarySibling(const fs::path& path) {
  static std::mt19937_64 random{std::random_device{}()};
  static const char kDigits[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  std::string tag;
  for (int i = 0; i < 8; ++i) tag += kDigits[random() % (sizeof kDigits - 1)];
  // The path made absolute: a name such as "file:x.mp4" must reach ffmpeg
  // as a file, not as a protocol.
  const fs::path absolute = fs::absolute(path);
  std::string name = ".";
  name += absolute.stem().string();
  name += ".reeve-" + std::to_string(getpid()) + "-" + tag;
  name += absolute.extension().string();
  return absolute.parent_path() / name;
}

void moveIntoPlace(const fs::path& from, const fs::path& to, bool replace) {
  // link() refuses an existing target where rename() would replace it. A
  // file system without hard links (vfat) gets a check, then rename().
  int failed = replace ? std::rename(from.c_str(), to.c_str()) : ::link(from.c_str(), to.c_str());
  if (failed != 0 && !replace && errno != EEXIST && !fs::exists(to)) {
    failed = std::rename(from.c_str(), to.c_str());
    if (failed == 0) return;
  }
  if (failed != 0) {
    const int error = errno;
    throw std::runtime_error(to.string() + ": cannot write: " +
                             (error == EEXIST ? std::string("it appeared while the run was writing; pass --force "
                                                            "to overwrite it")
                                              : std::string(std::strerror(error))));
  }
  if (!replace) ::unlink(from.c_str());
}

OutputFile::OutputFile(fs::path path, bool replace) : path_(std::move(path)), replace_(replace) {
  in_place_ = isStream(path_);
  if (in_place_) {
    writing_ = path_;
    file_ = std::fopen(path_.c_str(), "wb");
    if (!file_) fail();
    return;
  }
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    writing_ = temporarySibling(path_);
    fd = ::open(writing_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);  // umask applies
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) fail();
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    const int error = errno;
    ::close(fd);
    ::unlink(writing_.c_str());
    errno = error;
    fail();
  }
}

OutputFile::~OutputFile() {
  if (file_) std::fclose(file_);
  if (!in_place_ && !writing_.empty() && writing_ != path_) ::unlink(writing_.c_str());
}

void OutputFile::fail() const {
  throw std::runtime_error(path_.string() + ": cannot write: " + std::strerror(errno));
}

void OutputFile::write(std::string_view text) {
  if (!file_) throw std::logic_error(path_.string() + ": written after commit()");
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) fail();
}

void OutputFile::close() {
  if (!file_) return;
  const bool flushed = std::fflush(file_) == 0;
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0 || !flushed) fail();
}

void OutputFile::commit() {
  close();
  if (in_place_) return;
  moveIntoPlace(writing_, path_, replace_);
  writing_.clear();
}

}  // namespace reeve
