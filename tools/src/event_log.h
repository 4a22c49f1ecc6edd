// Link switches, merges and splits as JSON lines (one object per event).
#pragma once

#include <filesystem>
#include <vector>

#include "output_file.h"
#include "reeve/cable/cable.h"

namespace reeve {

/// Writes {"time_s", "cable", "link", "event", "orientation"} per line, and
/// "tension_N" for a break.
class EventLog {
 public:
  /// Opens `path` (an OutputFile: nothing appears there before commit()).
  EventLog(const std::filesystem::path& path, bool replace);
  /// Writes `events`, taken from `cables` (CableSystem::takeEvents).
  void write(const CableSystem& cables, const std::vector<CableEvent>& events);
  void close() { out_.close(); }
  void commit() { out_.commit(); }

 private:
  OutputFile out_;
};

}  // namespace reeve
