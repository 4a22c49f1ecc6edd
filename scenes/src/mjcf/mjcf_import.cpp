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

namespace {

using json = nlohmann::ordered_json;

// The norm of the joint accelerations (rad/s^2 about hinges and balls,
// m/s^2 along slides, both for a free joint's body) that a pull of 1 N
// along cable c gives the model at rest at load, nothing else acting (no
// gravity, limits, springs, drives, contacts or other cables): MuJoCo's
// actuator_acc0 for a gear of 1, |M^-1 J^T| (mj_setConst), measured by
// one substep of 1 us from rest, v = h a, in which the direct solver holds
// every joint exactly.
double unitPullAcceleration(const json& scene, int c, const std::vector<mjcf::Dof>& dofs, const std::string& path) {
  constexpr double h = 1e-6;
  json probe = scene;
  probe["solver"]["substeps"] = 1;
  probe["solver"]["method"] = "direct";
  probe["solver"]["gravity_m_per_s2"] = json::array({0.0, 0.0, 0.0});
  probe.erase("ground");
  probe.erase("junctions");
  probe.erase("contact_exclusions");
  for (json& body : probe["bodies"]) body.erase("collides");
  for (const char* list : {"hinges", "joints"})
    if (probe.contains(list))
      for (json& joint : probe[list]) {
        joint.erase("limit");
        joint.erase("drive");
      }
  json cable = probe["cables"][c];
  cable.erase("rest_length_m");
  cable["winch"]["max_pull_N"] = 1.0;
  probe["cables"] = json::array({cable});
  Scene s = parseScene(probe.dump(), path);
  s.world->step(h);
  const auto state = [&](const std::string& name) -> const BodyState& { return s.world->body(*s.world->findBody(name)); };
  const BodyState still;  // the world's
  double sum = 0.0;
  for (const mjcf::Dof& dof : dofs) {
    const BodyState& own = state(dof.own);
    const BodyState& other = dof.other.empty() || dof.other == "world" ? still : state(dof.other);
    const Vec3 w = own.omega - other.omega;
    const auto pointVelocity = [&](const BodyState& b) { return Vec3(b.v + b.omega.cross(dof.anchor - b.x)); };
    Vec3 a = Vec3::Zero();
    double along = 0.0;
    switch (dof.type) {
      case mjcf::JointType::Hinge: along = w.dot(dof.axis); break;
      case mjcf::JointType::Slide: along = (pointVelocity(own) - pointVelocity(other)).dot(dof.axis); break;
      case mjcf::JointType::Ball: a = w; break;
      case mjcf::JointType::Free: sum += pointVelocity(own).squaredNorm(); a = own.omega; break;
    }
    sum += along * along + a.squaredNorm();
  }
  return std::sqrt(sum) / h;
}

}  // namespace

MjcfImport importMjcf(const std::filesystem::path& path, const MjcfOptions& options) {
  const mjcf::Model model = mjcf::readModel(path.string());
  mjcf::Mapping mapping = mjcf::mapModel(model, options);
  MjcfImport& out = mapping.import;
  const std::vector<mjcf::TendonCables>& tendons = mapping.tendons;
  if (mapping.muscle_pulls.empty() &&
      std::none_of(tendons.begin(), tendons.end(),
                   [](const mjcf::TendonCables& t) { return !t.cables.empty() && std::isfinite(t.length); }))
    return out;
  json scene = json::parse(out.scene_json);
  // A muscle's default peak force, scale / acc0, from the model as built.
  for (const mjcf::MusclePull& muscle : mapping.muscle_pulls) {
    const double acc0 = unitPullAcceleration(scene, muscle.cable, mapping.dofs, path.string());
    if (!(acc0 > 0.0) || !std::isfinite(acc0)) {
      const mjcf::Origin& o = muscle.origin;
      throw SceneError::atLine(o.file, o.line, o.element, "a muscle's tendon that moves a joint (MuJoCo's acc0 > 0)",
                               std::to_string(acc0));
    }
    scene["cables"][muscle.cable]["winch"]["max_pull_N"] = muscle.times / acc0;
  }
  out.scene_json = scene.dump(2, ' ', false, json::error_handler_t::replace);
  const Scene taut = parseScene(out.scene_json, path.string());
  const CableSystem& cables = *taut.cables;
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
      json rest = json::array();
      for (std::size_t j = 0; j < cable.joints.size(); ++j)
        rest.push_back(cables.jointEnabled(c, static_cast<int>(j)) ? share * cables.lengthNow(c, static_cast<int>(j)) : 0.0);
      scene["cables"][c]["rest_length_m"] = rest;
    }
  }
  out.scene_json = scene.dump(2, ' ', false, json::error_handler_t::replace);
  return out;
}

bool isMjcfPath(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return ext == ".xml";
}

}  // namespace reeve
