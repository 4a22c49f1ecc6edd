#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common.h"
#include "reeve/machines/scene_json.h"

namespace reeve::machines {
namespace {

// Skilling's TransposetoAxes for 3 dimensions of `bits` bits: the Hilbert
// index in transposed form (its bits dealt round-robin to x[0], x[1],
// x[2], most significant first) becomes the point's coordinates.
void transposeToAxes(unsigned x[3], int bits) {
  const unsigned N = 2u << (bits - 1);
  unsigned t = x[2] >> 1;  // Gray decode
  for (int i = 2; i > 0; --i) x[i] ^= x[i - 1];
  x[0] ^= t;
  for (unsigned Q = 2; Q != N; Q <<= 1) {  // undo excess work
    const unsigned P = Q - 1;
    for (int i = 2; i >= 0; --i) {
      if (x[i] & Q) {
        x[0] ^= P;
      } else {
        t = (x[0] ^ x[i]) & P;
        x[0] ^= t;
        x[i] ^= t;
      }
    }
  }
}

// A unit vector normal to the unit `d`.
Vec3 normalTo(const Vec3& d) { return d.cross(std::abs(d.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).normalized(); }

}  // namespace

std::vector<Vec3> hilbertCurve(int level) {
  if (level < 1 || level > 6) throw std::invalid_argument("hilbertCurve: level must be in [1, 6]");
  const unsigned count = 1u << (3 * level);
  std::vector<Vec3> points;
  points.reserve(count);
  for (unsigned h = 0; h < count; ++h) {
    unsigned x[3] = {0, 0, 0};
    for (int bit = 3 * level - 1, k = 0; bit >= 0; --bit, ++k)
      if (h >> bit & 1u) x[k % 3] |= 1u << (level - 1 - k / 3);
    transposeToAxes(x, level);
    points.emplace_back(x[0], x[1], x[2]);
  }
  return points;
}

namespace {

// + 0.0 turns -0 into 0, so no "-0.0" is written.
nlohmann::ordered_json vec(const Vec3& v) { return nlohmann::ordered_json::array({v.x() + 0.0, v.y() + 0.0, v.z() + 0.0}); }

// The body orientation that turns local z (a cylinder's axis) onto the
// unit `axis`: about z x axis, or half a turn about x for -z.
nlohmann::ordered_json turningZOnto(const Vec3& axis) {
  const Vec3 about = Vec3::UnitZ().cross(axis);
  if (about.norm() < 1e-12)
    return {{"axis", vec(Vec3::UnitX())}, {"angle_rad", axis.z() > 0.0 ? 0.0 : M_PI}};
  return {{"axis", vec(about.normalized())}, {"angle_rad", std::acos(std::clamp(axis.z(), -1.0, 1.0))}};
}

const char* orientationName(int orientation) { return orientation > 0 ? "ccw" : "cw"; }

// Rounded to 1 nm so that the file does not depend on the last bits of
// the tangent geometry.
double nanometres(double x) { return std::round(x * 1e9) / 1e9; }

}  // namespace

nlohmann::ordered_json hilbertSceneJson(const HilbertSpec& spec) {
  if (spec.level < 1 || spec.level > 4) throw std::invalid_argument("hilbert: level must be in [1, 4]");
  if (!(spec.slack_m >= 0.0) || !(spec.pitch_m > 2.0 * spec.radius_m) || !(spec.radius_m > 0.0) ||
      !(spec.wheel_kg > 0.0) || !(spec.brake_torque_Nm >= 0.0) || !(spec.motor_torque_Nm > 0.0))
    throw std::invalid_argument(
        "hilbert: needs slack >= 0, radius > 0, pitch > 2 radius, masses and torques > 0 (brake >= 0)");
  const bool braked = spec.brake_torque_Nm > 0.0;
  const std::vector<Vec3> curve = hilbertCurve(spec.level);
  const int n = static_cast<int>(curve.size());
  // The cable's direction leaving each point: along the curve, and down
  // from the last wheel.
  std::vector<Vec3> out(n);
  for (int k = 0; k + 1 < n; ++k) out[k] = curve[k + 1] - curve[k];
  out[n - 1] = -Vec3::UnitY();
  // Axes: normal to the turn where the curve turns (the cable then goes
  // round the wheel counter-clockwise about it), the previous wheel's where
  // it runs straight (the cable then crosses over, clockwise).
  std::vector<Vec3> axis(n);
  std::vector<int> orientation(n, 1);
  axis[0] = normalTo(out[0]);
  for (int k = 1; k < n; ++k) {
    const Vec3 turn = out[k - 1].cross(out[k]);
    if (turn.norm() > 1e-9) {
      axis[k] = turn.normalized();
    } else {
      axis[k] = std::abs(axis[k - 1].dot(out[k])) < 1e-9 ? axis[k - 1] : normalTo(out[k]);
      orientation[k] = -orientation[k - 1];
    }
  }
  using json = nlohmann::ordered_json;
  const std::string name = "hilbert" + std::to_string(spec.level) + (spec.slack_m > 0.0 ? "_loose" : "");
  const double speed = spec.motor_speed_rad_per_s * spec.radius_m;
  json doc;
  doc["$schema"] = "scene.schema.json";  // for editors, beside the shipped scenes
  doc["name"] = name;
  std::string description =
      "Paper Fig. 18 / Fig. 1 right, written by `reeve generate hilbert --level " + std::to_string(spec.level) +
      (spec.slack_m > 0.0 ? " --slack " + json(spec.slack_m).dump() : std::string()) +
      (braked != (spec.level < 3) ? (braked ? " --end brake" : " --end load") : std::string()) +
      (spec.wheel_kg != 1.0 ? " --wheel-kg " + json(spec.wheel_kg).dump() : std::string()) + "`: " + std::to_string(n) +
      " wheels at the points of a level-" + std::to_string(spec.level) +
      " 3D Hilbert curve, one cable along it. Each wheel is hinged to the world at its centre with its axis normal "
      "to the curve's turn there, so its cable plane holds the directions of both spans that meet it; where the "
      "curve runs straight the wheel takes its neighbour's axis and the cable crosses over. The spans leave the "
      "rims up to one radius out of the plane, as in the paper's figures (the paper: the wheels would have to be "
      "indented). A motor on the first wheel, a drum, winds the cable in at " +
      json(speed).dump() + " m/s (surface speed, torque at most " + json(spec.motor_torque_Nm).dump() + " N m); ";
  description += braked ? "the last wheel is a drum paying it out against a brake of " +
                              json(spec.brake_torque_Nm).dump() + " N m. "
                        : "a " + json(spec.load_kg).dump() + " kg load hangs " + json(spec.load_drop_m).dump() +
                              " m below the last wheel. ";
  description += spec.slack_m > 0.0
                     ? "Every span starts " + json(spec.slack_m).dump() +
                           " m slack, so wheel k starts when the motor has taken in the slack of the k spans before "
                           "it, one after another. "
                     : "The cable is taut: every wheel starts at once. ";
  description += std::to_string(n - 1 + (braked ? 0 : 1)) + " cable joints (paper Table 1: " +
                 (spec.level == 2 ? "62" : spec.level == 3 ? "498" : "none") +
                 "; the paper's drums and ends differ by a few wheels).";
  doc["description"] = description;
  doc["solver"] = {{"frame_rate_hz", 60},
                   {"substeps", spec.budget.substeps},
                   {"iterations", spec.budget.iterations},
                   {"method", solverMethodName(spec.budget.solver)},
                   {"gravity_m_per_s2", vec(Vec3(0.0, -spec.gravity, 0.0))}};
  doc["duration_s"] = spec.duration_s;
  json bodies = json::array(), hinges = json::array(), links = json::array();
  const double stored = 2.0 * spec.pitch_m * n;  // enough for any run
  for (int k = 0; k < n; ++k) {
    const Vec3 at = spec.pitch_m * curve[k];
    const std::string wheel = "wheel" + std::to_string(k);
    bodies.push_back({{"name", wheel},
                      {"shape", {{"type", "cylinder"}, {"radius_m", spec.radius_m}, {"half_length_m", 0.05}}},
                      {"mass_kg", spec.wheel_kg},
                      {"position_m", vec(at)},
                      {"orientation", turningZOnto(axis[k])}});
    json hinge = {{"body", wheel}, {"anchor_m", vec(at)}, {"axis", vec(axis[k])}};
    json link = {{"body", wheel}, {"type", "rolling"}, {"orientation", orientationName(orientation[k])}};
    if (k == 0) {
      // Winding in turns the drum against the cable's travel round it.
      hinge["drive"] = {{"mode", "velocity"},
                        {"target_rad_per_s", -orientation[0] * spec.motor_speed_rad_per_s},
                        {"max_torque_N_m", spec.motor_torque_Nm}};
      link = {{"body", wheel}, {"type", "hybrid"}, {"orientation", orientationName(orientation[0])}, {"stored_m", stored}};
    } else if (k == n - 1 && braked) {
      hinge["drive"] = {{"mode", "velocity"}, {"target_rad_per_s", 0.0}, {"max_torque_N_m", spec.brake_torque_Nm}};
      link = {{"body", wheel}, {"type", "hybrid"}, {"orientation", orientationName(orientation[k])}, {"stored_m", stored}};
    }
    hinges.push_back(hinge);
    links.push_back(link);
  }
  if (!braked) {
    // The load hangs below the last wheel's departure point: the wheel lies
    // on the left of the cable's travel for a counter-clockwise link.
    const Vec3 last = spec.pitch_m * curve[n - 1];
    const Vec3 departure = last - orientation[n - 1] * spec.radius_m * axis[n - 1].cross(out[n - 1]);
    const double box = 0.1;
    bodies.push_back({{"name", "load"},
                      {"shape", {{"type", "box"}, {"half_extents_m", vec(Vec3::Constant(box))}}},
                      {"mass_kg", spec.load_kg},
                      {"position_m", vec(departure - Vec3(0.0, spec.load_drop_m + box, 0.0))}});
    links.push_back({{"body", "load"}, {"type", "attachment"}, {"point_m", vec(Vec3(0.0, box, 0.0))}});
  }
  doc["bodies"] = bodies;
  doc["hinges"] = hinges;
  doc["cables"] = json::array({{{"name", "rope"}, {"links", links}}});
  const double side = spec.pitch_m * ((1 << spec.level) - 1);
  const Vec3 centre = Vec3::Constant(0.5 * side);
  doc["camera"] = {{"eye_m", vec((centre + side * Vec3(1.6, 1.1, 2.4)).unaryExpr(&nanometres))}, {"target_m", vec(centre)}, {"fov_y_deg", 40}};
  if (spec.slack_m > 0.0) {
    // Slack on top of the taut spans' lengths, which the cable library
    // measures from the same file without slack.
    const Scene taut = parseScene(doc.dump(), name);
    json rest = json::array();
    for (int j = 0; j < static_cast<int>(taut.cables->cables()[0].joints.size()); ++j)
      rest.push_back(nanometres(taut.cables->restLength(0, j) + spec.slack_m));
    doc["cables"][0]["rest_length_m"] = rest;
  }
  return doc;
}

HilbertSpec hilbertSceneSpec(int level, double slack_m) {
  HilbertSpec spec;
  spec.level = level;
  spec.slack_m = slack_m;
  // Every level ends at a drum paying the cable out against a 10 N m
  // brake, as in the paper (level 3 ended at a 10 kg load until issue 29,
  // DESIGN.md "A cap the last solve ended at..."); brake 0 makes the load.
  spec.brake_torque_Nm = 10.0;
  spec.load_kg = 10.0;
  spec.load_drop_m = 3.0;
  spec.motor_speed_rad_per_s = level >= 3 ? 1.0 : 8.0;
  spec.gravity = 9.81;
  spec.budget = {1, 10};
  spec.duration_s = slack_m > 0.0 || level >= 3 ? 10.0 : 5.0;
  return spec;
}

Hilbert hilbert(const HilbertSpec& spec) {
  Hilbert m;
  m.spec = spec;
  const nlohmann::ordered_json doc = hilbertSceneJson(spec);
  m.scene = parseScene(doc.dump(), doc["name"].get<std::string>());
  const World& world = *m.scene.world;
  for (std::size_t k = 0; k < doc["bodies"].size(); ++k) {
    const std::string name = doc["bodies"][k]["name"];
    if (name != "load") m.wheels.push_back(*world.findBody(name));
  }
  if (auto load = world.findBody("load")) m.load = *load;
  m.motor = 0;  // hinges are in wheel order
  return m;
}

}  // namespace reeve::machines
