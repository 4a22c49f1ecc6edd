// importMjcf: the model read (mjcf_read.cpp), mapped (mjcf_scene.cpp), and
// each tendon's cable given the length its range or spring sets, shared
// among its spans in proportion to their lengths at load as Reeve measures
// them (its own tangents round the wraps): a frictionless run shares its
// rest length so (scenes/README.md, "rest_length_m").
#include <algorithm>
#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>

#include "mjcf_model.h"
#include "reeve/scene/mjcf.h"
#include "reeve/scene/scene.h"

namespace reeve {

MjcfImport importMjcf(const std::filesystem::path& path, const MjcfOptions& options) {
  const mjcf::Model model = mjcf::readModel(path.string());
  std::vector<std::pair<int, double>> lengths;
  MjcfImport out = mjcf::mapModel(model, options, lengths);
  if (std::none_of(lengths.begin(), lengths.end(), [](const auto& l) { return l.first >= 0 && std::isfinite(l.second); }))
    return out;
  const Scene taut = parseScene(out.scene_json, path.string());
  nlohmann::ordered_json scene = nlohmann::ordered_json::parse(out.scene_json);
  for (std::size_t t = 0; t < lengths.size(); ++t) {
    const auto [c, total] = lengths[t];
    if (c < 0 || !std::isfinite(total)) continue;
    const CableSystem& cables = *taut.cables;
    const Cable& cable = cables.cables()[c];
    double stored = 0.0, spans = 0.0;
    for (std::size_t k = 0; k < cable.links.size(); ++k) stored += cables.storedNow(c, static_cast<int>(k));
    for (std::size_t j = 0; j < cable.joints.size(); ++j)
      if (cables.jointEnabled(c, static_cast<int>(j))) spans += cables.lengthNow(c, static_cast<int>(j));
    const mjcf::Origin& o = model.tendons[t].origin;
    if (!(total - stored > 0.0))
      throw SceneError::atLine(o.file, o.line, o.element,
                               "a length longer than the cable its wraps hold (" + std::to_string(stored) + " m)",
                               std::to_string(total) + " m");
    const double share = (total - stored) / spans;
    nlohmann::ordered_json rest = nlohmann::ordered_json::array();
    for (std::size_t j = 0; j < cable.joints.size(); ++j)
      rest.push_back(cables.jointEnabled(c, static_cast<int>(j)) ? share * cables.lengthNow(c, static_cast<int>(j)) : 0.0);
    scene["cables"][c]["rest_length_m"] = rest;
  }
  out.scene_json = scene.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  return out;
}

bool isMjcfPath(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return ext == ".xml";
}

}  // namespace reeve
