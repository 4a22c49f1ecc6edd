// Scene document -> World, hinges, CableSystem: the checks a schema cannot
// make, then construction. The document has passed validateSceneSchema, so
// keys and types are as the schema says.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <unordered_map>
#include <vector>

#include "reeve/scene/scene.h"

namespace reeve::scene_detail {

/// Builds the scene of a schema-valid `document`. Throws SceneError naming
/// `source` for what the schema cannot check (see parseScene).
Scene buildScene(const nlohmann::json& document, const std::string& source);

/// The bodies of a scene by name, and their names in scene order.
struct BodyNames {
  std::unordered_map<std::string, BodyId> ids;
  std::vector<std::string> ordered;

  /// The body named by the string `name` found at `pointer`; "world" gives
  /// kWorldBody when `world_allowed`. Throws SceneError for other names.
  BodyId find(const nlohmann::json& name, const std::string& pointer, const std::string& source,
              bool world_allowed) const;
};

/// Where a body's origin lies in the frame its scene entry's body-local
/// coordinates are given in (m): a hull's centre of mass in the frame of
/// its vertices, zero for other shapes, which are centred on their origin.
Vec3 hullOrigin(const Shape& shape);

/// Adds "bodies" (build_bodies.cpp): unique names other than "world",
/// exactly one of density or mass when dynamic, nothing of either and no
/// velocity or damping when static, non-zero orientation axes.
BodyNames addBodies(const nlohmann::json& bodies, World& world, const std::string& source);

/// Excludes "contact_exclusions" (build_bodies.cpp): pairs of two
/// different known bodies (not "world").
void excludeContacts(const nlohmann::json& pairs, const BodyNames& names, World& world, const std::string& source);

/// Adds "hinges" (build_hinges.cpp): known bodies, two different ones,
/// non-zero axes, limits and drives as angleLimit and hingeDrive check them.
void addHinges(const nlohmann::json& hinges, const BodyNames& names, World& world,
               const std::string& source);

/// Adds "joints" (build_joints.cpp): prismatic, spherical and fixed joints
/// between known bodies, two different ones; non-zero axes, limits with
/// lower <= upper, angles in [-pi, pi] (a swing limit in [0, pi]), an
/// axis for a spherical joint's limits, and a position drive's
/// damping_N_s_per_m only with stiffness_N_per_m. Returns their kinds in
/// order (Scene::joint_kinds).
std::vector<JointKind> addJoints(const nlohmann::json& joints, const BodyNames& names, World& world,
                                 const std::string& source);

/// The angle limit {"lower_rad", "upper_rad"} at `pointer` (build_joints.cpp):
/// both in [-pi, pi], lower <= upper.
JointLimit angleLimit(const nlohmann::json& limit, const std::string& pointer,
                      const std::string& source);

/// The hinge drive at `pointer` (build_joints.cpp): velocity or angle mode,
/// exactly one of a constant target and a schedule (keyframe times strictly
/// increasing; an angle any number of turns); max_torque_N_m omitted means unlimited;
/// an angle drive's damping_N_m_s_per_rad only with stiffness_N_m_per_rad
/// (a torsional spring; omitted: a rigid drive).
HingeDrive hingeDrive(const nlohmann::json& drive, const std::string& pointer,
                      const std::string& source);

/// Adds "cables" (build_cables.cpp): unique names, known bodies, polygon
/// sections of non-zero area, no pinhole ends of open cables, hybrid links
/// only there, active ends, no stored cable on inactive links, not only
/// pinholes in a closed cable, one rest length per joint (0 for joints
/// leaving inactive links), a winch only on an open cable's attachment
/// end with commands in order of time, one mode each and speeds within its
/// maximum; CableSystem::addCable's own refusals at the cable's path.
void addCables(const nlohmann::json& cables, const BodyNames& names, CableSystem& system,
               const std::string& source);

/// Adds "junctions" (build_cables.cpp): unique names, known cables, each
/// in one junction; CableSystem::addJunction's own refusals (a cable that
/// cannot be a branch) at the branch's path.
void addJunctions(const nlohmann::json& junctions, CableSystem& system, const std::string& source);

/// [x, y, z] (schema-checked) as a vector.
Vec3 vec3(const nlohmann::json& xyz);

}  // namespace reeve::scene_detail
