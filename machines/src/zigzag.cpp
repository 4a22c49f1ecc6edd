#include <stdexcept>
#include <string>

#include "common.h"

namespace reeve::machines {

ZigZag zigzag(const ZigZagSpec& spec) {
  if (spec.wheels < 2) throw std::invalid_argument("zigzag: needs at least 2 wheels");
  ZigZag m;
  m.spec = spec;
  m.scene = detail::emptyScene("zigzag (generated)", spec.gravity, spec.budget);
  m.scene.description = "One cable zig-zagging over K hinged wheels between two boxes (reeve/machines/machines.h).";
  World& world = *m.scene.world;
  const int K = spec.wheels;
  const double r = spec.radius_m, box = 0.05;
  CableDef cable;
  cable.name = "rope";
  m.light = detail::addBox(world, "light", Vec3::Constant(box), spec.light_kg, Vec3(-r, -spec.drop_m, 0.0));
  cable.links.push_back(LinkDef::attachment(m.light, Vec3(0.0, box, 0.0)));
  for (int k = 0; k < K; ++k) {
    const bool top = k % 2 == 0 || k == K - 1;
    const Vec3 at(k * spec.pitch_m, top ? 0.0 : -spec.rows_apart_m, 0.0);
    const BodyId w = detail::addWheel(world, "wheel" + std::to_string(k), r, spec.wheel_kg, at);
    m.wheels.push_back(w);
    m.axles.push_back(world.addHinge({w, kWorldBody, at, Vec3::UnitZ()}));
    cable.links.push_back(LinkDef::rolling(w, top ? -1 : 1));  // over top wheels, under bottom ones
  }
  m.heavy = detail::addBox(world, "heavy", Vec3::Constant(box), spec.heavy_kg,
                           Vec3((K - 1) * spec.pitch_m + r, -spec.drop_m, 0.0));
  cable.links.push_back(LinkDef::attachment(m.heavy, Vec3(0.0, box, 0.0)));
  m.cable = m.scene.cables->addCable(cable);
  return m;
}

}  // namespace reeve::machines
