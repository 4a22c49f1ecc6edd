#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "common.h"

namespace reeve::machines {

BeltRing beltRing(const BeltRingSpec& spec) {
  if (spec.wheels < 2) throw std::invalid_argument("beltRing: needs at least 2 wheels");
  BeltRing m;
  m.spec = spec;
  m.scene = detail::emptyScene("belt ring (generated)", 0.0, spec.budget);
  m.scene.description = "A belt round K hinged wheels of very different masses, driven by a motor (reeve/machines/machines.h).";
  World& world = *m.scene.world;
  const int K = spec.wheels;
  const double pi = std::numbers::pi;
  // Wheels 3 radii apart round the circle, so the belt spans are straight.
  const double ring = std::max(3.0 * spec.radius_m * K / (2.0 * pi), 2.0 * spec.radius_m);
  CableDef belt;
  belt.name = "belt";
  belt.closed = true;
  for (int k = 0; k < K; ++k) {
    const double angle = 2.0 * pi * k / K;
    const Vec3 at(ring * std::cos(angle), ring * std::sin(angle), 0.0);
    const double mass = std::pow(10.0, spec.spread * ((7 * k) % 5 - 2) / 2.0);
    const BodyId w = detail::addWheel(world, "wheel" + std::to_string(k), spec.radius_m, mass, at);
    m.wheels.push_back(w);
    HingeDef hinge{w, kWorldBody, at, Vec3::UnitZ()};
    if (k == 0) hinge.drive = {HingeDrive::Mode::Velocity, spec.motor_speed_rad_per_s, spec.motor_torque_Nm};
    const HingeId id = world.addHinge(hinge);
    if (k == 0) m.motor = id;
    belt.links.push_back(LinkDef::rolling(w, 1));  // round the outside, counter-clockwise
  }
  m.cable = m.scene.cables->addCable(belt);
  return m;
}

}  // namespace reeve::machines
