#include "reeve/machines/segment_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <set>

#include "reeve/machines/rope_chain.h"
#include "reeve/machines/rope_path.h"

namespace reeve {

namespace {

nlohmann::ordered_json vec(const Vec3& v) { return nlohmann::ordered_json::array({v.x(), v.y(), v.z()}); }

int findCable(const Scene& scene, const std::string& name) {
  const auto& cables = scene.cables->cables();
  std::string names;
  for (std::size_t c = 0; c < cables.size(); ++c) {
    if (cables[c].name == name) return static_cast<int>(c);
    names += (names.empty() ? "" : ", ") + ("'" + cables[c].name + "'");
  }
  throw SegmentError("no cable named '" + name + "'; the scene's cables: " +
                     (names.empty() ? "(none)" : names));
}

// Orientation (axis-angle, JSON) turning local +z onto `dir`.
std::optional<nlohmann::ordered_json> zOnto(const Vec3& dir) {
  const Vec3 d = dir.normalized();
  const Vec3 cross = Vec3::UnitZ().cross(d);
  const double angle = std::atan2(cross.norm(), d.z());
  if (angle < 1e-12) return std::nullopt;
  const Vec3 axis = cross.norm() > 1e-12 ? cross.normalized() : Vec3::UnitX();
  return nlohmann::ordered_json{{"axis", vec(axis)}, {"angle_rad", angle}};
}

}  // namespace

nlohmann::ordered_json segmentScene(const nlohmann::ordered_json& input, const Scene& scene,
                            const SegmentOptions& options) {
  if (options.segments < 1) throw SegmentError("--segments must be at least 1");
  if (!(options.radius_m > 0.0) || !std::isfinite(options.radius_m))
    throw SegmentError("--radius must be a positive number of metres");
  const int c = findCable(scene, options.cable);
  const Cable& cable = scene.cables->cables()[c];
  const World& world = *scene.world;

  std::vector<RopePathPoint> path;
  try {
    path = ropeCentreline(*scene.cables, c, 1e-3);
  } catch (const std::invalid_argument& e) {
    throw SegmentError(e.what());
  }
  std::vector<Vec3> vertices;
  try {
    vertices = chainVertices(path, options.segments, scene.cables->totalLength(c));
  } catch (const std::invalid_argument& e) {
    throw SegmentError(std::string("cable '") + options.cable + "': " + e.what());
  }

  const Link& first = cable.links.front();
  const Link& last = cable.links.back();
  double end_mass = std::numeric_limits<double>::infinity();
  for (const Link* l : {&first, &last})
    if (world.bodyMass(l->body) > 0.0) end_mass = std::min(end_mass, world.bodyMass(l->body));
  if (!options.rope_mass_kg && !std::isfinite(end_mass))
    throw SegmentError("both ends of cable '" + options.cable + "' are on static bodies; give --rope-mass");
  const double rope_mass = options.rope_mass_kg.value_or(0.01 * end_mass);
  if (!(rope_mass > 0.0) || !std::isfinite(rope_mass))
    throw SegmentError("--rope-mass must be a positive number of kilograms");
  const double segment_mass = rope_mass / options.segments;

  nlohmann::ordered_json out = input;
  std::set<std::string> taken;
  for (const auto& b : out["bodies"]) taken.insert(b["name"].get<std::string>());
  const std::string prefix = options.cable + "_seg_";
  for (int i = 0; i < options.segments; ++i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%03d", i);
    if (taken.count(prefix + buf))
      throw SegmentError("the scene already has a body named '" + prefix + buf + "'");
  }
  auto segName = [&](int i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%03d", i);
    return prefix + buf;
  };

  // The wrapped bodies collide, so the chain rests on them.
  std::set<std::string> wrapped;
  for (std::size_t k = 1; k + 1 < cable.links.size(); ++k)
    if (cable.links[k].rolls() && cable.links[k].active) wrapped.insert(world.bodyDef(cable.links[k].body).name);
  for (auto& b : out["bodies"])
    if (wrapped.count(b["name"].get<std::string>())) b["collides"] = true;

  for (int i = 0; i < options.segments; ++i) {
    const Vec3 a = vertices[i], b = vertices[i + 1];
    const double len = (b - a).norm();
    if (!(len > 0.0)) throw SegmentError("two chain vertices coincide; use fewer segments");
    const double half = std::max(0.5 * len - options.radius_m, 0.25 * len);
    nlohmann::ordered_json body = {
        {"name", segName(i)},
        {"shape", {{"type", "cylinder"}, {"radius_m", options.radius_m}, {"half_length_m", half}}},
        {"mass_kg", segment_mass},
        {"position_m", vec(0.5 * (a + b))},
        {"collides", true}};
    if (auto o = zOnto(b - a)) body["orientation"] = *o;
    out["bodies"].push_back(body);
  }

  if (!out.contains("joints")) out["joints"] = nlohmann::ordered_json::array();
  auto spherical = [&](const std::string& body, const std::string& other, const Vec3& anchor) {
    out["joints"].push_back({{"type", "spherical"}, {"body", body}, {"other", other}, {"anchor_m", vec(anchor)}});
  };
  spherical(segName(0), world.bodyDef(first.body).name, vertices.front());
  for (int i = 0; i + 1 < options.segments; ++i) spherical(segName(i + 1), segName(i), vertices[i + 1]);
  spherical(segName(options.segments - 1), world.bodyDef(last.body).name, vertices.back());

  auto& cables = out["cables"];
  for (auto it = cables.begin(); it != cables.end(); ++it)
    if ((*it)["name"] == options.cable) {
      cables.erase(it);
      break;
    }
  if (cables.empty()) out.erase("cables");

  out["name"] = input["name"].get<std::string>() + "_segments";
  char note[256];
  std::snprintf(note, sizeof note,
                "Cable '%s' replaced by %d rigid cylinders (radius %g m, %g kg in all) joined by spherical "
                "joints along its path (generated by `%s`). ",
                options.cable.c_str(), options.segments, options.radius_m, rope_mass,
                options.command_line.empty() ? "reeve segment" : options.command_line.c_str());
  out["description"] = note + input.value("description", std::string());
  return out;
}

}  // namespace reeve
