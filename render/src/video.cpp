#include "reeve/render/video.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <spawn.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace reeve {
namespace {

// The first executable `name` in the directories of $PATH.
std::optional<std::filesystem::path> findOnPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (dir.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(dir) / name;
    if (access(candidate.c_str(), X_OK) == 0 && !std::filesystem::is_directory(candidate))
      return candidate;
  }
  return std::nullopt;
}

std::string describeStatus(int status) {
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "wait status " + std::to_string(status);
}

std::string formatFps(double fps) {
  std::ostringstream s;
  s.precision(17);
  s << fps;
  return s.str();
}

}  // namespace

VideoWriter::VideoWriter(const std::filesystem::path& path, int width, int height, double fps,
                         const std::filesystem::path& shown_as)
    : path_(path), shown_(shown_as.empty() ? path : shown_as), width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width % 2 != 0 || height % 2 != 0)
    throw std::invalid_argument("VideoWriter: '" + shown_.string() + "': frame size " +
                                std::to_string(width) + "x" + std::to_string(height) +
                                " must be positive and even (yuv420p)");
  if (!(fps > 0.0))
    throw std::invalid_argument("VideoWriter: '" + shown_.string() + "': fps must be > 0");
  const auto ffmpeg = findOnPath("ffmpeg");
  if (!ffmpeg)
    throw std::runtime_error("cannot write the video '" + shown_.string() +
                             "': ffmpeg program not found on PATH; install it (apt-get install "
                             "ffmpeg) or drop --video");
  // What ffmpeg says goes to a file in memory, read when it fails, so the
  // message can name the user's file rather than the temporary one.
  log_ = memfd_create("reeve-ffmpeg-stderr", MFD_CLOEXEC);
  if (log_ < 0) throw std::runtime_error("VideoWriter: memfd_create: " + std::string(std::strerror(errno)));

  // A socket rather than a pipe as ffmpeg's stdin, so that writing after
  // ffmpeg quit fails with EPIPE (MSG_NOSIGNAL) instead of raising SIGPIPE.
  int fds[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) {
    const std::string why = std::strerror(errno);
    close(log_);
    throw std::runtime_error("VideoWriter: socketpair: " + why);
  }
  shutdown(fds[0], SHUT_RD);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  const std::string rate = formatFps(fps);
  std::vector<std::string> args = {ffmpeg->string(), "-hide_banner", "-loglevel", "error",
                                   "-y", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s", size,
                                   "-r", rate, "-i", "pipe:0", "-c:v", "libx264",
                                   "-pix_fmt", "yuv420p", path.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDIN_FILENO);  // clears CLOEXEC
  posix_spawn_file_actions_adddup2(&actions, log_, STDERR_FILENO);
  // Its own process group: a Ctrl-C at the terminal reaches the writer,
  // which ends the video after its last whole frame, not ffmpeg half-way.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  const int error = posix_spawn(&child_, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  if (error != 0) {
    close(fds[0]);
    close(log_);
    throw std::runtime_error("VideoWriter: cannot start '" + ffmpeg->string() +
                             "': " + std::strerror(error));
  }
  stream_ = fds[0];
}

VideoWriter::~VideoWriter() {
  closeAndWait();
  if (log_ >= 0) close(log_);
}

void VideoWriter::add(const Image& frame) {
  if (frame.width != width_ || frame.height != height_ ||
      frame.rgb.size() != 3 * std::size_t(width_) * height_)
    throw std::invalid_argument("VideoWriter: '" + path_.string() + "': frame of " +
                                std::to_string(frame.width) + "x" +
                                std::to_string(frame.height) + " in a video of " +
                                std::to_string(width_) + "x" + std::to_string(height_));
  if (stream_ < 0) throw std::logic_error("VideoWriter: add() after finish()");
  const std::uint8_t* data = frame.rgb.data();
  std::size_t left = frame.rgb.size();
  while (left > 0) {
    const ssize_t sent = send(stream_, data, left, MSG_NOSIGNAL);
    if (sent < 0 && errno == EINTR) continue;
    if (sent < 0) {
      const std::string why = std::strerror(errno);
      const std::string failure = closeAndWait();
      throw std::runtime_error(!failure.empty() ? failure
                                                : "cannot write the video '" + shown_.string() +
                                                      "': ffmpeg stopped reading frames (" + why + ")");
    }
    data += sent;
    left -= static_cast<std::size_t>(sent);
  }
}

void VideoWriter::finish() {
  const std::string failure = closeAndWait();
  if (!failure.empty()) throw std::runtime_error(failure);
}

std::string VideoWriter::ffmpegReason() const {
  std::string text;
  char buffer[4096];
  ssize_t n;
  for (off_t at = 0; (n = pread(log_, buffer, sizeof buffer, at)) > 0; at += n) text.append(buffer, n);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  std::string line = text.substr(text.find_last_of('\n') + 1);  // npos + 1 = 0: the whole text
  const std::string temporary = path_.string(), shown = shown_.string();
  if (line.rfind(temporary + ": ", 0) == 0) return line.substr(temporary.size() + 2);  // "NAME: reason"
  for (std::size_t at = line.find(temporary); at != std::string::npos; at = line.find(temporary, at + shown.size()))
    line.replace(at, temporary.size(), shown);
  return line;
}

std::string VideoWriter::closeAndWait() {
  if (stream_ >= 0) close(stream_);
  stream_ = -1;
  if (child_ < 0) return "";
  int status = 0;
  pid_t waited;
  do waited = waitpid(child_, &status, 0);
  while (waited < 0 && errno == EINTR);
  child_ = -1;
  if (waited < 0) return "cannot write the video '" + shown_.string() + "': waitpid: " + std::strerror(errno);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  const std::string reason = ffmpegReason();
  return "cannot write the video '" + shown_.string() + "': " + (reason.empty() ? "ffmpeg failed" : reason) +
         " (ffmpeg, " + describeStatus(status) + ")";
}

}  // namespace reeve
