#include "frame_folder.h"

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>

#include "output_file.h"

namespace reeve {

namespace fs = std::filesystem;

namespace {

// The frame number of a name frameName() makes, or -1.
long frameNumber(const std::string& name) {
  const std::string prefix = "frame_", suffix = ".png";
  if (name.size() < prefix.size() + 5 + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return -1;
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.size() > 9) return -1;
  for (const char c : digits)
    if (!std::isdigit(static_cast<unsigned char>(c))) return -1;
  return std::stol(digits);
}

}  // namespace

fs::path frameName(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05d.png", frame);
  return name;
}

FrameFolder::FrameFolder(fs::path dir, bool replace) : dir_(std::move(dir)), replace_(replace) {
  created_dir_ = fs::create_directories(dir_);
  static std::mt19937_64 random{std::random_device{}()};
  for (int attempt = 0; attempt < 100; ++attempt) {
    writing_ = dir_ / (".reeve-" + std::to_string(getpid()) + "-" + std::to_string(random() % 100000000));
    if (fs::create_directory(writing_)) return;
  }
  throw std::runtime_error(dir_.string() + ": cannot make a temporary folder in it");
}

FrameFolder::~FrameFolder() {
  std::error_code ec;
  if (!writing_.empty()) fs::remove_all(writing_, ec);
  if (created_dir_) fs::remove(dir_, ec);  // only if still empty
}

fs::path FrameFolder::framePath(int frame) const { return dir_ / frameName(frame); }

void FrameFolder::write(int frame, const Image& image) {
  writePng(writing_ / frameName(frame), image);
  frames_ = frame + 1;
}

void FrameFolder::commit() {
  for (int f = 0; f < frames_; ++f) moveIntoPlace(writing_ / frameName(f), framePath(f), replace_);
  fs::remove(writing_);
  writing_.clear();
  created_dir_ = false;
  if (!replace_) return;
  // --force asked for this run's frames: an older, longer run's later
  // frames would otherwise pass for part of it.
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_))
    if (const long n = frameNumber(entry.path().filename().string()); n >= frames_ && entry.is_regular_file())
      fs::remove(entry.path());
}

}  // namespace reeve
