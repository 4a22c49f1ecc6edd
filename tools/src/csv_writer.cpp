#include "csv_writer.h"

#include <cmath>
#include <cstdio>
#include <iterator>
#include <stdexcept>

namespace reeve {

std::string csvField(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string quoted = "\"";
  for (const char c : field) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string nonFiniteMessage(double time_s, const std::string& what) {
  char t[32];
  std::snprintf(t, sizeof t, "%.9g", time_s);
  return std::string("the simulation became non-finite at t = ") + t + " s: " + what +
         "; nothing of that frame was written. Try more substeps or iterations";
}

namespace {

// Appends ",value" (or "value" first), refusing what is not finite; `what`
// names the value, built only then (no allocation per value and frame).
template <class What>
void append(std::string& row, double value, double time_s, const What& what) {
  if (!std::isfinite(value))
    throw std::runtime_error(nonFiniteMessage(time_s, what() + " is " + std::to_string(value)));
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", value == 0.0 ? 0.0 : value);  // never "-0"
  if (!row.empty()) row += ',';
  row += text;
}

// Links the cable can slide over or through get a slip speed column.
bool canSlip(const Link& link) { return link.type == LinkType::Pinhole || std::isfinite(link.mu); }

// The energy ledger's columns (energy.h), in this order.
constexpr const char* kEnergyColumns[] = {"kinetic_J",   "potential_J",  "elastic_J",        "drive_work_J",
                                          "load_work_J", "winch_work_J", "kinematic_work_J", "damping_J",
                                          "contact_J",   "friction_J",   "cable_damping_J",  "residual_J"};

}  // namespace

CsvWriter::CsvWriter(const std::filesystem::path& path, bool replace, const CableSystem& cables,
                     const EnergyWatch& energy)
    : out_(path, replace), cables_(cables), energy_(energy) {
  const World& world = cables.world();
  std::string header = "time_s";
  const auto add = [&](const std::string& name) {
    header += ',';
    header += csvField(name);
  };
  for (BodyId b = 0; b < world.bodyCount(); ++b) {
    if (world.bodyDef(b).is_static) continue;
    const std::string& n = world.bodyDef(b).name;
    for (const char* axis : {".x_m", ".y_m", ".z_m"}) add(n + axis);
  }
  for (const Cable& c : cables.cables()) {
    for (size_t j = 0; j < c.joints.size(); ++j) {
      const std::string p = c.name + "." + std::to_string(j);
      for (const char* column : {".tension_N", ".rest_length_m", ".length_m"}) add(p + column);
    }
    for (size_t k = 0; k < c.links.size(); ++k) add(c.name + ".link" + std::to_string(k) + ".stored_m");
    for (size_t k = 0; k < c.links.size(); ++k)
      if (canSlip(c.links[k])) add(c.name + ".link" + std::to_string(k) + ".slip_m_per_s");
    if (c.winch) add(c.name + ".winch_pull_N");
  }
  for (const char* column : kEnergyColumns) add(std::string("energy.") + column);
  out_.write(header + "\n");
}

void CsvWriter::writeRow() {
  const World& world = cables_.world();
  const double t = world.time();
  std::string row;
  append(row, t, t, [] { return std::string("the time"); });
  for (BodyId b = 0; b < world.bodyCount(); ++b) {
    if (world.bodyDef(b).is_static) continue;
    const Vec3& x = world.body(b).x;
    for (int i = 0; i < 3; ++i)
      append(row, x[i], t, [&] { return "body '" + world.bodyDef(b).name + "' position"; });
  }
  for (int c = 0; c < static_cast<int>(cables_.cables().size()); ++c) {
    const Cable& cable = cables_.cables()[c];
    for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
      const auto joint = [&](const char* quantity) {
        return [&cable, j, quantity] { return "cable '" + cable.name + "' joint " + std::to_string(j) + quantity; };
      };
      append(row, cables_.tension(c, j), t, joint(" tension"));
      append(row, cables_.restLengthNow(c, j), t, joint(" rest length"));
      append(row, cables_.length(c, j), t, joint(" length"));
    }
    for (std::size_t k = 0; k < cable.links.size(); ++k)
      append(row, cables_.storedNow(c, static_cast<int>(k)), t,
             [&] { return "cable '" + cable.name + "' link " + std::to_string(k) + " stored cable"; });
    for (std::size_t k = 0; k < cable.links.size(); ++k)
      if (canSlip(cable.links[k]))
        append(row, cable.links[k].slip_speed, t,
               [&] { return "cable '" + cable.name + "' link " + std::to_string(k) + " slip speed"; });
    if (cable.winch) append(row, cables_.winchPull(c), t, [&] { return "cable '" + cable.name + "' winch pull"; });
  }
  const EnergyLedger& e = energy_.ledger();
  const double energies[] = {e.kinetic_J,   e.potential_J,  e.elastic_J,         e.drive_work_J,
                             e.load_work_J, e.winch_work_J, e.kinematic_work_J,  e.damping_J,
                             e.contact_J,   e.friction_J,   e.cable_damping_J,   energy_.residual_J()};
  static_assert(std::size(energies) == std::size(kEnergyColumns));
  for (std::size_t i = 0; i < std::size(energies); ++i)
    append(row, energies[i], t, [&] { return std::string("the energy ledger's ") + kEnergyColumns[i]; });
  out_.write(row + "\n");
}

}  // namespace reeve
