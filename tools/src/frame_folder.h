// PNG frames of a run that appear all together or not at all.
#pragma once

#include <filesystem>

#include "reeve/render/image.h"

namespace reeve {

/// The folder `reeve run --png DIR` writes frame_00000.png, ... into. Frames
/// go to a hidden folder inside DIR (".reeve-PID-XXXXXXXX", same file
/// system) and commit() moves them into DIR once the run ended well; a
/// failed run removes them, and DIR too if the run created it, so DIR
/// holds the complete frames of a run or nothing new. Errors throw
/// std::runtime_error naming the file.
class FrameFolder {
 public:
  /// Creates DIR (and its parents) if missing, and the hidden folder.
  /// `replace` (--force): commit() replaces older frames of the same
  /// names and removes older frames numbered beyond this run's last one.
  FrameFolder(std::filesystem::path dir, bool replace);
  ~FrameFolder();
  FrameFolder(const FrameFolder&) = delete;
  FrameFolder& operator=(const FrameFolder&) = delete;

  /// DIR/frame_NNNNN.png, the name frame `frame` (0-based) ends up with.
  std::filesystem::path framePath(int frame) const;
  /// Writes frame `frame` (0-based; written in order from 0) into the
  /// hidden folder.
  void write(int frame, const Image& image);
  /// Moves the frames written into DIR.
  void commit();

 private:
  std::filesystem::path dir_, writing_;
  bool replace_ = false, created_dir_ = false;
  int frames_ = 0;
};

/// "frame_00042.png".
std::filesystem::path frameName(int frame);

}  // namespace reeve
