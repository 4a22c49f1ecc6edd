// MJCF XML -> mjcf::Model: <include>s expanded, <default> classes applied,
// orientations and angles converted, every name resolved. What the scene
// cannot carry is listed in Model::unmapped, not dropped.
#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>

#include "mjcf_model.h"
#include "reeve/engine/convex_hull.h"
#include "reeve/scene/scene.h"
#include "reeve/scene/scene_file.h"

namespace reeve::mjcf {
namespace {

// Includes within includes, at most: a cycle is an error, not a hang.
constexpr int kMaxIncludeDepth = 16;
// Bodies (and default classes) nested in each other, at most: the reader
// recurses once a level, and no hostile file may exhaust the stack
// (MuJoCo's humanoid nests 6 deep, a 100-link chain 100).
constexpr int kMaxNesting = 1000;

struct Source {
  std::string path, text;
  pugi::xml_document doc;
  std::vector<std::size_t> line_starts;  // offsets where each line starts
  int line(std::ptrdiff_t offset) const {
    return static_cast<int>(std::upper_bound(line_starts.begin(), line_starts.end(),
                                             static_cast<std::size_t>(std::max<std::ptrdiff_t>(offset, 0))) -
                            line_starts.begin());
  }
};

struct Node {
  pugi::xml_node xml;
  const Source* source = nullptr;
};

// The offset of the first byte that is not UTF-8 (RFC 3629: no overlong
// forms, no surrogates, nothing past U+10FFFF), or npos. pugixml passes
// such bytes through; names made of them would reach the scene's JSON.
std::size_t firstNonUtf8(const std::string& text) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = s[i];
    std::size_t more = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // the bounds of the first continuation byte
    if (c < 0x80) more = 0;
    else if (c >= 0xC2 && c <= 0xDF) more = 1;
    else if (c == 0xE0) more = 2, lo = 0xA0;
    else if (c == 0xED) more = 2, hi = 0x9F;
    else if (c >= 0xE1 && c <= 0xEF) more = 2;
    else if (c == 0xF0) more = 3, lo = 0x90;
    else if (c == 0xF4) more = 3, hi = 0x8F;
    else if (c >= 0xF1 && c <= 0xF3) more = 3;
    else return i;
    for (std::size_t k = 1; k <= more; ++k) {
      if (i + k >= n) return i;
      const unsigned char b = s[i + k];
      if (b < (k == 1 ? lo : 0x80) || b > (k == 1 ? hi : 0xBF)) return i;
    }
    i += more + 1;
  }
  return std::string::npos;
}

std::string describe(const pugi::xml_node& xml) {
  std::string text = std::string("<") + xml.name();
  if (const auto name = xml.attribute("name")) text += std::string(" name=\"") + name.value() + "\"";
  return text + ">";
}

Origin originOf(const Node& n) {
  return {n.source->path, n.source->line(n.xml.offset_debug()), describe(n.xml)};
}

[[noreturn]] void fail(const Node& n, const std::string& expected, const std::string& found) {
  const Origin o = originOf(n);
  throw SceneError::atLine(o.file, o.line, o.element, expected, found);
}

class Reader {
 public:
  Model read(const std::string& path) {
    model_.file = path;
    const Source& root_source = load(path, nullptr);
    const Node root{root_source.doc.document_element(), &root_source};
    if (std::string(root.xml.name()) != "mujoco") fail(root, "<mujoco> as the root element", describe(root.xml));
    if (const auto name = root.xml.attribute("model")) model_.name = name.value();
    Body world;
    world.origin = originOf(root);
    world.name = "world";
    model_.bodies.push_back(world);
    const std::vector<Node> sections = children(root);  // its includes read once
    // Settings and defaults first: the elements that use them may come earlier in the file.
    for (const Node& n : sections) {
      const std::string tag = n.xml.name();
      if (tag == "compiler") readCompiler(n);
      else if (tag == "option") readOption(n);
      else if (tag == "default") readDefaults(n, "main", "");
    }
    for (const Node& n : sections)  // before the geoms that use them
      if (std::string(n.xml.name()) == "asset") readAssets(n);
    for (const Node& n : sections)
      if (std::string(n.xml.name()) == "worldbody") readBodyChildren(n, 0, "main");
    for (const Node& n : sections)  // before the actuators that name them
      if (std::string(n.xml.name()) == "tendon") readTendons(n);
    for (const Node& n : sections) {
      const std::string tag = n.xml.name();
      if (tag == "actuator") readActuators(n);
      else if (tag == "contact") readContacts(n);
      else if (tag == "compiler" || tag == "option" || tag == "default" || tag == "worldbody" || tag == "tendon") continue;
      else if (tag == "visual" || tag == "asset" || tag == "size" || tag == "statistic") continue;  // drawing, memory; meshes read
      else unmapped(n, "not imported (Reeve has no " + tag + " section)");
    }
    listAttributes();
    return std::move(model_);
  }

 private:
  const Source& load(const std::string& path, const Node* from) {
    auto source = std::make_unique<Source>();
    source->path = path;
    try {
      source->text = readSceneFile(path);
    } catch (const SceneError& e) {
      if (!from) throw;
      fail(*from, "a readable file", path + ": " + e.found());
    }
    source->line_starts.push_back(0);
    for (std::size_t i = 0; i < source->text.size(); ++i)
      if (source->text[i] == '\n') source->line_starts.push_back(i + 1);
    if (const std::size_t bad = firstNonUtf8(source->text); bad != std::string::npos) {
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(source->text[bad]));
      throw SceneError::atLine(path, source->line(static_cast<std::ptrdiff_t>(bad)), "XML", "UTF-8 text", std::string("the byte ") + byte);
    }
    const pugi::xml_parse_result result =
        source->doc.load_buffer(source->text.data(), source->text.size(), pugi::parse_default, pugi::encoding_utf8);
    if (!result) {
      const int line = source->line(result.offset);
      throw SceneError::atLine(path, line, "XML", "well-formed XML", result.description());
    }
    sources_.push_back(std::move(source));
    return *sources_.back();
  }

  // An element's children, each <include> replaced by the children of the
  // root of the file it names (relative to the model's folder, as MuJoCo).
  std::vector<Node> children(const Node& parent, int depth = 0) {
    std::vector<Node> out;
    for (pugi::xml_node c = parent.xml.first_child(); c; c = c.next_sibling()) {
      if (c.type() != pugi::node_element) continue;
      const Node n{c, parent.source};
      if (std::string(c.name()) != "include") {
        out.push_back(n);
        continue;
      }
      if (depth >= kMaxIncludeDepth) fail(n, "includes nested at most " + std::to_string(kMaxIncludeDepth) + " deep", "more (a cycle?)");
      const std::string file = text(n, "file");
      const std::filesystem::path base = std::filesystem::path(model_.file).parent_path();
      const Source& s = load((base / file).string(), &n);
      const Node root{s.doc.document_element(), &s};
      for (const Node& inner : children(root, depth + 1)) out.push_back(inner);
    }
    return out;
  }

  // --- attributes -------------------------------------------------------

  std::string text(const Node& n, const char* name) {
    const auto a = n.xml.attribute(name);
    if (!a) fail(n, std::string("a ") + name + " attribute", "none");
    return a.value();
  }

  // The attribute `name` of element `n` (tag `tag`), or of its class's
  // defaults up the class tree; null if none.
  pugi::xml_attribute lookup(const Node& n, const std::string& tag, const std::string& cls, const char* name) {
    if (const auto a = n.xml.attribute(name)) return a;
    for (std::string c = cls; !c.empty();) {
      const auto it = classes_.find(c);
      if (it == classes_.end()) break;
      if (const auto d = it->second.defaults.find(tag); d != it->second.defaults.end())
        for (auto node = d->second.rbegin(); node != d->second.rend(); ++node)  // the last given wins
          if (const auto a = node->attribute(name)) return a;
      c = it->second.parent;
    }
    return {};
  }

  std::vector<double> numbers(const Node& n, const pugi::xml_attribute& a, std::size_t least, std::size_t most) {
    std::vector<double> values;
    std::istringstream in(a.value());
    in.imbue(std::locale::classic());
    std::string word;
    while (in >> word) {
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end != word.c_str() + word.size() || !std::isfinite(v))
        fail(n, std::string(a.name()) + " as finite numbers", "\"" + std::string(a.value()) + "\"");
      values.push_back(v);
    }
    if (values.size() < least || values.size() > most)
      fail(n, std::string(a.name()) + " of " + std::to_string(least) + (least == most ? "" : " to " + std::to_string(most)) +
                  " numbers",
           std::to_string(values.size()) + " (\"" + a.value() + "\")");
    return values;
  }

  double number(const Node& n, const std::string& tag, const std::string& cls, const char* name, double fallback) {
    const auto a = lookup(n, tag, cls, name);
    return a ? numbers(n, a, 1, 1)[0] : fallback;
  }
  Vec3 vec3(const Node& n, const std::string& tag, const std::string& cls, const char* name, const Vec3& fallback) {
    const auto a = lookup(n, tag, cls, name);
    if (!a) return fallback;
    const auto v = numbers(n, a, 3, 3);
    return Vec3(v[0], v[1], v[2]);
  }
  std::optional<bool> flag(const Node& n, const std::string& tag, const std::string& cls, const char* name) {
    const auto a = lookup(n, tag, cls, name);
    if (!a) return std::nullopt;
    const std::string v = a.value();
    if (v == "true") return true;
    if (v == "false") return false;
    if (v == "auto") return std::nullopt;
    fail(n, std::string(name) + " \"true\", \"false\" or \"auto\"", "\"" + v + "\"");
  }
  double angle(double value) const { return degrees_ ? value * std::numbers::pi / 180.0 : value; }

  // The orientation of `n`: quat, axisangle, euler, xyaxes or zaxis, at most one.
  Quat orientation(const Node& n, const std::string& tag, const std::string& cls) {
    Quat q = Quat::Identity();
    int given = 0;
    if (const auto a = lookup(n, tag, cls, "quat")) {
      const auto v = numbers(n, a, 4, 4);
      q = Quat(v[0], v[1], v[2], v[3]);
      if (q.norm() == 0.0) fail(n, "a non-zero quat", "0 0 0 0");
      q.normalize();
      ++given;
    }
    if (const auto a = lookup(n, tag, cls, "axisangle")) {
      const auto v = numbers(n, a, 4, 4);
      const Vec3 axis(v[0], v[1], v[2]);
      if (axis.norm() == 0.0) fail(n, "a non-zero axisangle axis", a.value());
      q = Quat(Eigen::AngleAxisd(angle(v[3]), axis.normalized()));
      ++given;
    }
    if (const auto a = lookup(n, tag, cls, "euler")) {
      const auto v = numbers(n, a, 3, 3);
      q = Quat::Identity();
      for (int i = 0; i < 3; ++i) {
        const char c = eulerseq_[i];
        const Vec3 axis = (c == 'x' || c == 'X') ? Vec3::UnitX() : (c == 'y' || c == 'Y') ? Vec3::UnitY() : Vec3::UnitZ();
        const Quat r(Eigen::AngleAxisd(angle(v[i]), axis));
        q = std::islower(static_cast<unsigned char>(c)) ? Quat(q * r) : Quat(r * q);  // intrinsic: about the turned axes
      }
      ++given;
    }
    if (const auto a = lookup(n, tag, cls, "xyaxes")) {
      const auto v = numbers(n, a, 6, 6);
      Vec3 x(v[0], v[1], v[2]), y(v[3], v[4], v[5]);
      if (x.norm() == 0.0) fail(n, "xyaxes with a non-zero x axis", a.value());
      x.normalize();
      y -= x * x.dot(y);
      if (y.norm() < 1e-12) fail(n, "xyaxes with a y axis not along x", a.value());
      y.normalize();
      Mat3 R;
      R << x, y, x.cross(y);
      q = Quat(R);
      ++given;
    }
    if (const auto a = lookup(n, tag, cls, "zaxis")) {
      const auto v = numbers(n, a, 3, 3);
      const Vec3 z(v[0], v[1], v[2]);
      if (z.norm() == 0.0) fail(n, "a non-zero zaxis", a.value());
      q = Quat::FromTwoVectors(Vec3::UnitZ(), z.normalized());
      ++given;
    }
    if (given > 1) fail(n, "at most one of quat, axisangle, euler, xyaxes and zaxis", std::to_string(given));
    return q;
  }

  void unmapped(const Node& n, const std::string& why) { model_.unmapped.push_back(originOf(n).where() + ": " + why); }
  // Attributes of `n` that change the physics but are not imported (MuJoCo's
  // soft-contact and limit settings, mostly): gathered per tag and
  // attribute, one line each however many elements have it (listAttributes).
  void unmappedAttributes(const Node& n, const std::string& tag, const std::string& cls,
                          std::initializer_list<const char*> names) {
    for (const char* name : names)
      if (lookup(n, tag, cls, name)) unmapped_attributes_[{tag, name}].push_back(originOf(n));
  }
  void listAttributes() {
    for (const auto& [key, origins] : unmapped_attributes_) {
      std::string line = origins.front().where() + ": " + key.second + " not imported";
      if (origins.size() > 1) {
        line.append(", nor on ").append(std::to_string(origins.size() - 1)).append(" more <").append(key.first).append("> (lines");
        for (std::size_t i = 1; i < origins.size() && i <= 10; ++i) line.append(" ").append(std::to_string(origins[i].line));
        line += origins.size() > 11 ? " ...)" : ")";
      }
      model_.unmapped.push_back(line);
    }
  }

  // --- sections ---------------------------------------------------------

  void readCompiler(const Node& n) {
    if (const auto a = n.xml.attribute("angle")) {
      const std::string v = a.value();
      if (v != "degree" && v != "radian") fail(n, "angle \"degree\" or \"radian\"", "\"" + v + "\"");
      degrees_ = v == "degree";
    }
    if (const auto a = n.xml.attribute("eulerseq")) {
      const std::string v = a.value();
      if (v.size() != 3 || v.find_first_not_of("xyzXYZ") != std::string::npos)
        fail(n, "eulerseq of three letters from xyzXYZ", "\"" + v + "\"");
      eulerseq_ = v;
    }
    if (const auto a = n.xml.attribute("autolimits")) autolimits_ = std::string(a.value()) != "false";
    if (const auto a = n.xml.attribute("inertiafromgeom")) {
      const std::string v = a.value();
      if (v != "true" && v != "false" && v != "auto") fail(n, "inertiafromgeom \"true\", \"false\" or \"auto\"", "\"" + v + "\"");
      model_.inertia_from_geom = v;
    }
    if (const auto a = n.xml.attribute("coordinate"); a && std::string(a.value()) != "local")
      fail(n, "coordinate=\"local\" (global coordinates were removed from MJCF)", a.value());
    for (const char* name : {"boundmass", "boundinertia", "settotalmass", "balanceinertia", "fitaabb"})
      if (n.xml.attribute(name)) unmapped(n, std::string(name) + " not imported");
    if (const auto a = n.xml.attribute("exactmeshinertia")) exact_mesh_inertia_ = std::string(a.value()) == "true";
    if (const auto a = n.xml.attribute("assetdir")) mesh_dir_ = a.value();
    if (const auto a = n.xml.attribute("meshdir")) mesh_dir_ = a.value();  // wins over assetdir, as in MuJoCo
  }

  // <asset>'s meshes: each read when a geom first uses it. The others
  // (textures, materials, heightfields, skins) are drawing or not imported.
  void readAssets(const Node& assets) {
    for (const Node& n : children(assets)) {
      const std::string tag = n.xml.name();
      if (tag == "hfield" || tag == "skin") unmapped(n, "not imported (Reeve has no " + tag + ")");
      if (tag != "mesh") continue;
      MeshAsset mesh;
      mesh.origin = originOf(n);
      const std::string cls = n.xml.attribute("class") ? n.xml.attribute("class").value() : "main";
      if (n.xml.attribute("vertex")) fail(n, "a mesh from a file (vertex lists are not imported)", "vertex=\"...\"");
      const std::string file = text(n, "file");
      std::filesystem::path dir = std::filesystem::path(model_.file).parent_path() / mesh_dir_;
      mesh.path = (std::filesystem::path(file).is_absolute() ? std::filesystem::path(file) : dir / file).string();
      if (const auto scale = lookup(n, "mesh", cls, "scale")) {
        const auto v = numbers(n, scale, 3, 3);
        mesh.scale = Vec3(v[0], v[1], v[2]);
      }
      unmappedAttributes(n, "mesh", cls, {"refpos", "refquat", "smoothnormal"});
      std::string name = n.xml.attribute("name") ? n.xml.attribute("name").value() : std::filesystem::path(file).stem().string();
      if (!meshes_.emplace(name, std::move(mesh)).second) fail(n, "a mesh name not already used", "\"" + name + "\"");
    }
  }

  // A mesh geom: the mesh's solid, scaled, moved to its centre of mass as
  // MuJoCo's compiler moves a mesh (the geom's frame follows, so nothing
  // moves in the world); its hull's corners for the shape.
  void readMeshGeom(const Node& n, const std::string& cls, Geom& g, double density, bool mass_given) {
    const auto attribute = lookup(n, "geom", cls, "mesh");
    if (!attribute) fail(n, "a mesh attribute on a mesh geom", "none");
    const auto it = meshes_.find(attribute.value());
    if (it == meshes_.end()) fail(n, "the name of a <mesh> asset", "\"" + std::string(attribute.value()) + "\"");
    MeshAsset& asset = it->second;
    if (!asset.loaded) {
      try {
        TriangleMesh mesh = readMeshFile(asset.path);
        for (Vec3& v : mesh.vertices) v = v.cwiseProduct(asset.scale);
        if (asset.scale.prod() < 0.0)  // mirrored: the triangles turn inside out, as MuJoCo turns them back
          for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
        asset.mass = meshMassProperties(mesh, !exact_mesh_inertia_);
        if (!(asset.mass.volume > 0.0))
          throw MeshError(asset.path + ": a mesh that bounds a solid (volume > 0" +
                          (exact_mesh_inertia_ ? ", its triangles outward" : "") + "), got a volume of " +
                          std::to_string(asset.mass.volume) + " m^3");
        asset.corners = makeConvexHull(mesh.vertices, true)->vertices;
        for (Vec3& v : asset.corners) v -= asset.mass.centroid;
      } catch (const MeshError& e) {
        throw SceneError::atLine(asset.origin.file, asset.origin.line, asset.origin.element, "a mesh Reeve can read", e.what());
      } catch (const std::invalid_argument& e) {
        throw SceneError::atLine(asset.origin.file, asset.origin.line, asset.origin.element, "a mesh that spans a volume", e.what());
      }
      asset.loaded = true;
    }
    g.pose = g.pose.then(Pose{asset.mass.centroid, Quat::Identity()});
    g.vertices = asset.corners;
    g.mass = mass_given ? g.mass : density * asset.mass.volume;
    g.inertia = g.mass / asset.mass.volume * asset.mass.inertia_unit_density;
  }

  void readOption(const Node& n) {
    if (const auto a = n.xml.attribute("timestep")) {
      model_.timestep = numbers(n, a, 1, 1)[0];
      if (!(model_.timestep > 0.0)) fail(n, "timestep > 0", a.value());
    }
    if (const auto a = n.xml.attribute("gravity")) {
      const auto v = numbers(n, a, 3, 3);
      model_.gravity = Vec3(v[0], v[1], v[2]);
    }
    for (const char* name : {"wind", "magnetic", "density", "viscosity"})
      if (const auto a = n.xml.attribute(name)) unmapped(n, std::string(name) + "=\"" + a.value() + "\" not imported");
  }

  void readDefaults(const Node& n, const std::string& cls, const std::string& parent, int depth = 0) {
    if (depth > kMaxNesting) fail(n, "defaults nested at most " + std::to_string(kMaxNesting) + " deep", "more");
    // The main class may be given in several <default> sections (a model and
    // the files it includes): they add up, the last one's attributes winning.
    if (classes_.count(cls) && cls != "main") fail(n, "a default class name used once", "\"" + cls + "\" again");
    DefaultClass& c = classes_[cls];
    c.parent = parent;
    for (const Node& child : children(n)) {
      const std::string tag = child.xml.name();
      if (tag == "default") {
        const auto name = child.xml.attribute("class");
        if (!name) fail(child, "a class attribute on a nested <default>", "none");
        readDefaults(child, name.value(), cls, depth + 1);
      } else {
        c.defaults[tag].push_back(child.xml);
      }
    }
  }

  std::string classOf(const Node& n, const std::string& inherited) {
    if (const auto a = n.xml.attribute("class")) {
      if (!classes_.count(a.value())) fail(n, "a class defined in <default>", "\"" + std::string(a.value()) + "\"");
      return a.value();
    }
    return inherited;
  }

  void readBodyChildren(const Node& n, int body, const std::string& childclass, int depth = 0) {
    for (const Node& c : children(n)) {
      const std::string tag = c.xml.name();
      if (tag == "body") readBody(c, body, childclass, depth + 1);
      else if (tag == "geom") readGeom(c, body, classOf(c, childclass));
      else if (tag == "site") readSite(c, body, classOf(c, childclass));
      else if (tag == "joint" || tag == "freejoint") readJoint(c, body, classOf(c, childclass));
      else if (tag == "inertial") readInertial(c, body);
      else if (tag == "camera" || tag == "light") continue;  // drawing
      else unmapped(c, "not imported");
    }
  }

  void readBody(const Node& n, int parent, const std::string& inherited, int depth) {
    if (depth > kMaxNesting) fail(n, "bodies nested at most " + std::to_string(kMaxNesting) + " deep", "more");
    Body b;
    b.origin = originOf(n);
    b.name = n.xml.attribute("name").value();
    b.parent = parent;
    b.pose.pos = vec3(n, "body", "", "pos", Vec3::Zero());
    b.pose.quat = orientation(n, "body", "");
    b.world = model_.bodies[parent].world.then(b.pose);
    std::string childclass = inherited;
    if (const auto a = n.xml.attribute("childclass")) {
      if (!classes_.count(a.value())) fail(n, "a childclass defined in <default>", "\"" + std::string(a.value()) + "\"");
      childclass = a.value();
    }
    for (const char* name : {"mocap", "gravcomp"})
      if (const auto a = n.xml.attribute(name); a && std::string(a.value()) != "false" && std::string(a.value()) != "0")
        unmapped(n, std::string(name) + "=\"" + a.value() + "\" not imported");
    if (!b.name.empty() && std::any_of(model_.bodies.begin(), model_.bodies.end(), [&](const Body& o) { return o.name == b.name; }))
      fail(n, "a body name used once", "\"" + b.name + "\" again");
    model_.bodies.push_back(b);
    readBodyChildren(n, static_cast<int>(model_.bodies.size()) - 1, childclass, depth);
  }

  void readInertial(const Node& n, int body) {
    Body& b = model_.bodies[body];
    if (b.has_inertial) fail(n, "one <inertial> in a body", "two");
    b.has_inertial = true;
    const auto mass = n.xml.attribute("mass");
    if (!mass) fail(n, "a mass attribute", "none");
    b.mass = numbers(n, mass, 1, 1)[0];
    if (b.mass < 0.0) fail(n, "mass >= 0", mass.value());
    b.com = vec3(n, "inertial", "", "pos", Vec3::Zero());
    const Quat q = orientation(n, "inertial", "");
    Mat3 I = Mat3::Zero();
    const auto diag = n.xml.attribute("diaginertia"), full = n.xml.attribute("fullinertia");
    if (diag && full) fail(n, "one of diaginertia and fullinertia", "both");
    if (diag) {
      const auto v = numbers(n, diag, 3, 3);
      I = Vec3(v[0], v[1], v[2]).asDiagonal();
    } else if (full) {
      const auto v = numbers(n, full, 6, 6);
      I << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
    } else if (b.mass > 0.0) {
      fail(n, "diaginertia or fullinertia", "neither");
    }
    b.inertia = q.toRotationMatrix() * I * q.toRotationMatrix().transpose();
  }

  void readGeom(const Node& n, int body, const std::string& cls) {
    Geom g;
    g.origin = originOf(n);
    g.name = n.xml.attribute("name").value();
    g.body = body;
    const auto type = lookup(n, "geom", cls, "type");
    const std::string t = type ? type.value() : "sphere";
    static const std::map<std::string, GeomType> kTypes{
        {"plane", GeomType::Plane},         {"sphere", GeomType::Sphere}, {"capsule", GeomType::Capsule},
        {"ellipsoid", GeomType::Ellipsoid}, {"cylinder", GeomType::Cylinder}, {"box", GeomType::Box},
        {"mesh", GeomType::Mesh}};
    const auto it = kTypes.find(t);
    if (it == kTypes.end()) fail(n, "a geom type of plane, sphere, capsule, ellipsoid, cylinder, box or mesh", "\"" + t + "\"");
    g.type = it->second;
    if (g.type != GeomType::Mesh && lookup(n, "geom", cls, "mesh"))
      fail(n, "type=\"mesh\" on a geom that names a mesh (a primitive fitted to a mesh is not imported)", "type \"" + t + "\"");
    if (const auto size = lookup(n, "geom", cls, "size")) {
      const auto v = numbers(n, size, 1, 3);
      for (std::size_t i = 0; i < v.size(); ++i) g.size[static_cast<int>(i)] = v[i];
    }
    g.pose.pos = vec3(n, "geom", cls, "pos", Vec3::Zero());
    g.pose.quat = orientation(n, "geom", cls);
    if (const auto fromto = lookup(n, "geom", cls, "fromto")) {
      if (g.type != GeomType::Capsule && g.type != GeomType::Cylinder && g.type != GeomType::Box &&
          g.type != GeomType::Ellipsoid)
        fail(n, "fromto only on a capsule, cylinder, box or ellipsoid", t);
      const auto v = numbers(n, fromto, 6, 6);
      const Vec3 from(v[0], v[1], v[2]), to(v[3], v[4], v[5]);
      if ((to - from).norm() == 0.0) fail(n, "fromto with two different points", fromto.value());
      g.pose.pos = 0.5 * (from + to);
      g.pose.quat = Quat::FromTwoVectors(Vec3::UnitZ(), (to - from).normalized());
      g.size[g.type == GeomType::Box || g.type == GeomType::Ellipsoid ? 2 : 1] = 0.5 * (to - from).norm();
    }
    const int needed = g.type == GeomType::Sphere ? 1 : g.type == GeomType::Capsule || g.type == GeomType::Cylinder ? 2
                     : g.type == GeomType::Plane || g.type == GeomType::Mesh ? 0 : 3;
    for (int i = 0; i < needed; ++i)
      if (!(g.size[i] > 0.0)) fail(n, "a " + t + " size of " + std::to_string(needed) + " positive numbers", "size " + std::to_string(i) + " = " + std::to_string(g.size[i]));
    const auto mass = lookup(n, "geom", cls, "mass");
    const double density = number(n, "geom", cls, "density", 1000.0);
    g.mass = mass ? numbers(n, mass, 1, 1)[0] : density * geomVolume(g.type, g.size);
    if (g.mass < 0.0) fail(n, "a geom mass >= 0", std::to_string(g.mass));
    g.inertia = g.mass * geomUnitInertia(g.type, g.size);
    if (g.type == GeomType::Mesh) readMeshGeom(n, cls, g, density, static_cast<bool>(mass));
    g.contype = static_cast<int>(number(n, "geom", cls, "contype", 1.0));
    g.conaffinity = static_cast<int>(number(n, "geom", cls, "conaffinity", 1.0));
    if (const auto f = lookup(n, "geom", cls, "friction")) g.friction = numbers(n, f, 1, 3)[0];
    unmappedAttributes(n, "geom", cls, {"margin", "gap", "solref", "solimp", "priority", "condim", "fluidshape"});
    model_.geoms.push_back(g);
    model_.bodies[body].geoms.push_back(static_cast<int>(model_.geoms.size()) - 1);
  }

  void readSite(const Node& n, int body, const std::string& cls) {
    Site s;
    s.origin = originOf(n);
    s.name = n.xml.attribute("name").value();
    s.body = body;
    s.pos = vec3(n, "site", cls, "pos", Vec3::Zero());
    if (const auto fromto = lookup(n, "site", cls, "fromto")) {
      const auto v = numbers(n, fromto, 6, 6);
      s.pos = 0.5 * (Vec3(v[0], v[1], v[2]) + Vec3(v[3], v[4], v[5]));
    }
    model_.sites.push_back(s);
    model_.bodies[body].sites.push_back(static_cast<int>(model_.sites.size()) - 1);
  }

  void readJoint(const Node& n, int body, const std::string& cls) {
    if (body == 0) fail(n, "a joint in a body (the world does not move)", "one in <worldbody>");
    Joint j;
    j.origin = originOf(n);
    j.name = n.xml.attribute("name").value();
    j.body = body;
    const bool freejoint = std::string(n.xml.name()) == "freejoint";
    const auto type = freejoint ? pugi::xml_attribute() : lookup(n, "joint", cls, "type");
    const std::string t = freejoint ? "free" : type ? type.value() : "hinge";
    if (t == "free") j.type = JointType::Free;
    else if (t == "ball") j.type = JointType::Ball;
    else if (t == "slide") j.type = JointType::Slide;
    else if (t == "hinge") j.type = JointType::Hinge;
    else fail(n, "a joint type of free, ball, slide or hinge", "\"" + t + "\"");
    if (freejoint) {
      model_.joints.push_back(j);
      model_.bodies[body].joints.push_back(static_cast<int>(model_.joints.size()) - 1);
      return;
    }
    j.pos = vec3(n, "joint", cls, "pos", Vec3::Zero());
    j.axis = vec3(n, "joint", cls, "axis", Vec3::UnitZ());
    if (j.axis.norm() == 0.0) fail(n, "a non-zero axis", "0 0 0");
    j.axis.normalize();
    const bool angular = j.type == JointType::Hinge || j.type == JointType::Ball;
    const auto range = lookup(n, "joint", cls, "range");
    if (range) {
      const auto v = numbers(n, range, 2, 2);
      j.range = {angular ? angle(v[0]) : v[0], angular ? angle(v[1]) : v[1]};
    }
    j.limited = flag(n, "joint", cls, "limited").value_or(autolimits_ && range);
    if (j.limited && !range) fail(n, "a range with limited=\"true\"", "none");
    if (j.limited && !(j.range[0] < j.range[1]) && j.type != JointType::Ball)
      fail(n, "a range with lower < upper", std::string(range.value()));
    j.damping = number(n, "joint", cls, "damping", 0.0);
    j.stiffness = number(n, "joint", cls, "stiffness", 0.0);
    j.springref = number(n, "joint", cls, "springref", 0.0);
    if (angular) j.springref = angle(j.springref);
    j.armature = number(n, "joint", cls, "armature", 0.0);
    j.frictionloss = number(n, "joint", cls, "frictionloss", 0.0);
    if (j.damping < 0.0 || j.stiffness < 0.0 || j.armature < 0.0 || j.frictionloss < 0.0)
      fail(n, "damping, stiffness, armature and frictionloss >= 0", "a negative one");
    if (number(n, "joint", cls, "ref", 0.0) != 0.0) unmapped(n, "ref not imported (Reeve's joints are 0 at load)");
    unmappedAttributes(n, "joint", cls, {"solreflimit", "solimplimit", "solreffriction", "solimpfriction", "margin"});
    model_.joints.push_back(j);
    model_.bodies[body].joints.push_back(static_cast<int>(model_.joints.size()) - 1);
  }

  int find(const Node& n, const char* attr, const std::string& kind, const auto& items) {
    const std::string name = text(n, attr);
    for (std::size_t i = 0; i < items.size(); ++i)
      if (items[i].name == name) return static_cast<int>(i);
    fail(n, "the name of a " + kind, "\"" + name + "\"");
  }

  // <contact>: its <exclude> pairs; explicit <pair>s are listed (Reeve
  // finds every pair the bodies' bits allow).
  void readContacts(const Node& section) {
    for (const Node& n : children(section)) {
      const std::string tag = n.xml.name();
      if (tag == "exclude")
        model_.contact_exclusions.emplace_back(find(n, "body1", "body", model_.bodies), find(n, "body2", "body", model_.bodies));
      else
        unmapped(n, "not imported (contacts come from the geoms' contype and conaffinity)");
    }
  }

  void readTendons(const Node& section) {
    for (const Node& n : children(section)) {
      const std::string tag = n.xml.name();
      const std::string cls = classOf(n, "main");
      Tendon t;
      t.origin = originOf(n);
      t.name = n.xml.attribute("name").value();
      if (tag == "fixed") {  // kept for the actuators that name it; not a cable
        t.spatial = false;
        model_.tendons.push_back(t);
        continue;
      }
      if (tag != "spatial") fail(n, "<spatial> or <fixed>", "<" + tag + ">");
      const auto range = lookup(n, "tendon", cls, "range");
      if (range) {
        const auto v = numbers(n, range, 2, 2);
        t.range = {v[0], v[1]};
      }
      t.limited = flag(n, "tendon", cls, "limited").value_or(autolimits_ && range);
      if (t.limited && !range) fail(n, "a range with limited=\"true\"", "none");
      t.stiffness = number(n, "tendon", cls, "stiffness", 0.0);
      t.damping = number(n, "tendon", cls, "damping", 0.0);
      t.frictionloss = number(n, "tendon", cls, "frictionloss", 0.0);
      if (const auto a = lookup(n, "tendon", cls, "springlength")) {
        const auto v = numbers(n, a, 1, 2);
        if (v[0] >= 0.0) t.springlength = v[0];
      }
      for (const Node& e : children(n)) {
        PathElement p;
        p.origin = originOf(e);
        const std::string etag = e.xml.name();
        if (etag == "site") {
          p.kind = PathElement::Kind::Site;
          p.index = find(e, "site", "site", model_.sites);
        } else if (etag == "geom") {
          p.kind = PathElement::Kind::Geom;
          p.index = find(e, "geom", "geom", model_.geoms);
          if (e.xml.attribute("sidesite")) p.sidesite = find(e, "sidesite", "site", model_.sites);
        } else if (etag == "pulley") {
          p.kind = PathElement::Kind::Pulley;
          p.divisor = number(e, "pulley", "", "divisor", 1.0);
        } else {
          fail(e, "<site>, <geom> or <pulley> in a spatial tendon", "<" + etag + ">");
        }
        t.path.push_back(p);
      }
      model_.tendons.push_back(t);
    }
  }

  void readActuators(const Node& section) {
    for (const Node& n : children(section)) {
      Actuator a;
      a.origin = originOf(n);
      a.name = n.xml.attribute("name").value();
      a.kind = n.xml.name();
      const std::string cls = classOf(n, "main");
      for (const char* target : {"joint", "tendon", "site", "body", "jointinparent"})
        if (const auto t = n.xml.attribute(target)) a.target = std::string(target) + " " + t.value();
      if (n.xml.attribute("joint")) a.joint = find(n, "joint", "joint", model_.joints);
      if (n.xml.attribute("tendon")) a.tendon = find(n, "tendon", "tendon", model_.tendons);
      if (const auto gear = lookup(n, a.kind, cls, "gear")) a.gear = numbers(n, gear, 1, 6)[0];
      a.kp = number(n, a.kind, cls, "kp", 1.0);
      a.kv = number(n, a.kind, cls, "kv", a.kind == "velocity" ? 1.0 : 0.0);
      const auto range = [&](const char* limited, const char* range_name, bool& on, std::array<double, 2>& r) {
        const auto given = lookup(n, a.kind, cls, range_name);
        if (given) {
          const auto v = numbers(n, given, 2, 2);
          r = {v[0], v[1]};
        }
        on = flag(n, a.kind, cls, limited).value_or(autolimits_ && given);
        if (on && !given) fail(n, std::string("a ") + range_name + " with " + limited + "=\"true\"", "none");
        if (on && !(r[0] <= r[1])) fail(n, std::string("a ") + range_name + " with lower <= upper", given.value());
      };
      range("ctrllimited", "ctrlrange", a.ctrllimited, a.ctrlrange);
      range("forcelimited", "forcerange", a.forcelimited, a.forcerange);
      if (a.kind == "muscle") {
        a.force = number(n, a.kind, cls, "force", -1.0);
        a.scale = number(n, a.kind, cls, "scale", 200.0);
        unmappedAttributes(n, a.kind, cls, {"lengthrange", "range", "lmin", "lmax", "vmax", "fpmax", "fvmax", "timeconst"});
      }
      model_.actuators.push_back(a);
    }
  }

  struct DefaultClass {
    std::string parent;
    std::map<std::string, std::vector<pugi::xml_node>> defaults;  // per tag, in the order given
  };

  struct MeshAsset {
    Origin origin;
    std::string path;  // the file, found as MuJoCo finds it (the model's folder, meshdir)
    Vec3 scale = Vec3::Ones();
    bool loaded = false;
    MeshMassProperties mass;   // scaled
    std::vector<Vec3> corners;  // its hull's, about its centre of mass
  };

  Model model_;
  std::vector<std::unique_ptr<Source>> sources_;
  std::map<std::string, MeshAsset> meshes_;
  std::string mesh_dir_;  // <compiler meshdir> (or assetdir), relative to the model's folder
  bool exact_mesh_inertia_ = false;  // <compiler exactmeshinertia>
  std::map<std::string, DefaultClass> classes_;
  std::map<std::pair<std::string, std::string>, std::vector<Origin>> unmapped_attributes_;  // per tag and attribute
  bool degrees_ = true;
  std::string eulerseq_ = "xyz";
  bool autolimits_ = true;
};

}  // namespace

double geomVolume(GeomType type, const Vec3& s) {
  constexpr double pi = std::numbers::pi;
  switch (type) {
    case GeomType::Sphere: return 4.0 / 3.0 * pi * s[0] * s[0] * s[0];
    case GeomType::Capsule: return pi * s[0] * s[0] * (2.0 * s[1] + 4.0 / 3.0 * s[0]);
    case GeomType::Ellipsoid: return 4.0 / 3.0 * pi * s[0] * s[1] * s[2];
    case GeomType::Cylinder: return pi * s[0] * s[0] * 2.0 * s[1];
    case GeomType::Box: return 8.0 * s[0] * s[1] * s[2];
    case GeomType::Plane:
    case GeomType::Mesh: return 0.0;
  }
  return 0.0;
}

Mat3 geomUnitInertia(GeomType type, const Vec3& s) {
  Vec3 d = Vec3::Zero();
  switch (type) {
    case GeomType::Sphere: d.setConstant(0.4 * s[0] * s[0]); break;
    case GeomType::Capsule: {
      // A cylinder of height l and two hemispheres (together a sphere), each
      // hemisphere's centre of mass 3 r / 8 beyond the cylinder's end.
      const double r = s[0], l = 2.0 * s[1];
      const double cylinder = l, sphere = 4.0 / 3.0 * r;  // their volumes over pi r^2
      const double total = cylinder + sphere;
      const double across = (cylinder * (3.0 * r * r + l * l) / 12.0 +
                             sphere * (0.4 * r * r + l * l / 4.0 + 3.0 * l * r / 8.0)) / total;
      d = Vec3(across, across, (cylinder * r * r / 2.0 + sphere * 0.4 * r * r) / total);
      break;
    }
    case GeomType::Ellipsoid:
      d = Vec3(s[1] * s[1] + s[2] * s[2], s[0] * s[0] + s[2] * s[2], s[0] * s[0] + s[1] * s[1]) / 5.0;
      break;
    case GeomType::Cylinder: {
      const double r2 = s[0] * s[0], l = 2.0 * s[1];
      d = Vec3((3.0 * r2 + l * l) / 12.0, (3.0 * r2 + l * l) / 12.0, r2 / 2.0);
      break;
    }
    case GeomType::Box:
      d = Vec3(s[1] * s[1] + s[2] * s[2], s[0] * s[0] + s[2] * s[2], s[0] * s[0] + s[1] * s[1]) / 3.0;
      break;
    case GeomType::Plane:
    case GeomType::Mesh: break;
  }
  return d.asDiagonal();
}

Model readModel(const std::string& path) {
  return Reader().read(path);
}

}  // namespace reeve::mjcf
