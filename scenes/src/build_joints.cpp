// "joints" (prismatic, spherical, fixed) and the limits and drives they
// share with "hinges": the checks the schema cannot make, then World::add...
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "build.h"
#include "describe.h"

namespace reeve::scene_detail {
namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;

// The bodies of a joint at `path`: known, "other" defaulting to "world",
// and two different ones.
std::pair<BodyId, BodyId> jointBodies(const json& j, const std::string& path,
                                      const BodyNames& names, const std::string& source) {
  const BodyId body = names.find(j.at("body"), path + "/body", source, false);
  const json other = j.value("other", json("world"));
  const BodyId other_id = names.find(other, path + "/other", source, true);
  if (other_id == body)
    throw SceneError(source, path + "/other",
                     "\"world\" or a body other than the joint's body " + literal(j.at("body")),
                     literal(other));
  return {body, other_id};
}

Vec3 nonZeroAxis(const json& j, const std::string& path, const std::string& what,
                 const std::string& source) {
  const Vec3 axis = vec3(j.at("axis"));
  if (axis.squaredNorm() == 0.0)
    throw SceneError(source, path + "/axis", "a non-zero " + what, literal(j.at("axis")));
  return axis;
}

// An angle (rad) at `pointer` within [-pi, pi].
double angleIn(const json& value, const std::string& pointer, const std::string& source) {
  const double angle = value.get<double>();
  if (!(std::abs(angle) <= kPi))
    throw SceneError(source, pointer, "an angle in [-pi, pi] rad", literal(value));
  return angle;
}

// The spring of an angle or position drive at `pointer` (schema-checked:
// stiffness > 0, damping >= 0, integration "implicit" or "trapezoidal")
// into `stiffness`, `damping` and `trapezoidal`, under the keys given;
// damping and integration only with a stiffness. Omitted: a rigid drive.
void driveSpring(const json& drive, const std::string& pointer, const char* stiffness_key,
                 const char* damping_key, double& stiffness, double& damping, bool& trapezoidal,
                 const std::string& source) {
  const auto k = drive.find(stiffness_key);
  const auto c = drive.find(damping_key);
  if (c != drive.end() && k == drive.end())
    throw SceneError(source, pointer + "/" + damping_key,
                     std::string("no ") + damping_key + " without " + stiffness_key +
                         " (damping belongs to a spring)",
                     literal(*c));
  const auto integration = drive.find("integration");
  if (integration != drive.end() && k == drive.end())
    throw SceneError(source, pointer + "/integration",
                     std::string("no integration without ") + stiffness_key + " (integration belongs to a spring)",
                     literal(*integration));
  if (k == drive.end()) return;
  stiffness = k->get<double>();
  damping = drive.value(damping_key, 0.0);
  trapezoidal = drive.value("integration", std::string("implicit")) == "trapezoidal";
}

// A drive's target at `pointer`, under `key`, or its "schedule" of
// {"t_s", key} keyframes (exactly one of the two), into `target` and
// `schedule`. Keyframe times strictly increasing.
void driveTarget(const json& drive, const std::string& pointer, const std::string& key, double& target,
                 std::vector<DriveKeyframe>& schedule, const std::string& source) {
  const auto constant = drive.find(key);
  const auto keyframes = drive.find("schedule");
  if ((constant == drive.end()) == (keyframes == drive.end()))
    throw SceneError(source, pointer, "exactly one of \"" + key + "\" (a constant target) and \"schedule\"",
                     constant == drive.end() ? "neither" : "both");
  if (constant != drive.end()) {
    target = constant->get<double>();
    return;
  }
  for (std::size_t k = 0; k < keyframes->size(); ++k) {
    const json& point = (*keyframes)[k];
    const DriveKeyframe keyframe{point.at("t_s").get<double>(), point.at(key).get<double>()};
    if (k > 0 && !(keyframe.time > schedule.back().time))
      throw SceneError(source, pointer + "/schedule/" + std::to_string(k) + "/t_s",
                       "a time after the previous keyframe's " + number(schedule.back().time) + " s",
                       literal(point.at("t_s")));
    schedule.push_back(keyframe);
  }
  target = scheduledTarget(schedule, 0.0);
}

// Passes World's own refusals on as a SceneError at the joint (the checks
// above should leave none).
template <class Add>
void addChecked(Add add, const std::string& path, const std::string& source) {
  try {
    add();
  } catch (const std::invalid_argument& e) {
    throw SceneError(source, path, "a joint the engine accepts", e.what());
  }
}

void addPrismatic(const json& j, const std::string& path, const BodyNames& names, World& world,
                  const std::string& source) {
  PrismaticDef def;
  std::tie(def.body, def.other) = jointBodies(j, path, names, source);
  def.anchor = vec3(j.at("anchor_m"));
  def.axis = nonZeroAxis(j, path, "prismatic axis", source);
  def.compliance = j.value("compliance", 0.0);
  if (const auto limit = j.find("limit"); limit != j.end()) {
    def.limit = {true, limit->at("lower_m").get<double>(), limit->at("upper_m").get<double>()};
    if (def.limit.lower > def.limit.upper)
      throw SceneError(source, path + "/limit/upper_m",
                       "a number >= lower_m " + number(def.limit.lower),
                       literal(limit->at("upper_m")));
  }
  if (const auto drive = j.find("drive"); drive != j.end()) {
    const bool velocity = drive->at("mode") == "velocity";
    def.drive.mode = velocity ? PrismaticDrive::Mode::Velocity : PrismaticDrive::Mode::Position;
    driveTarget(*drive, path + "/drive", velocity ? "target_m_per_s" : "target_m", def.drive.target,
                def.drive.schedule, source);
    def.drive.max_force = drive->value("max_force_N", 0.0);  // omitted: unlimited
    def.drive.until = drive->value("until_s", def.drive.until);  // omitted: always
    if (!velocity) {
      bool trapezoidal = false;
      driveSpring(*drive, path + "/drive", "stiffness_N_per_m", "damping_N_s_per_m", def.drive.stiffness,
                  def.drive.damping, trapezoidal, source);
      if (trapezoidal) def.drive.integration = PrismaticDrive::Integration::Trapezoidal;
    } else {
      def.drive.damping = drive->value("damping_N_s_per_m", 0.0);  // a damper; omitted: rigid
    }
  }
  addChecked([&] { world.addPrismatic(def); }, path, source);
}

void addSpherical(const json& j, const std::string& path, const BodyNames& names, World& world,
                  const std::string& source) {
  SphericalDef def;
  std::tie(def.body, def.other) = jointBodies(j, path, names, source);
  def.anchor = vec3(j.at("anchor_m"));
  def.compliance = j.value("compliance", 0.0);
  const bool limited = j.contains("swing_limit_rad") || j.contains("twist_limit");
  if (j.contains("axis")) {
    def.axis = nonZeroAxis(j, path, "twist axis", source);
  } else if (limited) {
    throw SceneError(source, path,
                     "required property \"axis\" (the twist axis of swing_limit_rad and "
                     "twist_limit)",
                     "nothing");
  }
  if (const auto swing = j.find("swing_limit_rad"); swing != j.end()) {
    def.swing_limit = {true, swing->get<double>()};
    if (def.swing_limit.max > kPi)
      throw SceneError(source, path + "/swing_limit_rad", "an angle in [0, pi] rad",
                       literal(*swing));
  }
  if (const auto twist = j.find("twist_limit"); twist != j.end()) {
    def.twist_limit = angleLimit(*twist, path + "/twist_limit", source);
    if (!def.swing_limit.enabled)
      throw SceneError(source, path, "swing_limit_rad of at most pi/2 with a twist_limit (the twist is ill-defined as the swing nears pi)",
                       "a twist_limit alone");
    if (def.swing_limit.max > kMaxSwingWithTwist)
      throw SceneError(source, path + "/swing_limit_rad", "at most pi/2 rad with a twist_limit (the twist is ill-defined as the swing nears pi)",
                       literal(j.at("swing_limit_rad")));
  }
  addChecked([&] { world.addSpherical(def); }, path, source);
}

void addFixed(const json& j, const std::string& path, const BodyNames& names, World& world,
              const std::string& source) {
  FixedDef def;
  std::tie(def.body, def.other) = jointBodies(j, path, names, source);
  def.anchor = vec3(j.at("anchor_m"));
  def.compliance = j.value("compliance", 0.0);
  addChecked([&] { world.addFixed(def); }, path, source);
}

}  // namespace

JointLimit angleLimit(const json& limit, const std::string& pointer, const std::string& source) {
  JointLimit result{true, angleIn(limit.at("lower_rad"), pointer + "/lower_rad", source),
                    angleIn(limit.at("upper_rad"), pointer + "/upper_rad", source)};
  if (result.lower > result.upper)
    throw SceneError(source, pointer + "/upper_rad",
                     "an angle >= lower_rad " + number(result.lower),
                     literal(limit.at("upper_rad")));
  return result;
}

HingeDrive hingeDrive(const json& drive, const std::string& pointer, const std::string& source) {
  HingeDrive result;
  if (drive.at("mode") == "velocity") {
    result.mode = HingeDrive::Mode::Velocity;
    driveTarget(drive, pointer, "target_rad_per_s", result.target, result.schedule, source);
    result.damping = drive.value("damping_N_m_s_per_rad", 0.0);  // a damper; omitted: rigid
  } else {
    result.mode = HingeDrive::Mode::Angle;
    driveTarget(drive, pointer, "target_rad", result.target, result.schedule, source);  // any number of turns
    bool trapezoidal = false;
    driveSpring(drive, pointer, "stiffness_N_m_per_rad", "damping_N_m_s_per_rad", result.stiffness,
                result.damping, trapezoidal, source);
    if (trapezoidal) result.integration = HingeDrive::Integration::Trapezoidal;
  }
  result.max_torque = drive.value("max_torque_N_m", 0.0);  // omitted: unlimited
  result.until = drive.value("until_s", result.until);      // omitted: always
  return result;
}

std::vector<JointKind> addJoints(const json& joints, const BodyNames& names, World& world,
                                 const std::string& source) {
  std::vector<JointKind> kinds;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const json& j = joints[i];
    const std::string path = "/joints/" + std::to_string(i);
    const std::string type = j.at("type").get<std::string>();
    if (type == "prismatic") {
      addPrismatic(j, path, names, world, source);
      kinds.push_back(JointKind::Prismatic);
    } else if (type == "spherical") {
      addSpherical(j, path, names, world, source);
      kinds.push_back(JointKind::Spherical);
    } else {  // the schema allows no other type
      addFixed(j, path, names, world, source);
      kinds.push_back(JointKind::Fixed);
    }
  }
  return kinds;
}

}  // namespace reeve::scene_detail
