#include "viewer_files.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <numbers>

#include "reeve/engine/convex_hull.h"
#include "reeve/render/cable_path.h"

namespace reeve {
namespace {

namespace fs = std::filesystem;

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

const char* driveName(HingeDrive::Mode mode) {
  switch (mode) {
    case HingeDrive::Mode::None: return "none";
    case HingeDrive::Mode::Angle: return "angle";
    case HingeDrive::Mode::Velocity: return "velocity";
  }
  return "none";
}

std::string plainBodyName(const World& world, BodyId id) {
  return id == kWorldBody ? std::string("world") : world.bodyDef(id).name;
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

std::string readViewerFile(const std::string& name, const char* option) {
  const fs::path path = viewerDir() / name;
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (!(in && text << in.rdbuf()))
    throw ViewerMissing(std::string(option) + ": cannot read the viewer's " + path.string() +
                        "; run `bash tools/setup.sh` (it installs three.js with npm ci in viewer/), or set "
                        "REEVE_VIEWER_DIR to a folder holding the viewer");
  return text.str();
}

std::vector<std::vector<Vec3>> viewerSpoolCoils(const CableSystem& cables, int c) {
  constexpr double kPitch = 0.02, kBand = 0.2;  // of the spool's radius
  const std::vector<Link>& links = cables.cables()[c].links;
  std::vector<std::vector<Vec3>> coils;
  for (const int k : {0, static_cast<int>(links.size()) - 1}) {
    const double radius = links[k].section.perimeter() / (2.0 * std::numbers::pi);
    std::vector<Vec3> coil = spoolCoil(cables, c, k, kPitch * radius, kViewerArcStepRad, kBand * radius);
    if (coil.size() >= 2) coils.push_back(std::move(coil));
  }
  return coils;
}

nlohmann::json sceneHead(const Scene& scene) {
  const World& world = *scene.world;
  nlohmann::json bodies = nlohmann::json::array(), cables = nlohmann::json::array(), hinges = nlohmann::json::array();
  // The sections rolling links wrap where the body's shape does not show
  // them (a polygon on a cylinder, a circle on a box), as the PNGs outline
  // them: body-local polylines, one per body and section.
  std::vector<nlohmann::json> outlines(world.bodyCount(), nlohmann::json::array());
  std::vector<std::pair<BodyId, const Link*>> outlined;
  const BodyState at_origin;  // body-local points
  for (const Cable& cable : scene.cables->cables())
    for (const Link& link : cable.links) {
      if ((link.type != LinkType::Rolling && link.type != LinkType::Hybrid) ||
          sectionMatchesShape(link, world.bodyDef(link.body).shape))
        continue;
      const bool seen = std::any_of(outlined.begin(), outlined.end(), [&](const auto& o) {
        return o.first == link.body && o.second->plane_offset == link.plane_offset &&
               o.second->section == link.section;
      });
      if (seen) continue;
      outlined.emplace_back(link.body, &link);
      nlohmann::json points = nlohmann::json::array();
      for (const Vec3& p : sectionOutline(link, at_origin, kViewerArcStepRad))
        for (int k = 0; k < 3; ++k) points.push_back(p[k]);
      outlines[link.body].push_back(points);
    }
  for (BodyId id = 0; id < world.bodyCount(); ++id) {
    const BodyDef& def = world.bodyDef(id);
    bodies.push_back({{"name", def.name},
                      {"shape", shapeJson(def.shape)},
                      {"dynamic", world.bodyMass(id) > 0.0},
                      {"outlines", outlines[id]}});
  }
  for (const Cable& cable : scene.cables->cables())
    cables.push_back({{"name", cable.name}, {"joints", cable.joints.size()}, {"winch", cable.winch.has_value()}});
  for (const HingeJoint& j : world.hinges())
    hinges.push_back({{"body", plainBodyName(world, j.a)},
                      {"other", plainBodyName(world, j.b)},
                      {"drive", driveName(j.drive.mode)}});
  nlohmann::json camera = nullptr;
  if (scene.camera)
    camera = {{"eye", vec(scene.camera->eye)}, {"target", vec(scene.camera->target)},
              {"up", vec(scene.camera->up)}, {"fov_y_deg", scene.camera->fov_y_deg}};
  return {{"name", scene.name},     {"description", scene.description},
          {"frame_rate_hz", scene.frame_rate_hz}, {"gravity", vec(world.settings().gravity)},
          {"camera", camera},       {"bodies", bodies},
          {"cables", cables},       {"hinges", hinges}};
}

}  // namespace reeve
