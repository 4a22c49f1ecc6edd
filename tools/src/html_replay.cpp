#include "html_replay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "reeve/render/cable_path.h"
#include "reeve/render/markers.h"

namespace reeve {
namespace {

namespace fs = std::filesystem;

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

}  // namespace

HtmlReplay::HtmlReplay(const fs::path& path, bool replace, const Scene& scene)
    : out_(path, replace), scene_(scene) {
  page_ = readViewerFile("replay.html", "--html");
  viewer_js_ = readViewerFile("replay.js", "--html");
  view3d_js_ = readViewerFile("view3d.js", "--html");
  three_js_ = readViewerFile(kThreeModule, "--html");
  orbit_js_ = readViewerFile(kOrbitControls, "--html");
}

void HtmlReplay::record() {
  const World& world = *scene_.world;
  const CableSystem& cables = *scene_.cables;
  const char* sep = frames_ == 0 ? "" : ",";
  times_ += sep;
  appendNumber(times_, world.time(), "the time");
  // Per frame: [x, y, z, qx, qy, qz, qw] per body; per cable its
  // polylines (paths, then spool coils) as flat [x, y, z, ...], its
  // joints' tensions (N) and end points ([x, y, z] twice a joint, null
  // while disabled); the link markers as flat [kind, x, y, z, ...].
  const auto numbers = [](std::string& out, std::initializer_list<double> values, const char* what) {
    for (const double v : values) {
      if (out.back() != '[') out += ',';
      appendNumber(out, v, what);
    }
  };
  poses_ += sep;
  poses_ += '[';
  for (BodyId id = 0; id < world.bodyCount(); ++id) {
    const BodyState& b = world.body(id);
    numbers(poses_, {b.x.x(), b.x.y(), b.x.z(), b.q.x(), b.q.y(), b.q.z(), b.q.w()}, "a body's pose");
  }
  poses_ += ']';
  for (std::string* list : {&paths_, &tensions_, &spans_}) *list += std::string(sep) + '[';
  const int cable_count = static_cast<int>(cables.cables().size());
  for (int c = 0; c < cable_count; ++c) {
    for (std::string* list : {&paths_, &tensions_, &spans_}) *list += c == 0 ? "[" : ",[";
    std::vector<std::vector<Vec3>> pieces = cablePaths(cables, c, kViewerArcStepRad);
    for (std::vector<Vec3>& coil : viewerSpoolCoils(cables, c)) pieces.push_back(std::move(coil));
    for (const std::vector<Vec3>& piece : pieces) {
      paths_ += paths_.back() == '[' ? "[" : ",[";
      for (const Vec3& p : piece) numbers(paths_, {p.x(), p.y(), p.z()}, "a cable's path");
      paths_ += ']';
    }
    const int joints = static_cast<int>(cables.cables()[c].joints.size());
    for (int j = 0; j < joints; ++j) {
      numbers(tensions_, {cables.tension(c, j)}, "a cable's tension");
      if (!cables.jointEnabled(c, j)) {
        spans_ += spans_.back() == '[' ? "null,null,null,null,null,null" : ",null,null,null,null,null,null";
        continue;
      }
      const Vec3 a = cables.startPoint(c, j), b = cables.endPoint(c, j);
      numbers(spans_, {a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}, "a span's end");
    }
    for (std::string* list : {&paths_, &tensions_, &spans_}) *list += ']';
  }
  for (std::string* list : {&paths_, &tensions_, &spans_}) *list += ']';
  markers_ += std::string(sep) + '[';
  for (const Marker& m : linkMarkers(cables))
    numbers(markers_, {static_cast<double>(m.kind), m.at.x(), m.at.y(), m.at.z()}, "a link marker");
  markers_ += ']';
  ++frames_;
}

void HtmlReplay::recordEvents(const std::vector<CableEvent>& events) {
  for (const CableEvent& e : events) {
    if (!events_.empty()) events_ += ',';
    nlohmann::json event = {{"time_s", e.time_s}, {"cable", scene_.cables->cables()[e.cable].name},
                            {"link", e.link},     {"event", eventName(e.kind)}};
    events_ += event.dump();
  }
}

void HtmlReplay::close() {
  const nlohmann::json head = sceneHead(scene_);
  std::string data = head.dump();
  data.pop_back();  // the closing brace: the frames follow
  data += ",\"events\":[" + events_ + "],\"frames\":{\"t\":[" + times_ + "],\"poses\":[" + poses_ +
          "],\"paths\":[" + paths_ + "],\"tensions\":[" + tensions_ + "],\"spans\":[" + spans_ +
          "],\"markers\":[" + markers_ + "]}}";
  const nlohmann::json imports = {
      {"imports",
       {{"three", "data:text/javascript;base64," + base64(three_js_)},
        {"three/addons/controls/OrbitControls.js", "data:text/javascript;base64," + base64(orbit_js_)},
        {"reeve/view3d.js", "data:text/javascript;base64," + base64(view3d_js_)}}}};
  out_.write(fill(page_, {{"/*REEVE_TITLE*/", htmlEscaped(scene_.name)},
                          {"/*REEVE_IMPORTS*/", scriptSafe(imports.dump())},
                          {"/*REEVE_DATA*/", scriptSafe(data)},
                          {"/*REEVE_VIEWER*/", viewer_js_}}));
  out_.close();
}

}  // namespace reeve
