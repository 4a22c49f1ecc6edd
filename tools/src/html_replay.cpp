#include "html_replay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "reeve/engine/convex_hull.h"
#include "reeve/render/cable_path.h"

namespace reeve {
namespace {

namespace fs = std::filesystem;

// Wrap points on circles at most this far apart (rad), as drawn in PNGs.
constexpr double kArcStepRad = 0.1;

std::string readViewerFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (!(in && text << in.rdbuf()))
    throw ViewerMissing("--html: cannot read the viewer's " + path.string() +
                        "; run `bash tools/setup.sh` (it installs three.js with npm ci in viewer/), or set "
                        "REEVE_VIEWER_DIR to a folder holding the viewer");
  return text.str();
}

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (n > 1) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (n > 2) v |= static_cast<unsigned char>(bytes[i + 2]);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? digits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// JSON for inside a <script> element, where "</script" would end it and
// "<!--" change how it is read: every '<' (only ever inside a JSON
// string) written as the escape \u003c.
std::string scriptSafe(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (const char ch : json) {
    if (ch == '<') out += "\\u003c";
    else out += ch;
  }
  return out;
}

// The template with each mark, in the order given (its order in the
// page), replaced once by its text; a mark is looked for only after the
// text put in before it, so a scene's own words are never taken for one.
std::string fill(const std::string& page, const std::vector<std::pair<std::string, std::string>>& marks) {
  std::string out;
  std::size_t from = 0;
  for (const auto& [mark, text] : marks) {
    const std::size_t at = page.find(mark, from);
    if (at == std::string::npos) throw std::runtime_error("--html: the viewer's replay.html has no " + mark);
    out.append(page, from, at - from);
    out += text;
    from = at + mark.size();
  }
  return out + page.substr(from);
}

std::string htmlEscaped(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      default: out += ch;
    }
  }
  return out;
}

void appendNumber(std::string& out, double value, const char* what) {
  if (!std::isfinite(value)) throw std::runtime_error(std::string("--html: ") + what + " is not finite");
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", value == 0.0 ? 0.0 : value);
  out += text;
}

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json shapeJson(const Shape& shape) {
  switch (shape.type) {
    case Shape::Type::Box: return {{"type", "box"}, {"half_extents", vec(shape.half_extents)}};
    case Shape::Type::Cylinder: return {{"type", "cylinder"}, {"radius", shape.radius}, {"half_length", shape.half_length}};
    case Shape::Type::Sphere: return {{"type", "sphere"}, {"radius", shape.radius}};
    case Shape::Type::Hull: {
      nlohmann::json vertices = nlohmann::json::array(), faces = nlohmann::json::array();
      for (const Vec3& v : shape.hull->vertices) vertices.push_back(vec(v));
      for (const ConvexHull::Face& f : shape.hull->faces) faces.push_back(f.vertices);
      return {{"type", "hull"}, {"vertices", vertices}, {"faces", faces}};
    }
  }
  return nullptr;
}

}  // namespace

fs::path viewerDir() {
  if (const char* dir = std::getenv("REEVE_VIEWER_DIR"); dir && *dir) return dir;
  // Installed (cmake --install): PREFIX/bin/reeve beside PREFIX/share/reeve/viewer.
  std::error_code ec;
  const fs::path installed = fs::read_symlink("/proc/self/exe", ec).parent_path().parent_path() / "share/reeve/viewer";
  if (!ec && fs::is_regular_file(installed / "replay.html", ec)) return installed;
  return REEVE_VIEWER_SOURCE_DIR;
}

HtmlReplay::HtmlReplay(const fs::path& path, bool replace, const Scene& scene)
    : out_(path, replace), scene_(scene) {
  const fs::path dir = viewerDir();
  page_ = readViewerFile(dir / "replay.html");
  viewer_js_ = readViewerFile(dir / "replay.js");
  three_js_ = readViewerFile(dir / "node_modules/three/build/three.module.min.js");
  orbit_js_ = readViewerFile(dir / "node_modules/three/examples/jsm/controls/OrbitControls.js");
}

void HtmlReplay::record() {
  const World& world = *scene_.world;
  const CableSystem& cables = *scene_.cables;
  const char* sep = frames_ == 0 ? "" : ",";
  times_ += sep;
  appendNumber(times_, world.time(), "the time");
  // Per frame: [x, y, z, qx, qy, qz, qw] per body; per cable its
  // polylines as flat [x, y, z, ...]; per cable its joints' tensions (N).
  poses_ += sep;
  poses_ += '[';
  for (BodyId id = 0; id < world.bodyCount(); ++id) {
    const BodyState& b = world.body(id);
    const double v[7] = {b.x.x(), b.x.y(), b.x.z(), b.q.x(), b.q.y(), b.q.z(), b.q.w()};
    for (int k = 0; k < 7; ++k) {
      if (id > 0 || k > 0) poses_ += ',';
      appendNumber(poses_, v[k], "a body's pose");
    }
  }
  poses_ += ']';
  paths_ += sep;
  paths_ += '[';
  tensions_ += sep;
  tensions_ += '[';
  const int cable_count = static_cast<int>(cables.cables().size());
  for (int c = 0; c < cable_count; ++c) {
    paths_ += c == 0 ? "[" : ",[";
    bool first_piece = true;
    for (const std::vector<Vec3>& piece : cablePaths(cables, c, kArcStepRad)) {
      paths_ += first_piece ? "[" : ",[";
      first_piece = false;
      for (std::size_t i = 0; i < piece.size(); ++i)
        for (int k = 0; k < 3; ++k) {
          if (i > 0 || k > 0) paths_ += ',';
          appendNumber(paths_, piece[i][k], "a cable's path");
        }
      paths_ += ']';
    }
    paths_ += ']';
    tensions_ += c == 0 ? "[" : ",[";
    const int joints = static_cast<int>(cables.cables()[c].joints.size());
    for (int j = 0; j < joints; ++j) {
      if (j > 0) tensions_ += ',';
      appendNumber(tensions_, cables.tension(c, j), "a cable's tension");
    }
    tensions_ += ']';
  }
  paths_ += ']';
  tensions_ += ']';
  ++frames_;
}

void HtmlReplay::close() {
  const World& world = *scene_.world;
  nlohmann::json bodies = nlohmann::json::array(), cables = nlohmann::json::array();
  for (BodyId id = 0; id < world.bodyCount(); ++id) {
    const BodyDef& def = world.bodyDef(id);
    bodies.push_back({{"name", def.name}, {"shape", shapeJson(def.shape)}, {"dynamic", world.bodyMass(id) > 0.0}});
  }
  for (const Cable& cable : scene_.cables->cables())
    cables.push_back({{"name", cable.name}, {"joints", cable.joints.size()}});
  nlohmann::json camera = nullptr;
  if (scene_.camera)
    camera = {{"eye", vec(scene_.camera->eye)}, {"target", vec(scene_.camera->target)},
              {"up", vec(scene_.camera->up)}, {"fov_y_deg", scene_.camera->fov_y_deg}};
  const nlohmann::json head = {{"name", scene_.name},     {"description", scene_.description},
                               {"frame_rate_hz", scene_.frame_rate_hz}, {"gravity", vec(world.settings().gravity)},
                               {"camera", camera},        {"bodies", bodies},
                               {"cables", cables}};
  std::string data = head.dump();
  data.pop_back();  // the closing brace: the frames follow
  data += ",\"frames\":{\"t\":[" + times_ + "],\"poses\":[" + poses_ + "],\"paths\":[" + paths_ +
          "],\"tensions\":[" + tensions_ + "]}}";
  const nlohmann::json imports = {
      {"imports",
       {{"three", "data:text/javascript;base64," + base64(three_js_)},
        {"three/addons/controls/OrbitControls.js", "data:text/javascript;base64," + base64(orbit_js_)}}}};
  out_.write(fill(page_, {{"/*REEVE_TITLE*/", htmlEscaped(scene_.name)},
                          {"/*REEVE_IMPORTS*/", scriptSafe(imports.dump())},
                          {"/*REEVE_DATA*/", scriptSafe(data)},
                          {"/*REEVE_VIEWER*/", viewer_js_}}));
  out_.close();
}

}  // namespace reeve
