#include "build.h"
#include "describe.h"
#include "reeve/engine/fp_exceptions.h"

namespace reeve::scene_detail {
namespace {

constexpr const char* kWorldName = "world";

// The "shape" object at `path` (schema-checked), and a hull's degenerate
// points as a SceneError. `keep_frame`: a hull about its vertices' origin,
// the body's centre of mass given apart (inertia_kg_m2).
Shape shapeOf(const nlohmann::json& shape, const std::string& path, const std::string& source, bool keep_frame) {
  const std::string type = shape.at("type").get<std::string>();
  if (type == "box") return Shape::box(vec3(shape.at("half_extents_m")));
  if (type == "cylinder")
    return Shape::cylinder(shape.at("radius_m").get<double>(),
                           shape.at("half_length_m").get<double>());
  if (type == "sphere") return Shape::sphere(shape.at("radius_m").get<double>());
  std::vector<Vec3> points;
  for (const nlohmann::json& p : shape.at("vertices_m")) points.push_back(vec3(p));
  try {
    return Shape::convexHull(points, keep_frame);
  } catch (const std::invalid_argument&) {  // the schema has checked their count and numbers
    throw SceneError(source, path + "/vertices_m", "points spanning a volume",
                     std::to_string(points.size()) + " points on one plane or line");
  }
}

}  // namespace

Vec3 hullOrigin(const Shape& shape) {
  return shape.type == Shape::Type::Hull ? shape.hull->input_centre_of_mass : Vec3::Zero();
}

Vec3 vec3(const nlohmann::json& xyz) {
  return Vec3(xyz.at(0).get<double>(), xyz.at(1).get<double>(), xyz.at(2).get<double>());
}

BodyId BodyNames::find(const nlohmann::json& name, const std::string& pointer,
                       const std::string& source, bool world_allowed) const {
  const std::string text = name.get<std::string>();
  if (world_allowed && text == kWorldName) return kWorldBody;
  if (const auto it = ids.find(text); it != ids.end()) return it->second;
  throw SceneError(source, pointer,
                   std::string(world_allowed ? "\"world\" or " : "") + "the name of a body (" +
                       nameList(ordered) + ")",
                   quote(text));
}

BodyNames addBodies(const nlohmann::json& bodies, World& world, const std::string& source) {
  BodyNames names;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const nlohmann::json& b = bodies[i];
    const std::string path = "/bodies/" + std::to_string(i);
    const auto fail = [&](const std::string& key, const std::string& expected,
                          const std::string& found) {
      throw SceneError(source, key.empty() ? path : childPointer(path, key), expected, found);
    };

    BodyDef def;
    def.name = b.at("name").get<std::string>();
    if (def.name == kWorldName)
      fail("name", "a body name other than \"world\" (it names the fixed world frame)",
           quote(def.name));
    if (names.ids.count(def.name))
      fail("name",
           "a body name not already used by /bodies/" + std::to_string(names.ids.at(def.name)),
           quote(def.name));
    def.shape = shapeOf(b.at("shape"), path + "/shape", source, b.contains("inertia_kg_m2"));
    def.position = vec3(b.at("position_m"));
    if (const auto o = b.find("orientation"); o != b.end()) {
      const Vec3 axis = vec3(o->at("axis"));
      if (axis.squaredNorm() == 0.0)
        throw SceneError(source, path + "/orientation/axis", "a non-zero rotation axis",
                         literal(o->at("axis")));
      def.orientation =
          Quat(Eigen::AngleAxisd(o->at("angle_rad").get<double>(), axis.normalized()));
    }
    // position_m places the frame of the vertices; the body's origin is the
    // hull's centre of mass (with inertia_kg_m2, the frame's origin: 0).
    def.position += def.orientation * hullOrigin(def.shape);
    const auto inertia = b.find("inertia_kg_m2");
    def.is_static = b.value("static", false);
    def.material.static_friction = b.value("static_friction", def.material.static_friction);
    def.material.dynamic_friction = b.value("dynamic_friction", def.material.dynamic_friction);
    def.material.restitution = b.value("restitution", def.material.restitution);
    def.collides = b.value("collides", false);
    def.contact_type = b.value("contact_type", def.contact_type);
    def.contact_affinity = b.value("contact_affinity", def.contact_affinity);
    const bool has_density = b.contains("density_kg_per_m3");
    const bool has_mass = b.contains("mass_kg");
    const auto motion = b.find("motion");
    const bool kinematic = motion != b.end();
    if (kinematic && def.is_static)
      fail("motion", "no motion for a static body (it never moves; omit \"static\" for a kinematic body)",
           literal(*motion));
    if (def.is_static || kinematic) {
      const std::string why = kinematic ? " for a kinematic body (its motion moves it)" : " for a static body (it never moves)";
      for (const char* key : {"density_kg_per_m3", "mass_kg", "inertia_kg_m2"})
        if (b.contains(key)) fail(key, "no density or mass" + why, literal(b.at(key)));
      for (const char* key : {"linear_velocity_m_per_s", "angular_velocity_rad_per_s"})
        if (b.contains(key)) fail(key, "no velocity" + why, literal(b.at(key)));
      for (const char* key : {"linear_damping_per_s", "angular_damping_per_s"})
        if (b.contains(key)) fail(key, "no damping" + why, literal(b.at(key)));
    }
    if (kinematic) {
      for (std::size_t k = 0; k < motion->size(); ++k) {
        const nlohmann::json& point = (*motion)[k];
        MotionKeyframe m;
        m.time = point.at("t_s").get<double>();
        m.velocity = vec3(point.value("velocity_m_per_s", nlohmann::json::array({0, 0, 0})));
        m.angular_velocity = vec3(point.value("angular_velocity_rad_per_s", nlohmann::json::array({0, 0, 0})));
        if (k > 0 && !(m.time > def.motion.back().time))
          throw SceneError(source, path + "/motion/" + std::to_string(k) + "/t_s",
                           "a time after the previous keyframe's " + number(def.motion.back().time) + " s",
                           literal(point.at("t_s")));
        def.motion.push_back(m);
      }
    } else if (!def.is_static) {
      if (has_density == has_mass)
        fail("", "exactly one of density_kg_per_m3 or mass_kg for a dynamic body",
             has_mass ? "both" : "neither");
      if (has_mass)
        def.mass = b.at("mass_kg").get<double>();
      else
        def.density = b.at("density_kg_per_m3").get<double>();
      if (inertia != b.end()) {
        if (!has_mass) fail("inertia_kg_m2", "mass_kg with moments of inertia", "density_kg_per_m3");
        def.inertia = vec3(*inertia);  // > 0 (the schema's); not always a rigid body's (an imported armature)
      }
      if (const auto v = b.find("linear_velocity_m_per_s"); v != b.end())
        def.linear_velocity = vec3(*v);
      if (const auto w = b.find("angular_velocity_rad_per_s"); w != b.end())
        def.angular_velocity = vec3(*w);
      def.linear_damping = b.value("linear_damping_per_s", 0.0);
      def.angular_damping = b.value("angular_damping_per_s", 0.0);
    }
    if (!def.is_static && !kinematic) {
      // Mass and moments of inertia whose squares (energies, the solver's
      // products of them) stay finite and non-zero in double precision
      // (every number in the file is at most 1e153: magnitudes.h):
      // half extents of 1e-200 m have volume 0, a radius of 1e-300 m an
      // inertia of 0, 1e150 kg/m^3 over a 1000 m box a mass of 1e159 kg.
      // The engine would refuse some with no JSON path, miss the others.
      const FloatingPointExceptionsMasked overflow_is_tested;  // kept out of a trapping program's way
      const double volume_m3 = volume(def.shape);
      const double m = has_mass ? def.mass : def.density * volume_m3;
      if (!isRepresentableMass(m))
        fail(has_mass ? "mass_kg" : "density_kg_per_m3",
             "a mass between 1e-100 and 1e100 kg (its cube finite and non-zero in double precision)",
             has_mass ? number(m) + " kg"
                      : number(def.density) + " kg/m^3 x " + number(volume_m3) + " m^3 = " + number(m) + " kg");
      const Mat3 tensor = def.inertia != Vec3::Zero() ? Mat3(def.inertia.asDiagonal()) : inertiaTensor(def.shape, m);
      const Vec3 moments = tensor.diagonal();
      if (!isRepresentableMass(moments.minCoeff()) || !isRepresentableMass(moments.maxCoeff()) ||
          !tensor.inverse().allFinite())
        fail(def.inertia != Vec3::Zero() ? "inertia_kg_m2" : "shape",
             "a size whose moments of inertia are between 1e-100 and 1e100 kg m^2",
             "moments " + number(moments.x()) + ", " + number(moments.y()) + ", " + number(moments.z()) +
                 " kg m^2 for " + number(m) + " kg");
    }
    const BodyId id = world.addBody(def);
    names.ids.emplace(def.name, id);
    names.ordered.push_back(def.name);
  }
  return names;
}

void excludeContacts(const nlohmann::json& pairs, const BodyNames& names, World& world, const std::string& source) {
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const std::string path = "/contact_exclusions/" + std::to_string(i);
    const BodyId a = names.find(pairs[i][0], path + "/0", source, false);
    const BodyId b = names.find(pairs[i][1], path + "/1", source, false);
    if (a == b) throw SceneError(source, path + "/1", "a body other than the first", quote(pairs[i][1].get<std::string>()));
    world.excludeContact(a, b);
  }
}

}  // namespace reeve::scene_detail
