// Per-frame CSV of body positions and cable joint state.
#pragma once

#include <filesystem>
#include <string>

#include "output_file.h"
#include "reeve/cable/cable.h"
#include "reeve/scene/energy.h"

namespace reeve {

/// "the simulation became non-finite at t = TIME s: WHAT; nothing of that
/// frame was written. ...": the run's guard and the CSV's own check.
std::string nonFiniteMessage(double time_s, const std::string& what);

/// Writes a header, then a row per writeRow() (reeve run: t = 0, then one
/// per frame): time_s; for each dynamic body
/// B: B.x_m, B.y_m, B.z_m; for each cable C, each joint j (0-based):
/// C.j.tension_N, C.j.rest_length_m, C.j.length_m (0 while the joint is
/// merged away or parted), then each link k: C.link<k>.stored_m, then
/// each link k the cable can slide over or through (a pinhole, or a link
/// with mu): C.link<k>.slip_m_per_s (CableSystem::slipSpeed), then, for a
/// cable with a winch, C.winch_pull_N (CableSystem::winchPull); last the
/// energy ledger of the watch's last check (EnergyLedger, J):
/// energy.kinetic_J, energy.potential_J, energy.elastic_J,
/// energy.drive_work_J, energy.load_work_J, energy.winch_work_J,
/// energy.kinematic_work_J, energy.damping_J, energy.contact_J,
/// energy.friction_J, energy.cable_damping_J, energy.residual_J
/// (EnergyWatch::residual_J). Header fields are
/// quoted per RFC 4180 where a name holds a comma, a quote or a line
/// break. Numbers have 10 significant digits; -0 is written 0.
class CsvWriter {
 public:
  /// Opens `path` (an OutputFile: nothing appears there before commit()).
  CsvWriter(const std::filesystem::path& path, bool replace, const CableSystem& cables, const EnergyWatch& energy);
  /// Appends the current state. Throws std::runtime_error naming the
  /// quantity if any number is not finite, before writing any of the row.
  void writeRow();
  void close() { out_.close(); }
  void commit() { out_.commit(); }

 private:
  OutputFile out_;
  const CableSystem& cables_;
  const EnergyWatch& energy_;
};

/// `field` as an RFC 4180 CSV field: quoted, with quotes doubled, when it
/// holds a comma, a quote, a CR or an LF; as it is otherwise.
std::string csvField(const std::string& field);

}  // namespace reeve
