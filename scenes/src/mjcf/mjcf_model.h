// The MJCF model as the importer reads it (mjcf_read.cpp) before it is
// mapped to a scene (mjcf_scene.cpp): every element resolved against its
// defaults, angles in radians, each frame relative to its body. Private to
// reeve_scene.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "reeve/engine/math.h"
#include "reeve/scene/mjcf.h"

namespace reeve::mjcf {

/// Where an element is: its file, line and a short description
/// (<joint name="elbow">), for errors and the unmapped list.
struct Origin {
  std::string file;
  int line = 0;
  std::string element;
  std::string where() const { return file + ":" + std::to_string(line) + ": " + element; }
};

struct Pose {
  Vec3 pos = Vec3::Zero();
  Quat quat = Quat::Identity();  // local -> parent
  Vec3 apply(const Vec3& p) const { return pos + quat * p; }
  Pose then(const Pose& child) const { return {apply(child.pos), quat * child.quat}; }
};

enum class GeomType { Plane, Sphere, Capsule, Ellipsoid, Cylinder, Box, Mesh };

struct Geom {
  Origin origin;
  std::string name;
  GeomType type = GeomType::Sphere;
  Pose pose;                      // in its body's frame
  Vec3 size = Vec3::Zero();       // MuJoCo's: radius, half-length, half-sizes
  double mass = 0.0;              // kg, from `mass` or density x volume
  Mat3 inertia = Mat3::Zero();    // kg m^2 about its centre, in its own frame
  int contype = 1, conaffinity = 1;
  double friction = 1.0;          // sliding
  int body = 0;
  /// A mesh geom's hull corners (m) about its centre of mass, in its frame
  /// (its pose moved to that centre, as MuJoCo's compiler moves it).
  std::vector<Vec3> vertices;
};

struct Site {
  Origin origin;
  std::string name;
  Vec3 pos = Vec3::Zero();  // in its body's frame
  int body = 0;
};

enum class JointType { Free, Ball, Slide, Hinge };

struct Joint {
  Origin origin;
  std::string name;
  JointType type = JointType::Hinge;
  Vec3 pos = Vec3::Zero();    // in its body's frame
  Vec3 axis = Vec3::UnitZ();  // in its body's frame, unit
  bool limited = false;
  std::array<double, 2> range{0.0, 0.0};  // rad or m
  double damping = 0.0, stiffness = 0.0, springref = 0.0, armature = 0.0, frictionloss = 0.0;
  int body = 0;
};

struct Body {
  Origin origin;
  std::string name;
  int parent = -1;    // -1 for the world
  Pose pose;          // in its parent's frame
  Pose world;         // in the world
  std::vector<int> joints, geoms, sites;
  // <inertial>, when given: mass, centre and inertia in the body's frame.
  bool has_inertial = false;
  double mass = 0.0;
  Vec3 com = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();  // about com
};

/// One element of a spatial tendon's path.
struct PathElement {
  Origin origin;
  enum class Kind { Site, Geom, Pulley } kind = Kind::Site;
  int index = -1;          // the site or geom
  int sidesite = -1;       // a geom's sidesite, or -1
  double divisor = 1.0;    // a pulley's
};

struct Tendon {
  Origin origin;
  std::string name;
  bool spatial = true;
  std::vector<PathElement> path;
  bool limited = false;
  std::array<double, 2> range{0.0, 0.0};
  double stiffness = 0.0, damping = 0.0, frictionloss = 0.0;
  std::optional<double> springlength;
};

struct Actuator {
  Origin origin;
  std::string name, kind;  // its tag: motor, position, velocity, muscle, general, ...
  std::string target;      // what it acts on, as "joint NAME" or "tendon NAME"
  int joint = -1, tendon = -1;  // the joint or tendon it acts on, or -1
  double gear = 1.0;       // its gear's first number
  double kp = 1.0, kv = 0.0;  // a position servo's gains (kv also a velocity servo's)
  bool ctrllimited = false, forcelimited = false;
  std::array<double, 2> ctrlrange{0.0, 0.0}, forcerange{0.0, 0.0};
  /// A muscle's peak active force F0 (N; < 0: scale / acc0, MuJoCo's
  /// default) and its scale.
  double force = -1.0, scale = 200.0;
};

struct Model {
  std::string name = "MuJoCo model";
  std::string file;
  double timestep = 0.002;
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);
  std::string inertia_from_geom = "auto";  // <compiler inertiafromgeom>: true, false or auto
  std::vector<Body> bodies;  // 0 is the world, parents before children
  std::vector<Geom> geoms;
  std::vector<Site> sites;
  std::vector<Joint> joints;
  std::vector<Tendon> tendons;
  std::vector<Actuator> actuators;
  /// <contact><exclude body1 body2>: pairs of bodies that never touch.
  std::vector<std::pair<int, int>> contact_exclusions;
  /// What was read but not kept: one line each (Origin::where() and why).
  std::vector<std::string> unmapped;
};

/// A triangle mesh: vertices (m) and triangles of vertex indices.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// A mesh file that cannot be read: "FILE[:LINE]: what was expected".
struct MeshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The largest mesh file read (bytes).
inline constexpr std::uintmax_t kMaxMeshFileBytes = 256u << 20;

/// Reads an OBJ (`v` and `f` records, polygons fanned) or STL (binary or
/// ASCII) file (mjcf_mesh.cpp), a regular file of at most
/// kMaxMeshFileBytes. Throws MeshError.
TriangleMesh readMeshFile(const std::string& path);

/// The solid a mesh bounds as MuJoCo's compiler takes it (mjcf_mesh.cpp):
/// its volume (m^3; <= 0 for one that bounds none, and then nothing else
/// is set), centre of mass (m) and inertia about it at density 1 (kg m^2
/// per kg/m^3). Exact for a closed mesh of outward triangles; `legacy`
/// (MuJoCo's default, `<compiler exactmeshinertia="false">`) counts every
/// pyramid of a triangle and the centre as positive.
struct MeshMassProperties {
  double volume = 0.0;
  Vec3 centroid = Vec3::Zero();
  Mat3 inertia_unit_density = Mat3::Zero();
};
MeshMassProperties meshMassProperties(const TriangleMesh& mesh, bool legacy);

/// Reads the model at `path` (throws SceneError as importMjcf does).
Model readModel(const std::string& path);

/// A tendon's cables in the scene: one, or one per pulley branch (joined
/// by a junction), each with its branch's divisor; none where it is not
/// imported. `length` (m): the tendon's length in MuJoCo's terms, sum_b
/// L_b / divisor_b, that its cables are to have in all (NaN: as long as
/// at load).
struct TendonCables {
  std::vector<int> cables;
  std::vector<double> divisors;
  double length = 0.0;
};

/// A degree of freedom of the model as the scene has it: an MJCF joint
/// between two Reeve bodies (`own` moves on `other`; a free joint's body
/// on nothing), at `anchor` (m, world) along or about `axis` (world, unit);
/// a free joint's `anchor` is its MJCF body's origin, where MuJoCo
/// measures its velocity.
struct Dof {
  JointType type = JointType::Hinge;
  std::string own, other;
  Vec3 anchor = Vec3::Zero(), axis = Vec3::UnitZ();
};

/// A winch pulling with MuJoCo's default muscle force, scale / acc0
/// (acc0: the norm of the joint accelerations a pull of 1 N along the
/// tendon gives at load, mjcf_import.cpp), times `times` (the control).
struct MusclePull {
  int cable = -1;
  double times = 0.0;  // ctrl x scale
  Origin origin;       // the muscle's
};

/// What mapModel makes: the scene JSON and the unmapped list (`import`),
/// each tendon's cables, the model's degrees of freedom, and the muscle
/// pulls left to set.
struct Mapping {
  MjcfImport import;
  std::vector<TendonCables> tendons;
  std::vector<Dof> dofs;
  std::vector<MusclePull> muscle_pulls;
};

/// The scene of `model` (mjcf_scene.cpp), its rest lengths taut.
Mapping mapModel(const Model& model, const MjcfOptions& options);

/// A geom's volume (m^3) and inertia about its centre in its frame for a
/// mass of 1 kg (MuJoCo's formulas; a capsule is a cylinder and two
/// hemispheres). Planes and meshes: 0.
double geomVolume(GeomType type, const Vec3& size);
Mat3 geomUnitInertia(GeomType type, const Vec3& size);

}  // namespace reeve::mjcf
