#include "build.h"

#include <climits>
#include <cmath>

#include "describe.h"

namespace reeve::scene_detail {
namespace {

// Defaults of optional keys; scene.schema.json states the same under
// "default" (a test compares them).
constexpr double kFrameRateHz = 60.0;
constexpr int kSubsteps = 10;
constexpr int kIterations = 2;
constexpr const char* kMethod = "direct";
constexpr double kDurationS = 5.0;
const Vec3 kGravity(0.0, -9.81, 0.0);

SolverSettings solverOf(const nlohmann::json& solver, const std::string& source) {
  SolverSettings settings;
  settings.gravity =
      solver.contains("gravity_m_per_s2") ? vec3(solver.at("gravity_m_per_s2")) : kGravity;
  settings.substeps = solver.value("substeps", kSubsteps);
  settings.iterations = solver.value("iterations", kIterations);
  // The schema allows only the known names.
  settings.solver = *solverMethodFromName(solver.value("method", std::string(kMethod)));
  if (solver.value("projection", std::string("end")) == "start") {
    if (settings.solver != SolverKind::Direct)
      throw SceneError(source, "/solver/projection", "\"end\" with method \"gauss-seidel\" (the start projection is the direct solver's)",
                       "\"start\"");
    settings.projection = Projection::Start;
  }
  settings.max_linear_speed = solver.value("max_linear_speed_m_per_s", settings.max_linear_speed);
  settings.max_angular_speed = solver.value("max_angular_speed_rad_per_s", settings.max_angular_speed);
  return settings;
}

CameraDef cameraOf(const nlohmann::json& camera, const std::string& source) {
  CameraDef def;
  def.eye = vec3(camera.at("eye_m"));
  def.target = vec3(camera.at("target_m"));
  if (camera.contains("up")) def.up = vec3(camera.at("up"));
  def.fov_y_deg = camera.value("fov_y_deg", def.fov_y_deg);
  const Vec3 view = def.target - def.eye;
  if (view.squaredNorm() == 0.0)
    throw SceneError(source, "/camera/target_m", "a point other than eye_m",
                     literal(camera.at("target_m")));
  if (def.up.cross(view).norm() <= 1e-9 * def.up.norm() * view.norm())
    throw SceneError(source, "/camera/up",
                     "a direction not parallel to the view direction target_m - eye_m",
                     camera.contains("up") ? literal(camera.at("up")) : "the default [0,1,0]");
  return def;
}

// "ground": the schema checks the numbers; the normal must be non-zero.
GroundPlane groundOf(const nlohmann::json& ground, const std::string& source) {
  GroundPlane g;
  g.height_m = ground.value("height_m", g.height_m);
  if (const auto n = ground.find("normal"); n != ground.end()) {
    g.normal = vec3(*n);
    if (g.normal.squaredNorm() == 0.0)
      throw SceneError(source, "/ground/normal", "a non-zero normal", literal(*n));
  }
  g.material.static_friction = ground.value("static_friction", g.material.static_friction);
  g.material.dynamic_friction = ground.value("dynamic_friction", g.material.dynamic_friction);
  g.material.restitution = ground.value("restitution", g.material.restitution);
  return g;
}

}  // namespace

Scene buildScene(const nlohmann::json& document, const std::string& source) {
  Scene scene;
  scene.name = document.at("name").get<std::string>();
  scene.description = document.value("description", std::string());
  const nlohmann::json& solver = document.at("solver");
  scene.frame_rate_hz = solver.value("frame_rate_hz", kFrameRateHz);
  scene.duration_s = document.value("duration_s", kDurationS);
  const double frames = std::round(scene.duration_s * scene.frame_rate_hz);
  if (frames < 1.0 || frames > INT_MAX)
    throw SceneError(source, "/duration_s",
                     "a duration of 1 to " + std::to_string(INT_MAX) +
                         " frames at solver/frame_rate_hz " + number(scene.frame_rate_hz),
                     number(scene.duration_s) + " s (" + number(frames) + " frames)");

  scene.world = std::make_unique<World>(solverOf(solver, source));
  scene.cables = std::make_unique<CableSystem>(*scene.world);
  const BodyNames names = addBodies(document.at("bodies"), *scene.world, source);
  if (const auto pairs = document.find("contact_exclusions"); pairs != document.end())
    excludeContacts(*pairs, names, *scene.world, source);
  if (const auto ground = document.find("ground"); ground != document.end())
    scene.world->setGround(groundOf(*ground, source));
  if (const auto hinges = document.find("hinges"); hinges != document.end())
    addHinges(*hinges, names, *scene.world, source);
  if (const auto joints = document.find("joints"); joints != document.end())
    scene.joint_kinds = addJoints(*joints, names, *scene.world, source);
  if (const auto cables = document.find("cables"); cables != document.end())
    addCables(*cables, names, *scene.cables, source);
  if (const auto junctions = document.find("junctions"); junctions != document.end())
    addJunctions(*junctions, *scene.cables, source);
  if (const auto camera = document.find("camera"); camera != document.end())
    scene.camera = cameraOf(*camera, source);
  return scene;
}

}  // namespace reeve::scene_detail

namespace reeve {

int Scene::frameCount() const { return static_cast<int>(std::lround(duration_s * frame_rate_hz)); }

}  // namespace reeve
