// An output file of a run that holds either everything or nothing new.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string_view>

namespace reeve {

/// A file the run writes, under a temporary name in `path`'s folder
/// (".NAME.reeve-XXXXXX" plus NAME's extension), moved onto `path` by
/// commit() once the run ended well and removed otherwise, so that the
/// user's folder holds a complete output or nothing new. A character
/// device or a FIFO (/dev/stdout, /dev/full, a pipe) is written in place.
/// Every write, flush and close is checked: a failure throws
/// std::runtime_error "PATH: cannot write: REASON".
class OutputFile {
 public:
  /// Creates the temporary file (the folder must exist). `replace`: commit()
  /// may replace an existing `path` (--force); otherwise it refuses if one
  /// appeared meanwhile.
  OutputFile(std::filesystem::path path, bool replace);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void write(std::string_view text);
  /// Closes the file, checking that everything reached it.
  void close();
  /// Moves the closed file onto `path`. Close every output of a run before
  /// committing any, so that a failing one leaves none in place.
  void commit();

 private:
  /// Throws "PATH: cannot write: strerror(errno)".
  [[noreturn]] void fail() const;

  std::filesystem::path path_, writing_;
  bool replace_ = false, in_place_ = false;
  std::FILE* file_ = nullptr;
};

/// A temporary name in `path`'s folder for a file someone else writes
/// (ffmpeg), with `path`'s extension; nothing is created.
std::filesystem::path temporarySibling(const std::filesystem::path& path);

/// Moves the finished `from` onto `to`: replacing it if `replace`, else
/// failing with EEXIST if it exists. Throws std::runtime_error naming `to`.
void moveIntoPlace(const std::filesystem::path& from, const std::filesystem::path& to, bool replace);

/// True for a character device or a FIFO: written in place, never replaced.
bool isStream(const std::filesystem::path& path);

}  // namespace reeve
