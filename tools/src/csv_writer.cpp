#include "csv_writer.h"

#include <cstring>
#include <stdexcept>

namespace reeve {

CsvWriter::CsvWriter(const std::filesystem::path& path, const CableSystem& cables)
    : out_(path), cables_(cables) {
  if (!out_) throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(errno));
  out_.precision(10);
  const World& world = cables.world();
  out_ << "time_s";
  for (BodyId b = 0; b < world.bodyCount(); ++b) {
    if (world.bodyDef(b).is_static) continue;
    const std::string& n = world.bodyDef(b).name;
    out_ << ',' << n << ".x_m," << n << ".y_m," << n << ".z_m";
  }
  for (const Cable& c : cables.cables()) {
    for (size_t j = 0; j < c.joints.size(); ++j) {
      const std::string p = c.name + "." + std::to_string(j);
      out_ << ',' << p << ".tension_N," << p << ".rest_length_m," << p << ".length_m";
    }
    for (size_t k = 0; k < c.links.size(); ++k) out_ << ',' << c.name << ".link" << k << ".stored_m";
  }
  out_ << '\n';
}

void CsvWriter::writeRow() {
  const World& world = cables_.world();
  out_ << world.time();
  for (BodyId b = 0; b < world.bodyCount(); ++b) {
    if (world.bodyDef(b).is_static) continue;
    const Vec3& x = world.body(b).x;
    out_ << ',' << x.x() << ',' << x.y() << ',' << x.z();
  }
  for (int c = 0; c < static_cast<int>(cables_.cables().size()); ++c) {
    for (int j = 0; j < static_cast<int>(cables_.cables()[c].joints.size()); ++j)
      out_ << ',' << cables_.tension(c, j) << ',' << cables_.restLength(c, j) << ','
           << cables_.length(c, j);
    for (const Link& link : cables_.cables()[c].links) out_ << ',' << link.stored;
  }
  out_ << '\n';
  if (!out_) throw std::runtime_error("CSV write failed (disk full?)");
}

}  // namespace reeve
