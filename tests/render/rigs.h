// Small scenes built in code for the render tests, one per feature the
// renderer shows: a square wheel, a pinhole, a spool, a loose span, a cable
// passing an inactive link, a belt.
#pragma once

#include <gtest/gtest.h>

#include <vector>

#include "reeve/cable/cable.h"
#include "reeve/render/cable_path.h"

namespace reeve::test {

/// A scene: a World and its cables (neither copied nor moved).
struct Rig {
  World world;
  CableSystem cables{world};
  int cable = 0;

  Rig() { world.settings().substeps = 20; }
  Rig(const Rig&) = delete;
  Rig& operator=(const Rig&) = delete;

  BodyId addStatic(const Shape& shape, const Vec3& position, const char* name = "") {
    BodyDef b;
    b.name = name;
    b.shape = shape;
    b.is_static = true;
    b.position = position;
    return world.addBody(b);
  }
  BodyId addDynamic(const Shape& shape, double mass, const Vec3& position,
                    const char* name = "") {
    BodyDef b;
    b.name = name;
    b.shape = shape;
    b.mass = mass;
    b.position = position;
    return world.addBody(b);
  }
  void run(int frames) {
    for (int f = 0; f < frames; ++f) world.step(1.0 / 60.0);
  }
};

/// The one polyline of an unbroken cable (cablePaths); a failure if there
/// is not exactly one.
inline std::vector<Vec3> onePath(const CableSystem& cables, int c, double max_step_rad) {
  auto paths = cablePaths(cables, c, max_step_rad);
  EXPECT_EQ(paths.size(), 1u);
  return paths.empty() ? std::vector<Vec3>{} : paths.front();
}

inline LinkDef attachment(BodyId body, const Vec3& point = Vec3::Zero()) {
  LinkDef l;
  l.body = body;
  l.type = LinkType::Attachment;
  l.point = point;
  return l;
}

inline LinkDef rolling(BodyId body, int orientation, Section section = {}) {
  LinkDef l;
  l.body = body;
  l.type = LinkType::Rolling;
  l.orientation = orientation;
  l.section = std::move(section);
  return l;
}

/// An Atwood machine over a square wheel (a box on a hinge, turned by
/// `angle` rad; its default section is its square): the cable runs from
/// the light box clockwise over the top of the square to the heavy box.
struct SquareWheelRig : Rig {
  static constexpr double kHalf = 0.25;  // m, half side of the square
  BodyId wheel, light_box, heavy_box;

  explicit SquareWheelRig(double angle = 0.3, double plane_offset = 0.0) {
    BodyDef w;
    w.name = "square wheel";
    w.shape = Shape::box(Vec3(kHalf, kHalf, 0.06));
    w.mass = 2.0;
    w.orientation = Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
    wheel = world.addBody(w);
    world.addHinge({wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ(), 0.0});
    light_box = addDynamic(Shape::box(Vec3(0.12, 0.12, 0.12)), 1.0, Vec3(-0.45, -1.1, 0.0));
    heavy_box = addDynamic(Shape::box(Vec3(0.15, 0.15, 0.15)), 1.5, Vec3(0.45, -1.1, 0.0));
    CableDef def;
    LinkDef on_wheel = rolling(wheel, -1);
    on_wheel.plane_offset = plane_offset;
    def.links = {attachment(light_box, Vec3(0.0, 0.12, 0.0)), on_wheel,
                 attachment(heavy_box, Vec3(0.0, 0.15, 0.0))};
    cable = cables.addCable(def);
  }
};

/// Paper Fig. 7 in small: a cable tied to a static block on the left runs
/// down through a pinhole in a static post and on to a hanging box.
struct PinholeRig : Rig {
  BodyId block, post, box;
  Vec3 hole = Vec3(0.0, 0.3, 0.0);  // world

  PinholeRig() {
    block = addStatic(Shape::box(Vec3(0.15, 0.1, 0.1)), Vec3(-1.0, 0.8, 0.0), "block");
    post = addStatic(Shape::box(Vec3(0.05, 0.05, 0.05)), Vec3(0.0, 0.3, 0.0), "post");
    box = addDynamic(Shape::box(Vec3(0.12, 0.12, 0.12)), 1.0, Vec3(0.5, -0.6, 0.0), "box");
    CableDef def;
    LinkDef pin;
    pin.body = post;
    pin.type = LinkType::Pinhole;
    def.links = {attachment(block, Vec3(0.0, -0.1, 0.0)), pin,
                 attachment(box, Vec3(0.0, 0.12, 0.0))};
    cable = cables.addCable(def);
  }
};

/// A spool: a drum (cylinder of radius kRadius on a hinge, or static)
/// whose first link is a hybrid (or rolling) end storing `stored` m of
/// cable, paying out to a hanging box. The cable leaves the drum's right
/// side going down (orientation -1: clockwise, walking from the drum).
struct SpoolRig : Rig {
  static constexpr double kRadius = 0.3;
  BodyId drum, box;

  explicit SpoolRig(double stored, LinkType type = LinkType::Hybrid, bool hinged = true,
                    Section section = {}) {
    BodyDef d;
    d.name = "drum";
    d.shape = Shape::cylinder(kRadius, 0.08);
    d.mass = 1.0;
    d.is_static = !hinged;
    drum = world.addBody(d);
    if (hinged) world.addHinge({drum, kWorldBody, Vec3::Zero(), Vec3::UnitZ(), 0.0});
    box = addDynamic(Shape::box(Vec3(0.12, 0.12, 0.12)), 1.0, Vec3(kRadius, -1.2, 0.0), "box");
    CableDef def;
    LinkDef spool = rolling(drum, -1, std::move(section));
    spool.type = type;
    spool.stored = stored;
    def.links = {spool, attachment(box, Vec3(0.0, 0.12, 0.0))};
    cable = cables.addCable(def);
  }
};

/// A loose cable between two static posts: rest length `slack` times the
/// distance between the tie points, which differ in height.
struct SlackRig : Rig {
  BodyId left, right;
  Vec3 a = Vec3(-1.0, 0.4, 0.0), b = Vec3(1.0, 0.1, 0.0);  // tie points, world

  explicit SlackRig(double slack) {
    left = addStatic(Shape::box(Vec3(0.05, 0.05, 0.05)), a, "left post");
    right = addStatic(Shape::box(Vec3(0.05, 0.05, 0.05)), b, "right post");
    CableDef def;
    def.links = {attachment(left), attachment(right)};
    def.rest_lengths = {slack * (b - a).norm()};
    cable = cables.addCable(def);
  }
};

/// A cable straight from a left post to a right post, passing high above a
/// wheel whose interior rolling link is inactive (the cable does not touch
/// it): joint 1, leaving the wheel, is disabled.
struct InactiveLinkRig : Rig {
  BodyId left, wheel, right;

  InactiveLinkRig() {
    left = addStatic(Shape::box(Vec3(0.05, 0.05, 0.05)), Vec3(-1.0, 1.0, 0.0), "left post");
    wheel = addStatic(Shape::cylinder(0.2, 0.05), Vec3(-0.2, -0.5, 0.0), "wheel");
    right = addStatic(Shape::box(Vec3(0.05, 0.05, 0.05)), Vec3(1.0, 1.0, 0.0), "right post");
    CableDef def;
    LinkDef idle = rolling(wheel, 1);
    idle.active = false;
    def.links = {attachment(left), idle, attachment(right)};
    cable = cables.addCable(def);
  }
};

/// A closed belt round two static wheels side by side, both wrapped
/// counter-clockwise.
struct BeltRig : Rig {
  static constexpr double kRadius = 0.25;
  BodyId left, right;

  BeltRig() {
    left = addStatic(Shape::cylinder(kRadius, 0.05), Vec3(-0.6, 0.0, 0.0), "left wheel");
    right = addStatic(Shape::cylinder(kRadius, 0.05), Vec3(0.6, 0.0, 0.0), "right wheel");
    CableDef def;
    def.closed = true;
    def.links = {rolling(left, 1), rolling(right, 1)};
    cable = cables.addCable(def);
  }
};

}  // namespace reeve::test
