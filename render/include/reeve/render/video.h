// H.264 video output through the `ffmpeg` program.
#pragma once

#include <filesystem>
#include <string>

#include <sys/types.h>

#include "reeve/render/image.h"

namespace reeve {

/// Streams frames as raw RGB into an `ffmpeg` child process that encodes
/// them with libx264, pixel format yuv420p, at a constant frame rate.
class VideoWriter {
 public:
  /// Starts ffmpeg writing `path` (replaced if it exists; the container
  /// follows the extension, e.g. .mp4) for frames of width x height pixels
  /// at `fps` frames per second. Throws std::invalid_argument unless width
  /// and height are positive and even (yuv420p) and fps > 0, and
  /// std::runtime_error if ffmpeg is not on PATH or cannot be started.
  VideoWriter(const std::filesystem::path& path, int width, int height, double fps);
  /// Finishes if not yet finished; never throws (a failure is lost: call
  /// finish() to see it).
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Appends one frame. Throws std::invalid_argument if its size differs
  /// from the video's, std::logic_error after finish(), and
  /// std::runtime_error (with ffmpeg's exit status) if ffmpeg has quit.
  void add(const Image& frame);

  /// Closes the stream and waits for ffmpeg. Throws std::runtime_error with
  /// ffmpeg's exit status if it failed. Further calls do nothing.
  void finish();

 private:
  /// Closes the stream, reaps ffmpeg and returns "" on success, else why
  /// it failed.
  std::string closeAndWait();

  std::filesystem::path path_;
  int width_, height_;
  int stream_ = -1;  // our end of ffmpeg's stdin; -1 once closed
  pid_t child_ = -1;
};

}  // namespace reeve
