// importMjcf: the model read (mjcf_read.cpp), mapped (mjcf_scene.cpp), and
// each tendon's cables given the length its range or spring sets, shared
// among their spans in proportion to their lengths at load as Reeve
// measures them (its own tangents round the wraps): a frictionless run
// shares its rest length so (scenes/README.md, "rest_length_m"), and a
// junction its cables'.
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
  std::vector<mjcf::TendonCables> tendons;
  MjcfImport out = mjcf::mapModel(model, options, tendons);
  if (std::none_of(tendons.begin(), tendons.end(),
                   [](const mjcf::TendonCables& t) { return !t.cables.empty() && std::isfinite(t.length); }))
    return out;
  const Scene taut = parseScene(out.scene_json, path.string());
  const CableSystem& cables = *taut.cables;
  nlohmann::ordered_json scene = nlohmann::ordered_json::parse(out.scene_json);
  for (std::size_t t = 0; t < tendons.size(); ++t) {
    const mjcf::TendonCables& tendon = tendons[t];
    if (tendon.cables.empty() || !std::isfinite(tendon.length)) continue;
    // MuJoCo's length is sum_b L_b / divisor_b over the branches: the
    // stored cable counted so, and the spans' share f of their lengths
    // such that sum_b (stored_b + f spans_b) / divisor_b is the length.
    double stored = 0.0, spans = 0.0;
    for (std::size_t b = 0; b < tendon.cables.size(); ++b) {
      const int c = tendon.cables[b];
      const Cable& cable = cables.cables()[c];
      for (std::size_t k = 0; k < cable.links.size(); ++k) stored += cables.storedNow(c, static_cast<int>(k)) / tendon.divisors[b];
      for (std::size_t j = 0; j < cable.joints.size(); ++j)
        if (cables.jointEnabled(c, static_cast<int>(j))) spans += cables.lengthNow(c, static_cast<int>(j)) / tendon.divisors[b];
    }
    const mjcf::Origin& o = model.tendons[t].origin;
    if (!(tendon.length - stored > 0.0))
      throw SceneError::atLine(o.file, o.line, o.element,
                               "a length longer than the cable its wraps hold (" + std::to_string(stored) + " m)",
                               std::to_string(tendon.length) + " m");
    const double share = (tendon.length - stored) / spans;
    for (const int c : tendon.cables) {
      const Cable& cable = cables.cables()[c];
      nlohmann::ordered_json rest = nlohmann::ordered_json::array();
      for (std::size_t j = 0; j < cable.joints.size(); ++j)
        rest.push_back(cables.jointEnabled(c, static_cast<int>(j)) ? share * cables.lengthNow(c, static_cast<int>(j)) : 0.0);
      scene["cables"][c]["rest_length_m"] = rest;
    }
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
