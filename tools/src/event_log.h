// Link switches, merges and splits as JSON lines (one object per event).
#pragma once

#include <filesystem>

#include "output_file.h"
#include "reeve/cable/cable.h"

namespace reeve {

/// Writes {"time_s", "cable", "link", "event", "orientation"} per line, and
/// "tension_N" for a break.
class EventLog {
 public:
  /// Opens `path` (an OutputFile: nothing appears there before commit()).
  EventLog(const std::filesystem::path& path, bool replace);
  /// Writes and clears the events the cable system gathered.
  void drain(CableSystem& cables);
  void close() { out_.close(); }
  void commit() { out_.commit(); }

 private:
  OutputFile out_;
};

}  // namespace reeve
