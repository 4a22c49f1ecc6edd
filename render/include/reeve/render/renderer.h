// Off-screen OpenGL renderer of a World and its cables (OSMesa: software
// rendering, no display or GPU needed). Including this header gives the
// whole render API: camera, images and PNG, video.
#pragma once

#include <memory>
#include <optional>

#include "reeve/cable/cable.h"
#include "reeve/render/camera.h"
#include "reeve/render/image.h"
#include "reeve/render/video.h"

namespace reeve {

/// Draws bodies (shaded boxes, cylinders, spheres; dynamic bodies in blues,
/// static ones in warm greys), a ground grid just below the lowest body, and
/// the cables as dark tubes (see cablePaths): the enabled spans only, loose ends hanging where a cable parted,
/// straight when taut and hanging as catenaries when loose, the arcs wrapped
/// on rolling links along their sections (polygon hulls too), and the cable
/// stored on spools as a coil (see spoolCoil). A section a rolling link
/// wraps that the body's shape does not show (a groove, a polygon on a
/// cylinder) is outlined thinly in a dark shade of the body's colour. Cable
/// hidden behind a body shows through it faintly. Link markers are drawn on
/// top in the paper's colours: red at the tangent points of rolling links,
/// green at attachments, blue at pinholes, and for hybrid links a red ball
/// with a green ring while rolling, a green ball with a red ring once tied;
/// inactive links get none.
/// Anti-aliased by 3x3 supersampling (less for images wider or taller than
/// a third of OSMesa's maximum, 16384 pixels with Mesa 22). Holds one OSMesa
/// context; reuse one Renderer for many frames. Not thread-safe: use it from
/// one thread at a time.
class Renderer {
 public:
  /// An off-screen context for images of width x height pixels.
  /// Throws std::invalid_argument unless both are positive, and
  /// std::runtime_error if OSMesa cannot create or bind the context or the
  /// size exceeds OSMesa's maximum.
  explicit Renderer(int width = 1280, int height = 720);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }

  /// One frame of the current poses of `world` (which must be the World of
  /// `cables`) seen through `camera`. The floor is placed below the lowest
  /// body and, across frames of one Renderer, only moves down or grows. Throws std::runtime_error if the
  /// context cannot be made current.
  Image render(const World& world, const CableSystem& cables, const Camera& camera);

 private:
  struct Context;
  int width_, height_;
  std::unique_ptr<Context> context_;
  std::optional<Vec3> floor_;  // floor centre of the last frame (m, world)
  double floor_half_ = 0.0;    // its half side (m)
};

}  // namespace reeve
