// A small Atwood machine built in code for the render tests: a wheel on a
// hinge at the origin, two boxes hanging from a cable over it
// (attachment -> rolling, clockwise -> attachment), a static beam above.
#pragma once

#include <cmath>
#include <numbers>

#include "reeve/cable/cable.h"
#include "reeve/render/camera.h"

namespace reeve::test {

struct AtwoodRig {
  static constexpr double kRadius = 0.3;  // wheel, m
  World world;
  CableSystem cables{world};
  BodyId wheel, beam, light_box, heavy_box;
  int cable;

  AtwoodRig() {
    world.settings().substeps = 20;
    BodyDef w;
    w.name = "wheel";
    w.shape = Shape::cylinder(kRadius, 0.06);
    w.mass = 2.0;
    wheel = world.addBody(w);
    world.addHinge({wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ(), 0.0});
    BodyDef b;
    b.name = "beam";
    b.shape = Shape::box(Vec3(0.5, 0.05, 0.15));
    b.is_static = true;
    b.position = Vec3(0.0, 0.6, 0.0);
    beam = world.addBody(b);
    BodyDef box;
    box.shape = Shape::box(Vec3(0.12, 0.12, 0.12));
    box.mass = 1.0;
    box.position = Vec3(-kRadius, -1.2, 0.0);
    light_box = world.addBody(box);
    box.shape = Shape::box(Vec3(0.15, 0.15, 0.15));
    box.mass = 2.0;
    box.position = Vec3(kRadius, -1.2, 0.0);
    heavy_box = world.addBody(box);
    CableDef def;
    def.links.resize(3);
    def.links[0].body = light_box;
    def.links[0].point = Vec3(0.0, 0.12, 0.0);
    def.links[1].body = wheel;
    def.links[1].type = LinkType::Rolling;
    def.links[1].orientation = -1;
    def.links[2].body = heavy_box;
    def.links[2].point = Vec3(0.0, 0.15, 0.0);
    cable = cables.addCable(def);
  }

  void run(int frames) {
    for (int f = 0; f < frames; ++f) world.step(1.0 / 60.0);
  }
};

/// Pixel (x right, y down from the top-left corner) where the world point
/// `p` appears, by the gluLookAt / gluPerspective maths, written here
/// independently of the renderer.
inline Eigen::Vector2d projectToPixel(const Camera& camera, const Vec3& p, int width,
                                      int height) {
  const Vec3 forward = (camera.target - camera.eye).normalized();
  const Vec3 right = forward.cross(camera.up).normalized();
  const Vec3 up = right.cross(forward);
  const Vec3 d = p - camera.eye;
  const double t = std::tan(camera.fov_y_deg * std::numbers::pi / 360.0);
  const double ndc_x = d.dot(right) / (d.dot(forward) * t * width / height);
  const double ndc_y = d.dot(up) / (d.dot(forward) * t);
  return {0.5 * (ndc_x + 1.0) * width, 0.5 * (1.0 - ndc_y) * height};
}

}  // namespace reeve::test
