// Per-frame CSV of body positions and cable joint state.
#pragma once

#include <fstream>
#include <filesystem>

#include "reeve/cable/cable.h"

namespace reeve {

/// Writes a header, then one row per frame: time_s; for each dynamic body
/// B: B.x_m, B.y_m, B.z_m; for each cable C, each joint j (0-based):
/// C.j.tension_N, C.j.rest_length_m, C.j.length_m (0 while the joint is
/// merged away), then each link k: C.link<k>.stored_m.
class CsvWriter {
 public:
  /// Opens `path` for writing; throws std::runtime_error naming it.
  CsvWriter(const std::filesystem::path& path, const CableSystem& cables);
  void writeRow();

 private:
  std::ofstream out_;
  const CableSystem& cables_;
};

}  // namespace reeve
