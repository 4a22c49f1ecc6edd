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

// Distance (m) from point p to the segment [a, b].
double pointSegmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

// Whether the segments [a, b] and [c, d] cross or touch.
bool segmentsMeet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 <= 0.0 && d2 >= 0.0) || (d1 >= 0.0 && d2 <= 0.0)) &&
         ((d3 <= 0.0 && d4 >= 0.0) || (d3 >= 0.0 && d4 <= 0.0));
}

// Distance (m) from the segment [a, b] of a section's plane to the section
// (a circle, or a convex polygon counter-clockwise); -1 where they meet.
double sectionClearance(const Section& section, const Vec2& a, const Vec2& b) {
  if (section.kind == Section::Kind::Circle) return pointSegmentDistance(section.centre, a, b) - section.radius;
  const std::vector<Vec2>& v = section.vertices;
  bool inside = true;  // a inside every edge
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 &p = v[i], &q = v[(i + 1) % v.size()];
    if (segmentsMeet(a, b, p, q)) return -1.0;
    inside = inside && cross(q - p, a - p) > 0.0;
    least = std::min({least, pointSegmentDistance(p, a, b), pointSegmentDistance(a, p, q),
                      pointSegmentDistance(b, p, q)});
  }
  return inside ? -1.0 : least;
}

// Whether the chord [a, b] (world) keeps `gap` (m) from the section that
// `link` wraps on `body`. Only the chord's part within `gap` of the cable
// plane is held to it: a chord elsewhere in 3D (another wheel's span,
// seen in this wheel's plane) passes the section by.
bool chordClears(const Link& link, const BodyState& body, const Vec3& a_world, const Vec3& b_world, double gap) {
  const Vec3 a = body.toLocal(a_world), b = body.toLocal(b_world);
  const double za = a.z() - link.plane_offset, dz = b.z() - a.z();
  double t0 = 0.0, t1 = 1.0;  // the chord's part in the slab |z - plane_offset| <= gap
  if (dz != 0.0) {
    const double u = (-gap - za) / dz, v = (gap - za) / dz;
    t0 = std::max(t0, std::min(u, v));
    t1 = std::min(t1, std::max(u, v));
  } else if (std::abs(za) > gap) {
    return true;
  }
  if (t0 > t1) return true;
  const Vec3 p = a + t0 * (b - a), q = a + t1 * (b - a);
  return sectionClearance(link.section, p.head<2>(), q.head<2>()) >= gap;
}

}  // namespace

nlohmann::ordered_json segmentScene(const nlohmann::ordered_json& input, const Scene& scene,
                            const SegmentOptions& options) {
  if (options.segments < 1) throw SegmentError("--segments must be at least 1");
  if (!(options.radius_m > 0.0) || !std::isfinite(options.radius_m))
    throw SegmentError("--radius must be a positive number of metres");
  if (options.substeps && *options.substeps < 1) throw SegmentError("--substeps must be at least 1");
  if (options.iterations && *options.iterations < 1) throw SegmentError("--iterations must be at least 1");
  const int c = findCable(scene, options.cable);
  const Cable& cable = scene.cables->cables()[c];
  const World& world = *scene.world;
  if (cable.junction >= 0)
    throw SegmentError("cable '" + options.cable + "' is a branch of junction '" +
                       scene.cables->junctions()[cable.junction].name + "' (not supported)");

  std::vector<RopePathPoint> path;
  try {
    path = ropeCentreline(*scene.cables, c, 1e-3);
  } catch (const std::invalid_argument& e) {
    throw SegmentError(e.what());
  }
  // The rods start clear of every section the cable wraps (by their
  // radius): laid on the cable's centre line, their chords cut into the
  // wheel and the first contacts threw the chain off it (DESIGN, "The
  // segmented rope baseline").
  std::vector<const Link*> wraps;
  for (std::size_t k = 1; k + 1 < cable.links.size(); ++k)
    if (cable.links[k].rolls() && cable.links[k].active) wraps.push_back(&cable.links[k]);
  const auto clear = [&](const std::vector<Vec3>& chain) {
    for (const Link* link : wraps)
      for (std::size_t i = 0; i + 1 < chain.size(); ++i)
        if (!chordClears(*link, world.body(link->body), chain[i], chain[i + 1], options.radius_m)) return false;
    return true;
  };
  std::vector<Vec3> vertices;
  try {
    vertices = clearChainVertices(path, options.segments, clear);
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
  for (const Link* link : wraps) wrapped.insert(world.bodyDef(link->body).name);
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

  if (options.substeps) out["solver"]["substeps"] = *options.substeps;
  if (options.iterations) out["solver"]["iterations"] = *options.iterations;
  out["name"] = input["name"].get<std::string>() + "_segments";
  // The command line may be of any length: formatted in two parts, not
  // one fixed buffer (which cut a long one off with its closing words).
  char numbers[160];
  std::snprintf(numbers, sizeof numbers, "%d rigid cylinders (radius %g m, %g kg in all)", options.segments,
                options.radius_m, rope_mass);
  const std::string note = "Cable '" + options.cable + "' replaced by " + numbers +
                           " joined by spherical joints along its path (generated by `" +
                           (options.command_line.empty() ? std::string("reeve segment") : options.command_line) +
                           "`). ";
  out["description"] = note + input.value("description", std::string());
  return out;
}

}  // namespace reeve
