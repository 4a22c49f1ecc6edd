// Link switches, merges and splits as JSON lines (one object per event).
#pragma once

#include <filesystem>
#include <fstream>

#include "reeve/cable/cable.h"

namespace reeve {

/// Writes {"time_s", "cable", "link", "event", "orientation"} per line.
class EventLog {
 public:
  /// Opens `path`; throws std::runtime_error naming it.
  explicit EventLog(const std::filesystem::path& path);
  /// Writes and clears the events the cable system gathered.
  void drain(CableSystem& cables);

 private:
  std::ofstream out_;
};

}  // namespace reeve
