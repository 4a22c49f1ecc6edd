// Worlds, bodies and measurements shared by the contact tests
// (test_contacts.cpp, test_hull.cpp).
#pragma once

#include <cmath>

#include "reeve/engine/world.h"

namespace reeve::test {

inline constexpr double kG = 9.81;          // m/s^2
inline constexpr double kFrame = 1.0 / 60;  // s

/// A world with gravity `gravity` (m/s^2) and the given solver budget.
inline World makeWorld(int substeps, int iterations, const Vec3& gravity = Vec3(0.0, -kG, 0.0)) {
  SolverSettings s;
  s.gravity = gravity;
  s.substeps = substeps;
  s.iterations = iterations;
  return World(s);
}

inline ContactMaterial material(double mu_s, double mu_d, double e) {
  ContactMaterial m;
  m.static_friction = mu_s;
  m.dynamic_friction = mu_d;
  m.restitution = e;
  return m;
}

inline GroundPlane ground(const Vec3& normal, const ContactMaterial& m) {
  GroundPlane g;
  g.normal = normal;
  g.material = m;
  return g;
}

/// A dynamic body of `mass` (kg) at `position` (m).
inline BodyId add(World& world, const Shape& shape, double mass, const Vec3& position,
                  const ContactMaterial& m, bool collides = false,
                  const Quat& orientation = Quat::Identity()) {
  BodyDef def;
  def.shape = shape;
  def.mass = mass;
  def.position = position;
  def.orientation = orientation;
  def.material = m;
  def.collides = collides;
  return world.addBody(def);
}

/// How body `id` slid along `downhill` (unit) from `start` (m) over
/// `seconds` of frames: the displacement (m), and the acceleration (m/s^2)
/// from the velocity change between t = 0.5 s and the end.
struct Slide {
  double displacement_m, acceleration_m_per_s2;
};

inline Slide measureSlide(World& world, BodyId id, const Vec3& start, const Vec3& downhill,
                          double seconds) {
  double v1 = 0.0;
  const int frames = static_cast<int>(std::lround(seconds / kFrame));
  const int f1 = static_cast<int>(std::lround(0.5 / kFrame));
  for (int i = 1; i <= frames; ++i) {
    world.step(kFrame);
    if (i == f1) v1 = world.body(id).v.dot(downhill);
  }
  const double v2 = world.body(id).v.dot(downhill);
  return {(world.body(id).x - start).dot(downhill), (v2 - v1) / (seconds - 0.5)};
}

}  // namespace reeve::test
