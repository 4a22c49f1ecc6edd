// mjcf::Model -> a scene's JSON (scene.schema.json). Each MJCF body with a
// joint becomes one Reeve body carrying the bodies welded to it (no joint:
// MuJoCo moves them together), at their joint centre of mass, along their
// principal axes, with their mass and moments; the world's geoms and the
// sites tendons are tied to become static bodies; each wrap cylinder a body
// of its own, welded (a frictionless pulley, as MuJoCo's wrap) or hinged
// (a wheel, `--wheels turning`). scenes/README.md, "MuJoCo models", lists
// the mapping.
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>

#include "mjcf_model.h"
#include "reeve/scene/mjcf.h"
#include "reeve/engine/shape.h"
#include "reeve/scene/scene.h"

namespace reeve::mjcf {
namespace {

using json = nlohmann::ordered_json;

// The speed (rad/s, m/s) a motor's drive aims at: never reached, so the
// drive stays at its torque cap, a constant torque (MuJoCo's motor); a
// motor's tendon is reeled in at it, its winch stalled at its pull.
constexpr double kMotorSpeed = 1e6;

// Solver iterations a substep for a model with a floor (solver()).
constexpr int kIterationsOnAFloor = 10;

// The mass of each light link between two joints of one body (a universal
// joint's cross), of the body: MuJoCo's joints there have no mass between
// them, and the direct solver is exact across this ratio.
constexpr double kJointLinkMass = 1e-6;

// A welded pulley's mass, of the body it is welded to: it stands for a
// geom whose mass stays with that body, so it should weigh nothing, and
// the direct solver is exact across this ratio.
constexpr double kWeldedWheelMass = 1e-6;

json vec(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

json orientationJson(const Quat& q) {
  const Eigen::AngleAxisd aa(q.normalized());
  return {{"axis", vec(aa.axis())}, {"angle_rad", aa.angle()}};
}

[[noreturn]] void fail(const Origin& o, const std::string& expected, const std::string& found) {
  throw SceneError::atLine(o.file, o.line, o.element, expected, found);
}

// Points on a geom's surface (its frame), for a hull.
std::vector<Vec3> surfacePoints(const Geom& g) {
  std::vector<Vec3> points;
  constexpr int kRound = 16;  // points on a circle
  const auto ring = [&](double r, double z) {
    for (int i = 0; i < kRound; ++i) {
      const double a = 2.0 * std::numbers::pi * i / kRound;
      points.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
  };
  const Vec3& s = g.size;
  switch (g.type) {
    case GeomType::Box:
      for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? s[0] : -s[0], i & 2 ? s[1] : -s[1], i & 4 ? s[2] : -s[2]);
      break;
    case GeomType::Cylinder: ring(s[0], -s[1]); ring(s[0], s[1]); break;
    case GeomType::Sphere:
    case GeomType::Capsule:
    case GeomType::Ellipsoid: {
      const double half = g.type == GeomType::Capsule ? s[1] : 0.0;
      const Vec3 radii = g.type == GeomType::Ellipsoid ? s : Vec3::Constant(s[0]);
      for (int k = -3; k <= 3; ++k) {  // latitudes, symmetric about the equator
        const double lat = k * std::numbers::pi / 8.0, z = radii.z() * std::sin(lat), r = std::cos(lat);
        for (int i = 0; i < kRound; ++i) {
          const double a = 2.0 * std::numbers::pi * i / kRound;
          const Vec3 p(radii.x() * r * std::cos(a), radii.y() * r * std::sin(a), z);
          if (half > 0.0 && k != 0) points.push_back(p + Vec3(0, 0, k > 0 ? half : -half));
          else if (half > 0.0) points.push_back(p + Vec3(0, 0, half)), points.push_back(p - Vec3(0, 0, half));
          else points.push_back(p);
        }
      }
      points.emplace_back(0, 0, radii.z() + half);
      points.emplace_back(0, 0, -radii.z() - half);
      break;
    }
    case GeomType::Mesh: points = g.vertices; break;
    case GeomType::Plane: break;
  }
  return points;
}

// A geom's own shape, about its centre in its frame, where Reeve has it.
json shapeOf(const Geom& g) {
  switch (g.type) {
    case GeomType::Sphere: return {{"type", "sphere"}, {"radius_m", g.size[0]}};
    case GeomType::Box: return {{"type", "box"}, {"half_extents_m", vec(g.size)}};
    case GeomType::Cylinder: return {{"type", "cylinder"}, {"radius_m", g.size[0]}, {"half_length_m", g.size[1]}};
    default: {
      json vertices = json::array();
      for (const Vec3& p : surfacePoints(g)) vertices.push_back(vec(p));
      return {{"type", "hull"}, {"vertices_m", vertices}};
    }
  }
}

// Mass, centre and inertia about it, summed in one frame.
struct MassProperties {
  double mass = 0.0;
  Vec3 first = Vec3::Zero();     // sum m p
  Mat3 second = Mat3::Zero();    // sum of each part's inertia about the frame's origin
  void add(double m, const Vec3& centre, const Mat3& inertia_about_centre) {
    mass += m;
    first += m * centre;
    second += inertia_about_centre + m * (centre.squaredNorm() * Mat3::Identity() - centre * centre.transpose());
  }
  Vec3 centre() const { return mass > 0.0 ? Vec3(first / mass) : Vec3::Zero(); }
  Mat3 aboutCentre() const {
    const Vec3 c = centre();
    return second - mass * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
  }
};

class Mapper {
 public:
  Mapper(const Model& model, const MjcfOptions& options) : m_(model), options_(options) {}

  Mapping map() {
    groupBodies();
    findWraps();  // which tendons are cables: their winch ends need the groups
    findContacts();
    for (std::size_t b = 0; b < m_.bodies.size(); ++b)
      if (group_[b] == static_cast<int>(b) && b != 0) addMovingBody(static_cast<int>(b));
    addStaticGeoms();
    for (std::size_t b = 1; b < m_.bodies.size(); ++b)
      if (group_[b] == static_cast<int>(b)) addJoint(static_cast<int>(b));
    for (const Actuator& a : m_.actuators) addJointActuator(a);
    addWheels();
    for (const Tendon& t : m_.tendons) addCable(t);
    for (const Actuator& a : m_.actuators)
      if (a.tendon >= 0 && !tendon_actuator_done_.count(&a))
        notImported(a, "an actuator on a tendon that is not imported (listed) is not imported");
    scene_["name"] = m_.name.empty() ? "MuJoCo model" : m_.name;
    scene_["description"] = "Imported from the MuJoCo model " + m_.file + " (reeve import mjcf).";
    scene_["solver"] = solver();
    scene_["duration_s"] = 5.0;
    scene_["bodies"] = bodies_;
    if (!hinges_.empty()) scene_["hinges"] = hinges_;
    if (!joints_.empty()) scene_["joints"] = joints_;
    if (!cables_.empty()) scene_["cables"] = cables_;
    if (!junctions_.empty()) scene_["junctions"] = junctions_;
    excludeContacts();
    if (!exclusions_.empty()) scene_["contact_exclusions"] = exclusions_;
    if (ground_) scene_["ground"] = *ground_;
    scene_["camera"] = camera();
    Mapping out;
    // Replace what is not UTF-8: the model's path may hold such bytes (its text may not).
    out.import.scene_json = scene_.dump(2, ' ', false, json::error_handler_t::replace);
    out.import.unmapped = m_.unmapped;
    out.import.unmapped.insert(out.import.unmapped.end(), unmapped_.begin(), unmapped_.end());
    out.tendons = cable_lengths_;
    out.dofs = dofs_;
    out.muscle_pulls = muscle_pulls_;
    return out;
  }

 private:
  // --- bodies -----------------------------------------------------------

  void findWraps() {
    wrap_.assign(m_.geoms.size(), 0);
    for (const Tendon& t : m_.tendons) {
      if (!mappable(t)) continue;
      for (std::size_t k = 0; k < t.path.size(); ++k) {
        const PathElement& e = t.path[k];
        if (e.kind != PathElement::Kind::Geom) continue;
        wrap_[e.index] = 1;
        const Geom& g = m_.geoms[e.index];
        if (g.type != GeomType::Sphere) continue;
        // A sphere is wrapped in the plane through its centre and the path's
        // neighbours at load (MuJoCo's, which turns as they move; Reeve's
        // cable plane turns with the sphere's body).
        const Vec3 c = m_.bodies[g.body].world.apply(g.pose.pos);
        const Vec3 a = elementPoint(t.path[k - 1]) - c, b = elementPoint(t.path[k + 1]) - c;
        Vec3 n = a.cross(b);
        if (!(n.norm() > 1e-9 * a.norm() * b.norm())) {  // in line with the centre: any plane through them
          const Vec3 along = (b - a).norm() > 0.0 ? Vec3(b - a) : a.norm() > 0.0 ? a : Vec3::UnitX();
          n = along.unitOrthogonal();
        }
        const Quat q = Quat::FromTwoVectors(Vec3::UnitZ(), n.normalized());
        if (const auto it = wrap_frame_.find(e.index); it == wrap_frame_.end())
          wrap_frame_[e.index] = Pose{c, q};
        else if (std::abs((it->second.quat * Vec3::UnitZ()).dot(n.normalized())) < 1.0 - 1e-9)
          unmapped_.push_back(e.origin.where() + ": a sphere wrapped in a second plane is not imported (the cable keeps the first tendon's plane)");
      }
    }
  }

  // A wrap geom's frame (world): its cable plane is the frame's xy plane.
  Pose wrapFrame(int gi) const {
    if (const auto it = wrap_frame_.find(gi); it != wrap_frame_.end()) return it->second;
    const Geom& g = m_.geoms[gi];
    return m_.bodies[g.body].world.then(g.pose);
  }

  // Whether a tendon becomes a cable, and if not, why (into unmapped_ once).
  bool mappable(const Tendon& t, bool report = false) {
    std::string why;
    const std::vector<Branch> branches = branchesOf(t);
    if (!t.spatial) why = "fixed tendons (joint couplings) are not imported";
    else if (std::any_of(branches.begin(), branches.end(), [&](const Branch& b) {
               return b.end - b.begin < 2 || t.path[b.begin].kind != PathElement::Kind::Site ||
                      t.path[b.end - 1].kind != PathElement::Kind::Site;
             }))
      why = branches.size() > 1 ? "a pulley branch that does not start and end at a site" : "a path that does not start and end at a site";
    else if (branches.size() > 1 && pulledBy(t))
      why = "an actuator pulling a tendon with pulley branches is not imported (a junction's cables have no winch)";
    else if (std::any_of(t.path.begin(), t.path.end(), [&](const PathElement& p) {
               return p.kind == PathElement::Kind::Geom && m_.geoms[p.index].type != GeomType::Cylinder &&
                      m_.geoms[p.index].type != GeomType::Sphere;
             }))
      why = "wraps on geoms other than cylinders and spheres are not imported yet";
    else if (!t.limited && !(t.stiffness > 0.0) && !pulledBy(t))
      why = "no range, no stiffness and no motor pulling it: it pulls on nothing in MuJoCo either";
    if (!why.empty() && report) unmapped_.push_back(t.origin.where() + ": " + why);
    return why.empty();
  }

  void groupBodies() {
    group_.assign(m_.bodies.size(), 0);
    for (std::size_t b = 1; b < m_.bodies.size(); ++b) {
      const Body& body = m_.bodies[b];
      group_[b] = body.joints.empty() ? group_[body.parent] : static_cast<int>(b);
    }
  }

  std::string uniqueName(std::string name, const std::string& fallback) {
    if (name.empty() || name == "world") name = fallback;
    std::string candidate = name;
    for (int k = 2; names_.count(candidate); ++k) candidate = name + "_" + std::to_string(k);
    names_.insert(candidate);
    return candidate;
  }

  void addMovingBody(int root) {
    const Body& r = m_.bodies[root];
    // A body of the group in the root's frame.
    const auto toRoot = [&](const Body& body) {
      return Pose{r.world.quat.conjugate() * (body.world.pos - r.world.pos), r.world.quat.conjugate() * body.world.quat};
    };
    MassProperties mp;  // in the root's frame
    std::vector<const Geom*> all;  // its geoms; its shape is theirs, or where some touch others (bodies_collide_), those
    for (std::size_t b = 0; b < m_.bodies.size(); ++b) {
      if (group_[b] != root) continue;
      const Body& body = m_.bodies[b];
      const Pose to_root = toRoot(body);
      const bool inertial = body.has_inertial && m_.inertia_from_geom != "true";
      if (inertial) {
        const Mat3 R = to_root.quat.toRotationMatrix();
        mp.add(body.mass, to_root.apply(body.com), R * body.inertia * R.transpose());
      }
      for (const int gi : body.geoms) {
        const Geom& g = m_.geoms[gi];
        if (g.type == GeomType::Plane) {
          unmapped_.push_back(g.origin.where() + ": a plane on a moving body is not imported");
          continue;
        }
        if (!(wrap_[gi] && options_.wheels == MjcfWheels::Turning)) all.push_back(&g);
        if (inertial || m_.inertia_from_geom == "false") continue;
        if (wrap_[gi] && options_.wheels == MjcfWheels::Turning) continue;  // the wheel's own
        const Pose p = to_root.then(g.pose);
        const Mat3 R = p.quat.toRotationMatrix();
        mp.add(g.mass, p.pos, R * g.inertia * R.transpose());
      }
    }
    for (const int j : r.joints)
      if (m_.joints[j].armature > 0.0) {
        const Joint& joint = m_.joints[j];
        if (joint.type == JointType::Hinge) mp.second += joint.armature * joint.axis * joint.axis.transpose();
        else unmapped_.push_back(joint.origin.where() + ": armature on a joint that is not a hinge is not imported");
      }
    std::vector<const Geom*> geoms;
    if (bodies_collide_) std::copy_if(all.begin(), all.end(), std::back_inserter(geoms), [](const Geom* g) { return touches(*g); });
    if (geoms.empty()) geoms = all;
    if (!(mp.mass > 0.0))
      fail(r.origin, "a moving body with mass (from <inertial> or its geoms, with the bodies welded to it)", "0 kg");
    const Vec3 c = mp.centre();
    const Mat3 I = mp.aboutCentre();
    // Its principal frame: the frame of its one geom where that is one (a
    // box stays a box), else the eigenvectors of its inertia.
    Mat3 axes = Mat3::Identity();
    json shape;
    const auto diagonalIn = [&](const Mat3& R) {
      const Mat3 local = R.transpose() * I * R;
      const double scale = local.diagonal().cwiseAbs().maxCoeff();
      return (local - Mat3(local.diagonal().asDiagonal())).cwiseAbs().maxCoeff() <= 1e-12 * scale;
    };
    if (geoms.size() == 1) {
      const Pose p = toRoot(m_.bodies[geoms[0]->body]).then(geoms[0]->pose);
      if ((p.pos - c).norm() <= 1e-9 * (1.0 + c.norm()) && diagonalIn(p.quat.toRotationMatrix())) {
        axes = p.quat.toRotationMatrix();
        shape = shapeOf(*geoms[0]);
      }
    }
    if (shape.is_null()) {
      if (!diagonalIn(Mat3::Identity())) {
        Eigen::SelfAdjointEigenSolver<Mat3> eig(I);
        axes = eig.eigenvectors();
        if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);
      }
      // The hull of its geoms about its centre of mass, to collide and draw
      // (the scene keeps a hull's vertices about the body's origin where its
      // moments are given); a small box where they span no volume.
      json vertices = json::array();
      std::vector<Vec3> points;
      for (const Geom* g : geoms) {
        const Pose p = toRoot(m_.bodies[g->body]).then(g->pose);
        for (const Vec3& s : surfacePoints(*g)) points.push_back(axes.transpose() * (p.apply(s) - c));
      }
      try {
        Shape::convexHull(points, true);
        for (const Vec3& v : points) vertices.push_back(vec(v));
        shape = {{"type", "hull"}, {"vertices_m", vertices}};
      } catch (const std::invalid_argument&) {
        shape = {{"type", "box"}, {"half_extents_m", vec(Vec3::Constant(0.01))}};
      }
    }
    const Vec3 moments = (axes.transpose() * I * axes).diagonal();
    if (!(moments.minCoeff() > 0.0))  // a point mass, or <inertial> moments of 0
      fail(r.origin, "a moving body with moments of inertia > 0 (from <inertial> or its geoms)",
           std::to_string(moments.x()) + ", " + std::to_string(moments.y()) + ", " + std::to_string(moments.z()) + " kg m^2");
    const Quat q = r.world.quat * Quat(axes);
    const std::string fallback = !r.name.empty() || r.geoms.empty() || m_.geoms[r.geoms[0]].name.empty()
                                     ? "body" + std::to_string(root)
                                     : m_.geoms[r.geoms[0]].name;
    json body = {{"name", uniqueName(r.name, fallback)},
                 {"shape", shape},
                 {"mass_kg", mp.mass},
                 {"inertia_kg_m2", vec(moments)},
                 {"position_m", vec(r.world.apply(c))}};
    if (q.angularDistance(Quat::Identity()) > 0.0) body["orientation"] = orientationJson(q);
    addContactKeys(body, geoms);
    if (body.value("collides", false)) colliding_.insert(body["name"].get<std::string>());
    reeve_body_[root] = body["name"];
    frame_[root] = Pose{r.world.apply(c), q.normalized()};
    mass_[root] = mp.mass;
    bodies_.push_back(body);
  }

  // --- contacts ---------------------------------------------------------

  // Whether geom g touches other geoms (a plane of the world is the ground,
  // which touches every body).
  static bool touches(const Geom& g) { return g.type != GeomType::Plane && (g.contype != 0 || g.conaffinity != 0); }

  // Bodies collide where two of the model's groups (the world's geoms one
  // of them) have geoms that touch: then each such body collides, with its
  // geoms' bits (BodyDef::contact_type, contact_affinity).
  void findContacts() {
    std::set<int> touching;
    for (const Geom& g : m_.geoms) {
      if (touches(g)) touching.insert(group_[g.body]);
      has_plane_ |= g.type == GeomType::Plane && group_[g.body] == 0;
    }
    bodies_collide_ = touching.size() >= 2;
  }

  // Collision keys of a Reeve body made of `geoms`: collides, the union of
  // their bits (MuJoCo pairs geoms; Reeve pairs bodies), and their largest
  // sliding friction (MuJoCo takes a pair's larger friction, Reeve their
  // mean) as its static and dynamic friction.
  void addContactKeys(json& body, const std::vector<const Geom*>& geoms) const {
    double friction = 0.0;
    std::uint32_t type = 0, affinity = 0;
    bool any = false;
    for (const Geom* g : geoms) {
      friction = std::max(friction, g->friction);
      if (!touches(*g)) continue;
      any = true;
      type |= static_cast<std::uint32_t>(g->contype);
      affinity |= static_cast<std::uint32_t>(g->conaffinity);
    }
    if (!geoms.empty() && (bodies_collide_ || has_plane_)) {
      body["static_friction"] = friction;
      body["dynamic_friction"] = friction;
    }
    if (!bodies_collide_ || !any) return;
    body["collides"] = true;
    if (type != 1) body["contact_type"] = type;
    if (affinity != 1) body["contact_affinity"] = affinity;
  }

  // MuJoCo's filterparent (a body never touches its parent, unless that is
  // the world) and the model's <exclude> pairs, between the Reeve bodies
  // that collide.
  void excludeContacts() {
    if (!bodies_collide_) return;
    std::set<std::pair<std::string, std::string>> pairs;
    const auto add = [&](const std::string& a, const std::string& b) {
      if (a != b && colliding_.count(a) && colliding_.count(b)) pairs.insert(std::minmax(a, b));
    };
    for (std::size_t b = 1; b < m_.bodies.size(); ++b) {
      const int own = group_[b], parent = group_[m_.bodies[b].parent];
      if (own == static_cast<int>(b) && parent != 0) add(reeve_body_.at(own), reeve_body_.at(parent));
    }
    for (const auto& [b1, b2] : m_.contact_exclusions) {
      const int g1 = group_[b1], g2 = group_[b2];
      // The world's side is each of its static geoms.
      std::vector<std::string> side1, side2;
      for (const auto& [gi, name] : geom_body_) {
        if (group_[m_.geoms[gi].body] != 0) continue;
        if (g1 == 0) side1.push_back(name);
        if (g2 == 0) side2.push_back(name);
      }
      if (g1 != 0) side1.push_back(reeve_body_.at(g1));
      if (g2 != 0) side2.push_back(reeve_body_.at(g2));
      for (const std::string& a : side1)
        for (const std::string& b : side2) add(a, b);
    }
    for (const auto& [a, b] : pairs) exclusions_.push_back(json::array({a, b}));
  }

  // The world's geoms (and those of bodies welded to it), each a static body.
  void addStaticGeoms() {
    for (std::size_t gi = 0; gi < m_.geoms.size(); ++gi) {
      const Geom& g = m_.geoms[gi];
      if (group_[g.body] != 0) continue;
      const Pose p = wrapFrame(static_cast<int>(gi));
      if (g.type == GeomType::Plane) {
        if (ground_) {
          unmapped_.push_back(g.origin.where() + ": a second plane is not imported (Reeve has one ground)");
          continue;
        }
        const Vec3 n = p.quat * Vec3::UnitZ();
        ground_ = json{{"normal", vec(n)}, {"height_m", n.dot(p.pos)}};
        continue;
      }
      if (wrap_[gi] && options_.wheels == MjcfWheels::Turning) continue;
      json body = {{"name", uniqueName(g.name, "geom" + std::to_string(gi))},
                   {"shape", shapeOf(g)}, {"static", true}, {"position_m", vec(p.pos)}};
      if (p.quat.angularDistance(Quat::Identity()) > 0.0) body["orientation"] = orientationJson(p.quat);
      if (!wrap_[gi]) addContactKeys(body, {&g});  // a fixed wrap is a pulley, not a wall
      if (body.value("collides", false)) colliding_.insert(body["name"].get<std::string>());
      geom_body_[static_cast<int>(gi)] = body["name"];
      bodies_.push_back(body);
    }
  }

  std::string reeveBodyOf(int mj_body) const { return group_[mj_body] == 0 ? "world" : reeve_body_.at(group_[mj_body]); }

  // --- joints -----------------------------------------------------------

  // A body's joints, parent side first (MuJoCo's order): one joint joins
  // it to its parent's Reeve body; several are a chain through light links
  // of their own (kJointLinkMass of it, at its centre of mass), the first
  // joint between the parent and the first link, the last between the
  // last link and the body.
  void addJoint(int b) {
    const Body& body = m_.bodies[b];
    std::string other = reeveBodyOf(body.parent);
    const std::size_t n = body.joints.size();
    for (std::size_t k = 0; k < n; ++k) {
      std::string own = reeve_body_.at(b);
      if (k + 1 < n) {
        own = uniqueName(reeve_body_.at(b) + "_joint" + std::to_string(k + 1), "link");
        const double mass = kJointLinkMass * mass_.at(b);
        bodies_.push_back({{"name", own}, {"shape", {{"type", "sphere"}, {"radius_m", 0.01}}}, {"mass_kg", mass},
                           {"position_m", vec(frame_.at(b).pos)}});
      }
      addJoint(body, body.joints[k], own, other);
      other = own;
    }
  }

  void addJoint(const Body& body, int index, const std::string& own, const std::string& other) {
    const Joint& j = m_.joints[index];
    if (j.type == JointType::Free) {
      if (body.joints.size() > 1) unmapped_.push_back(j.origin.where() + ": a free joint beside other joints is not imported");
      else dofs_.push_back({JointType::Free, own, "", body.world.pos, Vec3::UnitZ()});
      return;
    }
    const Vec3 anchor = body.world.apply(j.pos), axis = body.world.quat * j.axis;
    dofs_.push_back({j.type, own, other, anchor, axis.normalized()});
    if (j.frictionloss > 0.0) unmapped_.push_back(j.origin.where() + ": frictionloss not imported");
    if (j.type == JointType::Ball) {
      if (j.limited) unmapped_.push_back(j.origin.where() + ": a ball joint's range (a cone on its whole rotation) is not imported");
      if (j.damping > 0.0 || j.stiffness > 0.0) unmapped_.push_back(j.origin.where() + ": a ball joint's damping and stiffness are not imported");
      joints_.push_back({{"type", "spherical"}, {"body", own}, {"other", other}, {"anchor_m", vec(anchor)}});
      return;
    }
    const bool hinge = j.type == JointType::Hinge;
    json def = {{"body", own}, {"other", other}, {"anchor_m", vec(anchor)}, {"axis", vec(axis)}};
    if (!hinge) def["type"] = "prismatic";
    if (j.limited) {
      if (hinge && (j.range[0] < -std::numbers::pi || j.range[1] > std::numbers::pi))
        unmapped_.push_back(j.origin.where() + ": a range beyond [-180, 180] degrees is not imported (Reeve's hinge limits are within it)");
      else if (hinge) def["limit"] = {{"lower_rad", j.range[0]}, {"upper_rad", j.range[1]}};
      else def["limit"] = {{"lower_m", j.range[0]}, {"upper_m", j.range[1]}};
    }
    if (j.stiffness > 0.0) {
      // MuJoCo's passive spring, -k (q - springref) - d q', as a spring drive.
      def["drive"] = hinge ? json{{"mode", "angle"}, {"target_rad", j.springref}, {"stiffness_N_m_per_rad", j.stiffness},
                                  {"damping_N_m_s_per_rad", j.damping}}
                           : json{{"mode", "position"}, {"target_m", j.springref}, {"stiffness_N_per_m", j.stiffness},
                                  {"damping_N_s_per_m", j.damping}};
    } else if (j.damping > 0.0) {
      // MuJoCo's joint damping, -d q': a damper toward standing still.
      def["drive"] = hinge ? json{{"mode", "velocity"}, {"target_rad_per_s", 0.0}, {"damping_N_m_s_per_rad", j.damping}}
                           : json{{"mode", "velocity"}, {"target_m_per_s", 0.0}, {"damping_N_s_per_m", j.damping}};
    }
    json& list = hinge ? hinges_ : joints_;
    joint_slot_[index] = {&list, list.size()};
    list.push_back(def);
  }

  // --- actuators (their controls held constant) --------------------------

  double control(const Actuator& a) const {
    const auto it = options_.controls.find(a.name);
    const double u = it == options_.controls.end() ? 0.0 : it->second;
    return a.ctrllimited ? std::clamp(u, a.ctrlrange[0], a.ctrlrange[1]) : u;
  }
  // A motor's force (N or N m at the joint or along the tendon: gear x ctrl,
  // within its forcerange).
  double motorForce(const Actuator& a) const {
    const double f = control(a);
    return a.gear * (a.forcelimited ? std::clamp(f, a.forcerange[0], a.forcerange[1]) : f);
  }
  void notImported(const Actuator& a, const std::string& why) {
    unmapped_.push_back(a.origin.where() + ": " + why + (a.target.empty() ? "" : " (on the " + a.target + ")"));
  }

  // A motor, position or velocity actuator on a hinge or slide: a drive.
  void addJointActuator(const Actuator& a) {
    if (a.tendon >= 0) return;  // addCable's
    if (a.joint < 0) return notImported(a, "an actuator not on a joint or tendon is not imported");
    const Joint& j = m_.joints[a.joint];
    const auto slot = joint_slot_.find(a.joint);
    if (slot == joint_slot_.end()) return notImported(a, "an actuator on a free or ball joint is not imported");
    json& def = (*slot->second.first)[slot->second.second];
    if (a.kind == "motor" && motorForce(a) == 0.0) return;  // at rest: it pushes nothing
    if (def.contains("drive")) return notImported(a, "a second drive on a joint with a spring or damping is not imported");
    const bool hinge = j.type == JointType::Hinge;
    const double g = a.gear, force_cap = a.forcelimited ? g * std::max(std::abs(a.forcerange[0]), std::abs(a.forcerange[1])) : 0.0;
    json drive;
    if (a.kind == "motor") {
      const double f = motorForce(a);
      drive = {{"mode", "velocity"}, {hinge ? "target_rad_per_s" : "target_m_per_s", std::copysign(kMotorSpeed, f)},
               {hinge ? "max_torque_N_m" : "max_force_N", std::abs(f)}};
    } else if (a.kind == "position" || a.kind == "velocity") {
      // Its force gain x (ctrl - gear q) (or q') acts with moment gear: a
      // spring or damper of gain x gear^2 toward ctrl / gear.
      const double u = control(a) / g;
      if (a.kind == "position") {
        drive = {{"mode", hinge ? "angle" : "position"}, {hinge ? "target_rad" : "target_m", u},
                 {hinge ? "stiffness_N_m_per_rad" : "stiffness_N_per_m", a.kp * g * g}};
        if (a.kv > 0.0) drive[hinge ? "damping_N_m_s_per_rad" : "damping_N_s_per_m"] = a.kv * g * g;
      } else {
        drive = {{"mode", "velocity"}, {hinge ? "target_rad_per_s" : "target_m_per_s", u},
                 {hinge ? "damping_N_m_s_per_rad" : "damping_N_s_per_m", a.kv * g * g}};
      }
      if (force_cap > 0.0) drive[hinge ? "max_torque_N_m" : "max_force_N"] = force_cap;
    } else {
      return notImported(a, "<" + a.kind + "> actuators are not imported yet");
    }
    def["drive"] = drive;
  }

  // The motor pulling tendon t, if one does (MuJoCo's tendon force is
  // negative where it shortens it), else null.
  // Whether actuator a pulls its tendon with its control held: a motor
  // whose force shortens it (MuJoCo's tendon force is negative then), a
  // muscle with a control above 0 (and a gear that pulls).
  bool pulls(const Actuator& a) const {
    if (a.kind == "motor") return motorForce(a) < 0.0;
    return a.kind == "muscle" && control(a) > 0.0 && a.gear > 0.0;
  }
  // The first actuator that pulls tendon t (tendonPull), or null.
  const Actuator* tendonPull(const Tendon& t) const {
    const int index = static_cast<int>(&t - m_.tendons.data());
    for (const Actuator& a : m_.actuators)
      if (a.tendon == index && pulls(a)) return &a;
    return nullptr;
  }
  // The end of tendon t where a winch's drum is: one tied to the world,
  // else its first site's body (the pull is between the tendon's ends all
  // the same: MuJoCo's tendon force acts on every body along it).
  const char* winchEnd(const Tendon& t) const {
    const auto onWorld = [&](const PathElement& e) {
      return e.kind == PathElement::Kind::Site && group_[m_.sites[e.index].body] == 0;
    };
    return t.path.empty() || onWorld(t.path.front()) ? "first" : onWorld(t.path.back()) ? "last" : "first";
  }
  bool pulledBy(const Tendon& t) const { return tendonPull(t) != nullptr; }

  // --- wrap cylinders ---------------------------------------------------

  void addWheels() {
    for (std::size_t gi = 0; gi < m_.geoms.size(); ++gi) {
      if (!wrap_[gi] || geom_body_.count(static_cast<int>(gi))) continue;  // the world's fixed ones are static already
      const Geom& g = m_.geoms[gi];
      const int owner = group_[g.body];
      const std::string other = owner == 0 ? "world" : reeve_body_.at(owner);
      const Pose p = wrapFrame(static_cast<int>(gi));
      const bool turning = options_.wheels == MjcfWheels::Turning;
      const std::string name = uniqueName(g.name, "wheel" + std::to_string(gi));
      double mass = turning ? g.mass : kWeldedWheelMass * (owner == 0 ? 0.0 : mass_.at(owner));
      if (!(mass > 0.0)) {  // a turning wheel of mass 0 (MuJoCo's wraps often are)
        mass = 1000.0 * geomVolume(g.type, g.size);
        unmapped_.push_back(g.origin.where() + ": mass 0 for a turning wheel; it weighs " + std::to_string(mass) +
                            " kg (density 1000)");
      }
      json body = {{"name", name}, {"shape", shapeOf(g)}, {"mass_kg", mass}, {"position_m", vec(p.pos)}};
      if (p.quat.angularDistance(Quat::Identity()) > 0.0) body["orientation"] = orientationJson(p.quat);
      if (turning) addContactKeys(body, {&g});  // fixed: its shape is its owner's already
      if (body.value("collides", false)) {
        colliding_.insert(name);
        if (owner != 0 && colliding_.count(other)) exclusions_.push_back(json::array({std::min(name, other), std::max(name, other)}));
      }
      bodies_.push_back(body);
      geom_body_[static_cast<int>(gi)] = name;
      if (turning)
        hinges_.push_back({{"body", name}, {"other", other}, {"anchor_m", vec(p.pos)}, {"axis", vec(p.quat * Vec3::UnitZ())}});
      else
        joints_.push_back({{"type", "fixed"}, {"body", name}, {"other", other}, {"anchor_m", vec(p.pos)}});
    }
  }

  // --- tendons ----------------------------------------------------------

  Vec3 sitePosition(int s) const { return m_.bodies[m_.sites[s].body].world.apply(m_.sites[s].pos); }
  Vec3 elementPoint(const PathElement& e) const {
    if (e.kind == PathElement::Kind::Site) return sitePosition(e.index);
    const Geom& g = m_.geoms[e.index];
    return m_.bodies[g.body].world.then(g.pose).pos;
  }

  // A site's link: tied to (or through) the Reeve body that carries it, at
  // its point in that body's frame; a site of the world gets a static body.
  json siteLink(int s, const char* type) {
    const Site& site = m_.sites[s];
    const Vec3 world = sitePosition(s);
    std::string body;
    Vec3 local;
    if (group_[site.body] == 0) {
      if (!site_body_.count(s)) {
        site_body_[s] = uniqueName(site.name, "site" + std::to_string(s));
        bodies_.push_back({{"name", site_body_[s]}, {"shape", {{"type", "sphere"}, {"radius_m", 0.005}}}, {"static", true},
                           {"position_m", vec(world)}});
      }
      body = site_body_[s];
      local = Vec3::Zero();
    } else {
      const Pose& f = frame_.at(group_[site.body]);
      body = reeve_body_.at(group_[site.body]);
      local = f.quat.conjugate() * (world - f.pos);
    }
    return {{"type", type}, {"body", body}, {"point_m", vec(local)}};
  }

  // A stretch of a tendon's path: its elements [begin, end), after a
  // pulley of `divisor` (1 for the first).
  struct Branch {
    std::size_t begin = 0, end = 0;
    double divisor = 1.0;
  };
  static std::vector<Branch> branchesOf(const Tendon& t) {
    std::vector<Branch> branches(1);
    for (std::size_t k = 0; k < t.path.size(); ++k) {
      if (t.path[k].kind != PathElement::Kind::Pulley) continue;
      branches.back().end = k;
      branches.push_back({k + 1, 0, t.path[k].divisor});
    }
    branches.back().end = t.path.size();
    return branches;
  }

  // The links of a branch's path: its first and last sites tied, the sites
  // between pinholes, its wraps rolling links (mu 0 where the wheels are
  // fixed, or where `slides`: a pulley branch, which is one run).
  json branchLinks(const Tendon& t, const Branch& branch, bool slides) {
    json links = json::array();
    for (std::size_t k = branch.begin; k < branch.end; ++k) {
      const PathElement& e = t.path[k];
      if (e.kind == PathElement::Kind::Site) {
        links.push_back(siteLink(e.index, k == branch.begin || k + 1 == branch.end ? "attachment" : "pinhole"));
        continue;
      }
      // A wrap: which way round, from the path's neighbours (and its
      // sidesite), in the cylinder's plane seen from its +z.
      const Geom& g = m_.geoms[e.index];
      const Pose p = wrapFrame(e.index);
      const auto inPlane = [&](const Vec3& w) { return Vec2((p.quat.conjugate() * (w - p.pos)).head<2>()); };
      const Vec2 a = inPlane(elementPoint(t.path[k - 1])), b = inPlane(elementPoint(t.path[k + 1]));
      const Vec2 d = b - a;
      const auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
      // Clockwise when the path passes the centre on its left (the centre
      // to the right of a -> b: a rope over the top of a wheel, left to
      // right), or round the side its sidesite is on.
      const Vec2 side_site = e.sidesite >= 0 ? inPlane(sitePosition(e.sidesite)) : Vec2::Zero();
      const double clockwise = e.sidesite >= 0 ? cross(d, side_site) : cross(d, a);
      json link = {{"type", "rolling"}, {"body", geom_body_.at(e.index)}, {"orientation", clockwise > 0.0 ? "cw" : "ccw"}};
      // A straight path that misses the cylinder is not wrapped until it
      // would cut it (Reeve's inactive link), unless a sidesite on the
      // other side of the centre makes MuJoCo wrap it the long way.
      const double t01 = d.squaredNorm() > 0.0 ? std::clamp(-a.dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      const Vec2 nearest = a + t01 * d;
      if (nearest.norm() >= g.size[0] && !(e.sidesite >= 0 && side_site.dot(nearest) < 0.0)) link["active"] = false;
      if (options_.wheels == MjcfWheels::Fixed || slides) link["mu"] = 0.0;
      links.push_back(link);
    }
    return links;
  }

  // The length (m) a tendon's cable or cables are to have in all: its
  // range's upper end, or its spring length; NaN: as long as at load. What
  // of its range, damping and frictionloss is not imported is listed.
  double tendonLength(const Tendon& t) {
    double length = std::numeric_limits<double>::quiet_NaN();
    if (t.limited) {
      if (t.range[0] > 0.0) unmapped_.push_back(t.origin.where() + ": the range's lower end is not imported (a cable does not push)");
      length = t.range[1];
    }
    if (t.stiffness > 0.0) {
      if (t.limited) unmapped_.push_back(t.origin.where() + ": the range with a stiffness is not imported (the cable is the spring)");
      length = t.springlength ? *t.springlength : std::numeric_limits<double>::quiet_NaN();
    } else if (t.damping > 0.0) {
      unmapped_.push_back(t.origin.where() + ": damping without stiffness is not imported");
    }
    if (t.frictionloss > 0.0) unmapped_.push_back(t.origin.where() + ": frictionloss not imported");
    return length;
  }

  void addCable(const Tendon& t) {
    if (!mappable(t, true)) {
      cable_lengths_.push_back({});
      return;
    }
    const std::vector<Branch> branches = branchesOf(t);
    if (branches.size() > 1) return addJunction(t, branches);
    json cable = {{"name", uniqueName(t.name, "tendon" + std::to_string(cables_.size()))},
                  {"links", branchLinks(t, branches[0], false)}};
    double length = tendonLength(t);
    if (t.stiffness > 0.0) {
      cable["compliance_m_per_N"] = 1.0 / t.stiffness;  // set per metre once its length is known
      if (t.damping > 0.0) cable["damping_N_s_per_m"] = t.damping;
    }
    const Actuator* puller = tendonPull(t);
    for (const Actuator& a : m_.actuators) {
      if (a.tendon != static_cast<int>(&t - m_.tendons.data())) continue;
      tendon_actuator_done_.insert(&a);
      if (a.kind == "muscle")
        notImported(a, "a muscle is a constant pull, control x peak force: its force-length and force-velocity curves, "
                       "passive force and activation are not imported");
      if (&a == puller) continue;
      if (a.kind != "motor" && a.kind != "muscle") notImported(a, "<" + a.kind + "> actuators are not imported yet");
      else if (a.kind == "motor" && motorForce(a) > 0.0) notImported(a, "a motor pushing along a tendon is not imported (a cable pulls only)");
      else if (a.kind == "muscle" && a.gear < 0.0) notImported(a, "a muscle with a negative gear pushes: not imported (a cable pulls only)");
      else if (pulls(a)) notImported(a, "a second actuator pulling a tendon is not imported");
    }
    if (puller) {
      // A winch at one end, hauling in faster than anything moves, stalled
      // at the actuator's pull: a constant tension. A muscle pulls with its
      // control times its peak force F0: `force`, or MuJoCo's scale / acc0,
      // set once the scene is built (mjcf_import.cpp).
      double pull = puller->kind == "motor" ? -motorForce(*puller) : control(*puller) * puller->force * puller->gear;
      if (puller->kind == "muscle" && !(puller->force > 0.0)) {
        muscle_pulls_.push_back({static_cast<int>(cables_.size()), control(*puller) * puller->scale, puller->origin});
        pull = 1.0;  // for now
      }
      cable["winch"] = {{"end", winchEnd(t)}, {"max_speed_m_per_s", kMotorSpeed}, {"max_pull_N", pull},
                        {"commands", json::array({{{"from_s", 0.0}, {"speed_m_per_s", kMotorSpeed}}})}};
      if (t.limited) unmapped_.push_back(t.origin.where() + ": the range of a tendon an actuator pulls is not imported");
      length = std::numeric_limits<double>::quiet_NaN();
    }
    cable_lengths_.push_back({{static_cast<int>(cables_.size())}, {1.0}, length});
    cables_.push_back(cable);
  }

  // A tendon of pulley branches: a cable per branch, joined by a junction
  // (sum_b L_b / divisor_b, MuJoCo's length). Its stiffness k is shared so
  // that the junction's compliance, sum_b c_b / divisor_b^2, is 1 / k: each
  // of n branches gets c_b = divisor_b^2 / (n k); its damping d likewise,
  // the branches' dashpots in series, d_b = n d / divisor_b^2.
  void addJunction(const Tendon& t, const std::vector<Branch>& branches) {
    const std::string name = uniqueName(t.name, "tendon" + std::to_string(&t - m_.tendons.data()));
    const double n = static_cast<double>(branches.size());
    TendonCables out;
    out.length = tendonLength(t);
    if (options_.wheels == MjcfWheels::Turning &&
        std::any_of(t.path.begin(), t.path.end(), [](const PathElement& e) { return e.kind == PathElement::Kind::Geom; }))
      unmapped_.push_back(t.origin.where() + ": its wraps do not turn its wheels (pulley branches slide over their wraps, mu 0)");
    json members = json::array();
    for (std::size_t b = 0; b < branches.size(); ++b) {
      const double divisor = branches[b].divisor;
      json cable = {{"name", uniqueName(name + "_branch" + std::to_string(b + 1), "branch")},
                    {"links", branchLinks(t, branches[b], true)}};
      if (t.stiffness > 0.0) {
        cable["compliance_m_per_N"] = divisor * divisor / (n * t.stiffness);
        if (t.damping > 0.0) cable["damping_N_s_per_m"] = n * t.damping / (divisor * divisor);
      }
      members.push_back({{"cable", cable["name"]}, {"divisor", divisor}});
      out.cables.push_back(static_cast<int>(cables_.size()));
      out.divisors.push_back(divisor);
      cables_.push_back(cable);
    }
    for (const Actuator& a : m_.actuators)
      if (a.tendon == static_cast<int>(&t - m_.tendons.data())) {
        tendon_actuator_done_.insert(&a);
        notImported(a, "an actuator on a tendon with pulley branches is not imported");
      }
    junctions_.push_back({{"name", name}, {"branches", members}});
    cable_lengths_.push_back(out);
  }

  // --- settings ---------------------------------------------------------

  json solver() const {
    // Substeps of MuJoCo's timestep, as many as make frames near 60 Hz.
    const int substeps = std::max(1, static_cast<int>(std::lround(1.0 / (60.0 * m_.timestep))));
    // The direct solver (the default, said so): the welded pulleys and the
    // links between joints weigh 1e-6 of their bodies, a ratio Gauss-Seidel
    // is not exact across (scenes/README.md, "MuJoCo models").
    json solver = {{"frame_rate_hz", 1.0 / (substeps * m_.timestep)}, {"substeps", substeps},
                   {"method", "direct"}, {"gravity_m_per_s2", vec(m_.gravity)}};
    // On a floor, contacts take every iteration (the direct solver stops
    // early only without them): at the default 2, humanoid.xml's landing
    // at MuJoCo's 5 ms step created energy in 43 frames of 120, at 5 in
    // one (12 J), at 10 in none.
    if (ground_) solver["iterations"] = kIterationsOnAFloor;
    return solver;
  }

  json camera() const {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Body& b : m_.bodies) lo = lo.cwiseMin(b.world.pos), hi = hi.cwiseMax(b.world.pos);
    for (std::size_t s = 0; s < m_.sites.size(); ++s) lo = lo.cwiseMin(sitePosition(static_cast<int>(s))), hi = hi.cwiseMax(sitePosition(static_cast<int>(s)));
    const Vec3 centre = 0.5 * (lo + hi);
    const double size = std::max(1.0, (hi - lo).norm());
    // MuJoCo's convention: up is against gravity (+z by default).
    const Vec3 up = m_.gravity.norm() > 0.0 ? Vec3(-m_.gravity.normalized()) : Vec3::UnitZ();
    const Vec3 side = up.unitOrthogonal();
    return {{"eye_m", vec(centre + 2.0 * size * side.cross(up) + 0.5 * size * up)}, {"target_m", vec(centre)}, {"up", vec(up)}};
  }

  const Model& m_;
  MjcfOptions options_;
  json scene_, bodies_ = json::array(), hinges_ = json::array(), joints_ = json::array(), cables_ = json::array(),
      junctions_ = json::array();
  std::optional<json> ground_;
  std::vector<char> wrap_;
  std::map<int, Pose> wrap_frame_;  // per wrapped sphere: its cable plane's frame (world)
  std::vector<int> group_;
  std::set<std::string> names_{"world"};
  std::map<int, std::string> reeve_body_, geom_body_, site_body_;
  std::map<int, Pose> frame_;  // a moving group's Reeve body frame (world)
  std::map<int, double> mass_;  // a moving group's mass (kg)
  std::map<int, std::pair<json*, std::size_t>> joint_slot_;
  std::set<const Actuator*> tendon_actuator_done_;  // listed or mapped by addCable  // per MJCF joint: its entry in hinges_ or joints_
  std::vector<std::string> unmapped_;
  std::vector<TendonCables> cable_lengths_;
  std::vector<Dof> dofs_;
  std::vector<MusclePull> muscle_pulls_;
  bool bodies_collide_ = false;  // findContacts
  bool has_plane_ = false;       // the world has a plane (findContacts): the ground
  std::set<std::string> colliding_;  // Reeve bodies that collide
  json exclusions_ = json::array();
};

}  // namespace

Mapping mapModel(const Model& model, const MjcfOptions& options) { return Mapper(model, options).map(); }

}  // namespace reeve::mjcf
