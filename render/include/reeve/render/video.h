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
  /// Errors name the video `shown_as` (the user's name for it, when
  /// `path` is a temporary stand-in; empty: `path`), also inside what
  /// ffmpeg said.
  VideoWriter(const std::filesystem::path& path, int width, int height, double fps,
              const std::filesystem::path& shown_as = {});
  /// Finishes if not yet finished; never throws (a failure is lost: call
  /// finish() to see it).
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Appends one frame. Throws std::invalid_argument if its size differs
  /// from the video's, std::logic_error after finish(), and
  /// std::runtime_error if ffmpeg has quit: "cannot write the video
  /// 'NAME': REASON (ffmpeg, exit status N)", REASON what ffmpeg said.
  void add(const Image& frame);

  /// Closes the stream and waits for ffmpeg. Throws std::runtime_error as
  /// add() if it failed. Further calls do nothing.
  void finish();

 private:
  /// Closes the stream, reaps ffmpeg and returns "" on success, else the
  /// error message add() and finish() throw.
  std::string closeAndWait();
  /// ffmpeg's last line on stderr, the temporary name replaced by shown_.
  std::string ffmpegReason() const;

  std::filesystem::path path_, shown_;
  int log_ = -1;  // ffmpeg's stderr: an unnamed temporary file
  int width_, height_;
  int stream_ = -1;  // our end of ffmpeg's stdin; -1 once closed
  pid_t child_ = -1;
};

}  // namespace reeve
