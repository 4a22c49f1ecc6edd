#include "live_scene.h"

#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "reeve/engine/fp_exceptions.h"
#include "reeve/engine/thread_pool.h"
#include "reeve/render/cable_path.h"
#include "reeve/render/markers.h"
#include "reeve/scene/scene_file.h"
#include "reeve/scene/warnings.h"
#include "run_scene.h"
#include "viewer_files.h"

namespace reeve {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

static_assert(std::endian::native == std::endian::little, "the page reads the frames little-endian");

// The drag's spring: critically damped at this frequency (Hz) for any
// mass (MuJoCo's perturbation likewise scales with the body), its pull at
// most this acceleration (m/s^2), so a far target cannot fling the body.
constexpr double kDragHz = 1.5;
constexpr double kMaxDragAcceleration = 500.0;

const std::string kBuiltIn = "<built-in simple.json>";

struct CommandError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The value at `key` of a command, checked: "/key: expected WHAT, got VALUE".
[[noreturn]] void bad(const std::string& key, const std::string& expected, const json& got) {
  throw CommandError("/" + key + ": expected " + expected + ", got " + (got.is_null() ? "nothing" : got.dump()));
}

int integer(const json& command, const std::string& key, int low, int high) {
  const json& v = command.contains(key) ? command.at(key) : json();
  const std::string expected = "an integer " + std::to_string(low) + ".." + std::to_string(high);
  if (!v.is_number_integer()) bad(key, expected, v);
  const auto value = v.get<long long>();
  if (value < low || value > high) bad(key, expected, v);
  return static_cast<int>(value);
}

double number(const json& command, const std::string& key, double low, double high) {
  const json& v = command.contains(key) ? command.at(key) : json();
  char expected[96];
  std::snprintf(expected, sizeof expected, "a number %g..%g", low, high);
  if (!v.is_number() || !(v.get<double>() >= low && v.get<double>() <= high)) bad(key, expected, v);
  return v.get<double>();
}

Vec3 vector3(const json& command, const std::string& key, double bound) {
  const json& v = command.contains(key) ? command.at(key) : json();
  char expected[96];
  std::snprintf(expected, sizeof expected, "[x, y, z] with each of -%g..%g m", bound, bound);
  if (!v.is_array() || v.size() != 3) bad(key, expected, v);
  Vec3 out;
  for (int k = 0; k < 3; ++k) {
    if (!v[k].is_number() || !(std::abs(v[k].get<double>()) <= bound)) bad(key, expected, v);
    out[k] = v[k].get<double>();
  }
  return out;
}

// Refuses a key the command does not take (a typo must not pass unseen).
void onlyKeys(const json& command, std::initializer_list<const char*> keys) {
  for (const auto& [key, value] : command.items()) {
    bool known = key == "cmd";
    for (const char* k : keys) known |= key == k;
    if (!known) throw CommandError("/" + key + ": not a key of the '" + command.at("cmd").get<std::string>() + "' command");
  }
}

struct Bytes {
  std::string out;
  template <typename T>
  void put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    out.append(raw, sizeof(T));
  }
  void u32(std::size_t v) { put(static_cast<std::uint32_t>(v)); }
  void f64(double v) { put(v); }
};

std::string framed(unsigned char type, const std::string& payload) {
  Bytes b;
  b.u32(payload.size() + 1);
  b.out += static_cast<char>(type);
  return b.out + payload;
}

}  // namespace

std::string jsonMessage(const std::string& text) { return framed(kJsonMessage, text); }

LiveScene::LiveScene(fs::path file, Overrides overrides)
    : LiveScene(file.empty() ? std::string(defaultSceneJson()) : sceneJsonOf(file),
                file.empty() ? kBuiltIn : file.string(), overrides) {}

LiveScene::LiveScene(std::string text, std::string source, Overrides overrides)
    : source_(std::move(source)), text_(std::move(text)), overrides_(overrides) {
  start(parseScene(text_, source_));
}

void LiveScene::start(Scene scene) {
  drag_.reset();
  scene_ = std::move(scene);
  SolverSettings& s = scene_.world->settings();
  if (overrides_.substeps) s.substeps = *overrides_.substeps;
  if (overrides_.iterations) s.iterations = *overrides_.iterations;
  if (overrides_.solver) s.solver = *overrides_.solver;
  scene_.world->setThreads(overrides_.threads.value_or(ThreadPool::cores()));
  if (s.solver == SolverKind::GaussSeidel) s.projection = Projection::End;  // the start projection is the direct solver's
  ++generation_;
  frame_ = 0;
  last_iterations_ = 0;
  physics_ms_ = 0.0;
  steps_wanted_ = 0;
  ended_ = false;
  failure_.reset();
  slipping_.clear();
  for (const Cable& cable : scene_.cables->cables()) {
    slipping_.emplace_back();
    for (const Link& link : cable.links) slipping_.back().push_back(link.slipping);
  }
}

void LiveScene::reloadFile(const fs::path& file) { reload(sceneJsonOf(file)); }

void LiveScene::reload(const std::string& text) {
  Scene scene = parseScene(text, source_);
  text_ = text;
  start(std::move(scene));
  playing_ = true;  // an edit is made to be seen running
}

std::optional<std::string> LiveScene::command(const std::string& text) {
  if (text.size() > kMaxCommandBytes)
    return "a command is at most " + std::to_string(kMaxCommandBytes) + " bytes, got " + std::to_string(text.size());
  const json command = [&] {
    const FloatingPointExceptionsMasked overflow_is_tested;  // strtod on "1e400": refused below, not trapped
    return json::parse(text, nullptr, /*allow_exceptions=*/false);
  }();
  if (command.is_discarded()) return "expected a JSON object, got text that is not JSON";
  if (!command.is_object()) return "expected a JSON object, got " + command.dump().substr(0, 80);
  if (!command.contains("cmd") || !command.at("cmd").is_string())
    return "/cmd: expected one of play, pause, step, reset, set, drive, winch, drag, release";
  const std::string cmd = command.at("cmd").get<std::string>();
  World& world = *scene_.world;
  try {
    if (cmd == "play" || cmd == "pause" || cmd == "reset" || cmd == "release") {
      onlyKeys(command, {});
      if (cmd == "reset") start(parseScene(text_, source_));
      else if (cmd == "release") releaseDrag();
      else {
        playing_ = cmd == "play";
        steps_wanted_ = 0;
      }
    } else if (cmd == "step") {
      onlyKeys(command, {"frames"});
      const int frames = command.contains("frames") ? integer(command, "frames", 1, 1000) : 1;
      playing_ = false;
      steps_wanted_ += frames;
    } else if (cmd == "set") {
      onlyKeys(command, {"substeps", "iterations", "solver", "rtf"});
      if (command.size() < 2) throw CommandError("/: expected substeps, iterations, solver or rtf to set");
      Overrides next = overrides_;
      if (command.contains("substeps")) next.substeps = integer(command, "substeps", 1, 100000);
      if (command.contains("iterations")) next.iterations = integer(command, "iterations", 1, 100000);
      if (command.contains("solver")) {
        const json& v = command.at("solver");
        const auto solver = v.is_string() ? solverMethodFromName(v.get<std::string>()) : std::nullopt;
        if (!solver) bad("solver", "\"direct\" or \"gauss-seidel\"", v);
        next.solver = *solver;
      }
      const double rtf = command.contains("rtf") ? number(command, "rtf", kMinRealTimeFactor, kMaxRealTimeFactor) : rtf_;
      overrides_ = next;
      rtf_ = rtf;
      SolverSettings& s = world.settings();
      if (next.substeps) s.substeps = *next.substeps;
      if (next.iterations) s.iterations = *next.iterations;
      if (next.solver) s.solver = *next.solver;
      if (s.solver == SolverKind::GaussSeidel) s.projection = Projection::End;
    } else if (cmd == "drive") {
      onlyKeys(command, {"hinge", "target"});
      const int count = static_cast<int>(world.hinges().size());
      if (count == 0) throw CommandError("/hinge: the scene has no hinges");
      const int i = integer(command, "hinge", 0, count - 1);
      HingeDrive& drive = world.hinge(i).drive;
      if (drive.mode == HingeDrive::Mode::None) throw CommandError("/hinge: hinge " + std::to_string(i) + " has no drive");
      drive.target = number(command, "target", -1e9, 1e9);
      drive.schedule.clear();  // the page's target holds from now on
    } else if (cmd == "winch") {
      onlyKeys(command, {"cable", "speed"});
      const int count = static_cast<int>(scene_.cables->cables().size());
      if (count == 0) throw CommandError("/cable: the scene has no cables");
      const int c = integer(command, "cable", 0, count - 1);
      const Cable& cable = scene_.cables->cables()[c];
      if (!cable.winch) throw CommandError("/cable: cable '" + cable.name + "' has no winch");
      WinchDef winch = *cable.winch;
      winch.speed = number(command, "speed", -winch.max_speed, winch.max_speed);
      if (!std::isfinite(winch.speed)) bad("speed", "a finite speed", command.at("speed"));
      winch.target_stored.reset();
      winch.schedule.clear();
      try {
        scene_.cables->setWinch(c, winch);
      } catch (const std::invalid_argument& e) {
        throw CommandError(std::string("/speed: ") + e.what());
      }
    } else if (cmd == "drag") {
      onlyKeys(command, {"body", "point", "target"});
      const int i = integer(command, "body", 0, world.bodyCount() - 1);
      if (world.bodyMass(i) == 0.0) throw CommandError("/body: body '" + world.bodyDef(i).name + "' is not dynamic");
      const Vec3 point = vector3(command, "point", 1e3), target = vector3(command, "target", 1e6);
      if (!drag_ || drag_->body != i) {
        releaseDrag();
        const BodyState& b = world.body(i);
        drag_ = Drag{i, point, target, b.applied_force, b.applied_torque};
      }
      drag_->point = point;
      drag_->target = target;
    } else {
      return "/cmd: expected one of play, pause, step, reset, set, drive, winch, drag, release, got \"" + cmd + "\"";
    }
  } catch (const CommandError& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

void LiveScene::applyDrag() {
  if (!drag_) return;
  BodyState& b = scene_.world->body(drag_->body);
  const double mass = scene_.world->bodyMass(drag_->body);
  const double w = 2.0 * std::numbers::pi * kDragHz;
  const Vec3 arm = b.q * drag_->point;
  const Vec3 speed = b.v + b.omega.cross(arm);
  Vec3 pull = w * w * (drag_->target - (b.x + arm)) - 2.0 * w * speed;  // m/s^2
  if (const double a = pull.norm(); a > kMaxDragAcceleration) pull *= kMaxDragAcceleration / a;
  b.applied_force = drag_->force + mass * pull;
  b.applied_torque = drag_->torque + arm.cross(mass * pull);
}

void LiveScene::releaseDrag() {
  if (!drag_) return;
  BodyState& b = scene_.world->body(drag_->body);
  b.applied_force = drag_->force;
  b.applied_torque = drag_->torque;
  drag_.reset();
}

void LiveScene::stepFrame() {
  if (failure_) return;
  if (steps_wanted_ > 0) --steps_wanted_;
  applyDrag();
  const auto t0 = std::chrono::steady_clock::now();
  scene_.world->step(frameSeconds());
  physics_ms_ = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  last_iterations_ = scene_.world->lastStepIterations();
  ++frame_;
  failure_ = stopReason(scene_);
  if (!ended_ && static_cast<int>(frame_) >= scene_.frameCount()) {
    ended_ = true;
    playing_ = false;
  }
}

std::string LiveScene::sceneMessage() const {
  json head = sceneHead(scene_);
  head["type"] = "scene";
  head["generation"] = generation_;
  head["file"] = source_;
  json warnings = json::array();
  for (const SceneWarning& w : sceneWarnings(scene_)) warnings.push_back({{"json_path", w.json_path}, {"message", w.message}});
  head["warnings"] = warnings;
  return jsonMessage(head.dump());
}

std::string LiveScene::statusMessage() const {
  const SolverSettings& s = scene_.world->settings();
  const json status = {{"type", "status"},
                       {"generation", generation_},
                       {"frame", frame_},
                       {"t", scene_.world->time()},
                       {"playing", playing()},
                       {"failure", failure_ ? json(*failure_) : json()},
                       {"ended", ended_},
                       {"duration_s", scene_.duration_s},
                       {"rtf", rtf_},
                       {"settings",
                        {{"substeps", s.substeps},
                         {"iterations", s.iterations},
                         {"solver", solverMethodName(s.solver)},
                         {"projection", s.projection == Projection::Start ? "start" : "end"}}},
                       {"dragging", drag_ ? json(drag_->body) : json()}};
  return jsonMessage(status.dump());
}

std::string LiveScene::frameMessage() const {
  const World& world = *scene_.world;
  const CableSystem& cables = *scene_.cables;
  Bytes b;
  b.u32(generation_);
  b.u32(frame_);
  b.f64(world.time());
  b.u32(static_cast<std::size_t>(last_iterations_));
  b.f64(physics_ms_);
  b.u32(static_cast<std::size_t>(world.bodyCount()));
  for (BodyId id = 0; id < world.bodyCount(); ++id) {
    const BodyState& s = world.body(id);
    for (const double v : {s.x.x(), s.x.y(), s.x.z(), s.q.x(), s.q.y(), s.q.z(), s.q.w(), s.v.x(), s.v.y(), s.v.z()})
      b.f64(v);
  }
  b.u32(world.hinges().size());
  for (int i = 0; i < static_cast<int>(world.hinges().size()); ++i) {
    b.f64(world.hingeAngle(i));
    b.f64(world.hingeDriveTorque(i));
  }
  b.u32(cables.cables().size());
  for (int c = 0; c < static_cast<int>(cables.cables().size()); ++c) {
    const int joints = static_cast<int>(cables.cables()[c].joints.size());
    b.u32(static_cast<std::size_t>(joints));
    for (int j = 0; j < joints; ++j) {
      b.f64(cables.tension(c, j));
      b.f64(cables.restLength(c, j));
      const bool enabled = cables.jointEnabled(c, j);
      for (const Vec3& p : {cables.startPoint(c, j), cables.endPoint(c, j)})
        for (int k = 0; k < 3; ++k) b.put(enabled ? static_cast<float>(p[k]) : std::numeric_limits<float>::quiet_NaN());
    }
    const auto polylines = [&](const std::vector<std::vector<Vec3>>& pieces) {
      b.u32(pieces.size());
      for (const std::vector<Vec3>& piece : pieces) {
        b.u32(piece.size());
        for (const Vec3& p : piece)
          for (int k = 0; k < 3; ++k) b.put(static_cast<float>(p[k]));
      }
    };
    polylines(cablePaths(cables, c, kViewerArcStepRad));
    polylines(viewerSpoolCoils(cables, c));
  }
  const std::vector<Marker> markers = linkMarkers(cables);
  b.u32(markers.size());
  for (const Marker& m : markers) {
    b.u32(static_cast<std::size_t>(m.kind));
    for (int k = 0; k < 3; ++k) b.put(static_cast<float>(m.at[k]));
  }
  return framed(kFrameMessage, b.out);
}

std::vector<std::string> LiveScene::takeEventMessages() {
  std::vector<std::string> out;
  for (const CableEvent& e : scene_.cables->takeEvents()) {
    json event = {{"type", "event"},
                  {"generation", generation_},
                  {"time_s", e.time_s},
                  {"cable", scene_.cables->cables()[e.cable].name},
                  {"link", e.link},
                  {"event", eventName(e.kind)},
                  {"orientation", e.orientation > 0 ? "ccw" : "cw"}};
    if (e.kind == CableEvent::Kind::Break) event["tension_N"] = e.tension;
    if (e.kind == CableEvent::Kind::SpanRunsOut) event["message"] = spanRunsOutMessage(e, scene_);
    out.push_back(jsonMessage(event.dump()));
  }
  const std::vector<Cable>& cables = scene_.cables->cables();
  for (std::size_t c = 0; c < cables.size(); ++c)
    for (std::size_t k = 0; k < cables[c].links.size(); ++k) {
      const Link& link = cables[c].links[k];
      if (!(link.mu > 0.0 && std::isfinite(link.mu)) || static_cast<bool>(slipping_[c][k]) == link.slipping) continue;
      slipping_[c][k] = link.slipping;
      const json event = {{"type", "event"}, {"generation", generation_},        {"time_s", scene_.world->time()},
                          {"cable", cables[c].name}, {"link", k}, {"event", link.slipping ? "slips" : "sticks"}};
      out.push_back(jsonMessage(event.dump()));
    }
  return out;
}

}  // namespace reeve
