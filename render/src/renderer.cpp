#include "reeve/render/renderer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <GL/osmesa.h>

#include "draw.h"
#include "reeve/engine/fp_exceptions.h"
#include "reeve/render/markers.h"
#include "reeve/render/cable_path.h"
#include "scene_points.h"
#include "supersample.h"
#include "view.h"

namespace reeve {
namespace {

constexpr int kSupersample = 3;  // 3x3 samples per output pixel, where OSMesa allows
constexpr double kArcStepRad = 2.0 * std::numbers::pi / 96.0;

// Where the floor goes and how far everything drawn reaches (m, world).
struct Layout {
  Vec3 floor_centre = Vec3::Zero();  // just below the lowest body, under the scene's centre
  double floor_half = 1.0;           // half side of the square floor
  Eigen::AlignedBox3d all;           // bodies, cables and floor
};

Layout layout(const World& world, const CableSystem& cables) {
  Eigen::AlignedBox3d scene;
  for (const Vec3& p : scenePoints(world, cables)) scene.extend(p);
  if (scene.isEmpty()) scene.extend(Vec3::Zero());
  const double extent = std::max(scene.sizes().maxCoeff(), 1e-3);
  Layout l;
  l.floor_centre = Vec3(scene.center().x(), scene.min().y() - 0.02 * extent, scene.center().z());
  l.floor_half = 0.75 * extent;
  l.all = scene;
  l.all.extend(l.floor_centre - Vec3(l.floor_half, 0.0, l.floor_half));
  l.all.extend(l.floor_centre + Vec3(l.floor_half, 0.0, l.floor_half));
  return l;
}

void setUpLights() {
  // Positions are given with an identity model-view: fixed to the camera.
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  const GLfloat ambient[] = {0.32f, 0.32f, 0.33f, 1.0f};
  const GLfloat key_position[] = {-0.45f, 0.65f, 0.62f, 0.0f};
  const GLfloat key_diffuse[] = {0.72f, 0.71f, 0.69f, 1.0f};
  const GLfloat key_specular[] = {0.35f, 0.35f, 0.35f, 1.0f};
  const GLfloat fill_position[] = {0.7f, -0.1f, 0.7f, 0.0f};
  const GLfloat fill_diffuse[] = {0.25f, 0.26f, 0.28f, 1.0f};
  const GLfloat black[] = {0.0f, 0.0f, 0.0f, 1.0f};
  const GLfloat specular[] = {0.30f, 0.30f, 0.30f, 1.0f};
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  glLightfv(GL_LIGHT0, GL_POSITION, key_position);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, key_diffuse);
  glLightfv(GL_LIGHT0, GL_SPECULAR, key_specular);
  glLightfv(GL_LIGHT1, GL_POSITION, fill_position);
  glLightfv(GL_LIGHT1, GL_DIFFUSE, fill_diffuse);
  glLightfv(GL_LIGHT1, GL_SPECULAR, black);
  glEnable(GL_LIGHT0);
  glEnable(GL_LIGHT1);
  glColorMaterial(GL_FRONT, GL_AMBIENT_AND_DIFFUSE);
  glEnable(GL_COLOR_MATERIAL);
  glMaterialfv(GL_FRONT, GL_SPECULAR, specular);
  glMaterialf(GL_FRONT, GL_SHININESS, 40.0f);
}

// Projection with a depth range around everything drawn, lights fixed to
// the camera, then the view: the model-view matrix ends as world -> eye.
void loadCamera(const Camera& camera, const Layout& l, double aspect) {
  const double reach = 0.5 * l.all.diagonal().norm();
  const double eye_to_centre = (camera.eye - l.all.center()).norm();
  const double far = 1.01 * (eye_to_centre + reach);
  const double near = std::max(0.99 * (eye_to_centre - reach), 1e-3 * far);
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(projectionMatrix(camera, aspect, near, far).data());
  setUpLights();
  glLoadMatrixd(viewMatrix(camera).data());
}

// The floor, unlit, fading into the background with distance. Not drawn
// when the camera is below it: seen from underneath it would only hide the
// bodies above it.
void drawGround(const Camera& camera, const Layout& l, float line_px) {
  if (camera.eye.y() <= l.floor_centre.y()) return;
  const double eye_to_floor = (camera.eye - l.floor_centre).norm();
  const GLfloat fog_colour[] = {style::kBackground.x(), style::kBackground.y(),
                                style::kBackground.z(), 1.0f};
  glFogi(GL_FOG_MODE, GL_LINEAR);
  glFogfv(GL_FOG_COLOR, fog_colour);
  glFogf(GL_FOG_START, static_cast<float>(eye_to_floor - 0.5 * l.floor_half));
  glFogf(GL_FOG_END, static_cast<float>(eye_to_floor + 1.5 * l.floor_half));
  glDisable(GL_LIGHTING);
  glDisable(GL_CULL_FACE);
  glEnable(GL_FOG);
  drawFloor(l.floor_centre.y(), l.floor_centre.x(), l.floor_centre.z(), l.floor_half, line_px);
  glDisable(GL_FOG);
}

void drawBodies(const ShapeMeshes& meshes, const World& world) {
  glEnable(GL_LIGHTING);
  glEnable(GL_NORMALIZE);  // shapes are scaled unit meshes
  glEnable(GL_CULL_FACE);
  for (BodyId id = 0; id < world.bodyCount(); ++id) {
    const BodyDef& def = world.bodyDef(id);
    drawBody(meshes, def.shape, world.body(id), style::bodyColour(id, def.is_static));
  }
}

// `mesh` in `colour`, then where it is hidden behind bodies faintly
// through them: front faces only, each pixel blended once (stencil).
void drawSeeThrough(const Mesh& mesh, const style::Colour& colour) {
  setColour(colour);
  drawMesh(mesh);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_EQUAL, 0, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
  setColour(colour, style::kHiddenCableAlpha);
  drawMesh(mesh);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

// Outlines of the sections rolling links wrap where the body's shape does
// not show them, thin tubes in a dark shade of the body's colour, one per
// body and section.
void drawSectionOutlines(const ShapeMeshes& meshes, const CableSystem& cables, double radius) {
  const World& world = cables.world();
  std::vector<std::pair<BodyId, const Link*>> drawn;
  for (const Cable& cable : cables.cables())
    for (const Link& link : cable.links) {
      const BodyDef& def = world.bodyDef(link.body);
      if ((link.type != LinkType::Rolling && link.type != LinkType::Hybrid) ||
          sectionMatchesShape(link, def.shape))
        continue;
      const bool seen = std::any_of(drawn.begin(), drawn.end(), [&](const auto& d) {
        return d.first == link.body && d.second->plane_offset == link.plane_offset &&
               d.second->section == link.section;
      });
      if (seen) continue;
      drawn.emplace_back(link.body, &link);
      Mesh outline;
      appendTube(outline, sectionOutline(link, world.body(link.body), kArcStepRad), radius,
                 kTubeSides / 2, meshes.ball);
      drawSeeThrough(outline, style::bodyColour(link.body, def.is_static) *
                                  style::kSectionOutlineShade);
    }
}

// Link markers in the paper's colours (see style.h), over everything.
// Back faces are culled, so a ball needs no depth test to cover itself
// correctly; hybrid rings face the camera.
void drawMarkers(const ShapeMeshes& meshes, const CableSystem& cables, const Camera& camera,
                 double radius) {
  glDisable(GL_DEPTH_TEST);
  for (const Marker& m : linkMarkers(cables)) {
    const auto ball = [&](const style::Colour& colour) {
      setColour(colour);
      drawBall(meshes, m.at, radius);
    };
    const auto ring = [&](const style::Colour& colour) {
      setColour(colour);
      drawRing(meshes, m.at, (camera.eye - m.at).normalized(), style::kHybridRingRadius * radius);
    };
    switch (m.kind) {
      case MarkerKind::Rolling: ball(style::kRollingMarker); break;
      case MarkerKind::Attachment: ball(style::kAttachmentMarker); break;
      case MarkerKind::Pinhole: ball(style::kPinholeMarker); break;
      case MarkerKind::HybridRolling:
        ball(style::kRollingMarker);
        ring(style::kAttachmentMarker);
        break;
      case MarkerKind::HybridAttached:
        ball(style::kAttachmentMarker);
        ring(style::kRollingMarker);
        break;
    }
  }
  glEnable(GL_DEPTH_TEST);
}

// How far a body reaches across the view (m): the largest of its half
// sizes seen from direction `view` (unit, world). A thin disc seen face on
// shows its radius; a thin peg seen end on little more than its own.
double visibleHalfSize(const Shape& shape, const BodyState& body, const Vec3& view) {
  const auto across = [&](int axis, double half) { return half * (body.q * Vec3::Unit(axis)).cross(view).norm(); };
  switch (shape.type) {
    case Shape::Type::Box:
      return std::max({across(0, shape.half_extents.x()), across(1, shape.half_extents.y()),
                       across(2, shape.half_extents.z())});
    case Shape::Type::Cylinder: return std::max(shape.radius, across(2, shape.half_length));
    case Shape::Type::Sphere: return shape.radius;
    case Shape::Type::Hull: return shape.hull->bounding_radius;
  }
  return 0.0;
}

// Bodies smaller than a link marker at their distance (a 1 cm peg, a 3 cm
// spool in a 5 m scene) would vanish under their markers and cable: a ring
// in the body's colour round each, facing the camera, over everything,
// keeps them in sight. `pixel` (m) is a pixel's size at the target.
void drawSmallBodyRings(const ShapeMeshes& meshes, const World& world, const Camera& camera, double pixel,
                        double marker_radius) {
  const Vec3 forward = (camera.target - camera.eye).normalized();
  const double target_depth = (camera.target - camera.eye).norm();
  glDisable(GL_DEPTH_TEST);
  for (BodyId id = 0; id < world.bodyCount(); ++id) {
    const Vec3& centre = world.body(id).x;
    const double depth = (centre - camera.eye).dot(forward);
    if (depth <= 0.0) continue;  // behind the camera
    const double scale = depth / target_depth;  // marker_radius and pixel are sizes at the target
    const Vec3 view = (camera.eye - centre).normalized();
    const double size = visibleHalfSize(world.bodyDef(id).shape, world.body(id), view);
    if (size >= marker_radius * scale) continue;
    setColour(style::bodyColour(id, world.bodyDef(id).is_static));
    drawRing(meshes, centre, view, size + (style::kSmallBodyRingScale * marker_radius + pixel) * scale);
  }
  glEnable(GL_DEPTH_TEST);
}

}  // namespace

struct Renderer::Context {
  OSMesaContext osmesa = nullptr;
  int supersample = kSupersample;
  std::vector<std::uint8_t> buffer;  // RGBA, supersampled, bottom row first
  ShapeMeshes meshes;

  ~Context() {
    const FloatingPointExceptionsMasked mesa;  // Mesa raises them as a matter of course
    if (osmesa) OSMesaDestroyContext(osmesa);
  }
  void makeCurrent(int width, int height) {
    if (!OSMesaMakeCurrent(osmesa, buffer.data(), GL_UNSIGNED_BYTE, width, height))
      throw std::runtime_error("Renderer: OSMesaMakeCurrent failed for a " +
                               std::to_string(width) + "x" + std::to_string(height) +
                               " RGBA buffer");
  }
};

Renderer::Renderer(int width, int height) : width_(width), height_(height) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("Renderer: image size must be positive, got " +
                                std::to_string(width) + "x" + std::to_string(height));
  const FloatingPointExceptionsMasked mesa;  // Mesa raises them as a matter of course
  context_ = std::make_unique<Context>();
  Context& c = *context_;
  c.osmesa = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
  if (!c.osmesa)
    throw std::runtime_error(
        "Renderer: OSMesaCreateContextExt (RGBA, 24-bit depth, 8-bit stencil) failed; is "
        "Mesa's libOSMesa installed (apt-get install libosmesa6)?");
  // OSMesa accepts larger buffers but clips drawing to its maximum size.
  c.buffer.resize(4);
  c.makeCurrent(1, 1);
  GLint max_width = 0, max_height = 0;
  OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &max_width);
  OSMesaGetIntegerv(OSMESA_MAX_HEIGHT, &max_height);
  c.supersample = std::min({kSupersample, max_width / width, max_height / height});
  if (c.supersample < 1)
    throw std::runtime_error("Renderer: " + std::to_string(width) + "x" +
                             std::to_string(height) + " exceeds OSMesa's maximum of " +
                             std::to_string(max_width) + "x" + std::to_string(max_height));
  c.buffer.resize(4 * std::size_t(width) * c.supersample * height * c.supersample);
  c.makeCurrent(width * c.supersample, height * c.supersample);
}

Renderer::~Renderer() = default;

Image Renderer::render(const World& world, const CableSystem& cables, const Camera& camera) {
  const FloatingPointExceptionsMasked mesa;  // Mesa raises them as a matter of course
  const int factor = context_->supersample;
  const int w = width_ * factor, h = height_ * factor;
  context_->makeCurrent(w, h);
  const ShapeMeshes& meshes = context_->meshes;
  Layout l = layout(world, cables);
  // The floor only ever moves down and grows, so it does not jump about in
  // a video as weights rise and fall.
  if (floor_) {
    l.floor_centre = Vec3(floor_->x(), std::min(floor_->y(), l.floor_centre.y()), floor_->z());
    l.floor_half = std::max(floor_half_, l.floor_half);
    l.all.extend(l.floor_centre - Vec3(l.floor_half, 0.0, l.floor_half));
    l.all.extend(l.floor_centre + Vec3(l.floor_half, 0.0, l.floor_half));
  }
  floor_ = l.floor_centre;
  floor_half_ = l.floor_half;

  glViewport(0, 0, w, h);
  glClearColor(style::kBackground.x(), style::kBackground.y(), style::kBackground.z(), 1.0f);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  loadCamera(camera, l, double(width_) / height_);
  drawGround(camera, l, factor);
  drawBodies(meshes, world);

  // Cable thickness: a fixed number of pixels at the target's distance.
  const double pixel = 2.0 * (camera.target - camera.eye).norm() *
                       std::tan(camera.fov_y_deg * std::numbers::pi / 360.0) / height_;
  const double cable_radius = style::kCableRadiusPx * pixel;
  drawSectionOutlines(meshes, cables, style::kSectionOutlineScale * cable_radius);
  Mesh tubes;
  for (int c = 0; c < static_cast<int>(cables.cables().size()); ++c) {
    for (const auto& piece : cablePaths(cables, c, kArcStepRad))
      appendTube(tubes, piece, cable_radius, kTubeSides, meshes.ball);
    const int last = static_cast<int>(cables.cables()[c].links.size()) - 1;
    for (int k : {0, last})
      appendTube(tubes,
                 spoolCoil(cables, c, k, style::kCoilPitchScale * cable_radius, kArcStepRad,
                           style::kCoilMinBandScale * cable_radius),
                 style::kCoilTubeScale * cable_radius, kTubeSides / 2, meshes.ball);
  }
  drawSeeThrough(tubes, style::kCable);
  drawMarkers(meshes, cables, camera, style::kMarkerScale * cable_radius);
  drawSmallBodyRings(meshes, world, camera, pixel, style::kMarkerScale * cable_radius);

  glFinish();
  return downsample(context_->buffer, width_, height_, factor);
}

}  // namespace reeve
