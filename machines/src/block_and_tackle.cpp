#include "common.h"

namespace reeve::machines {

BlockAndTackle blockAndTackle(const BlockAndTackleSpec& spec) {
  BlockAndTackle m;
  m.spec = spec;
  m.scene = detail::emptyScene("block and tackle (generated)", spec.gravity, spec.budget);
  m.scene.description = "A block and tackle with four strands; the lower sheaves turn on the moving block (reeve/machines/machines.h).";
  World& world = *m.scene.world;
  const double r = spec.radius_m, D = spec.drop_m;
  // Vertical strands: lower A at x = 0, upper A at 2r, lower B at 4r, upper
  // B at 6r; the tie above lower A's left side, the counterweight under
  // upper B's right side.
  BodyDef upper;
  upper.name = "upper_block";
  upper.is_static = true;
  upper.shape = Shape::box(Vec3(5.0 * r, 0.1, 0.1));
  upper.position = Vec3(3.0 * r, 0.25, 0.0);
  m.upper_block = world.addBody(upper);
  // The lower block's centre of mass hangs below its axles, so it does not
  // tip over.
  m.lower_block = detail::addBox(world, "lower_block", Vec3(4.0 * r, 0.1, 0.05), spec.block_kg,
                                 Vec3(2.0 * r, -D - 0.3, 0.0));
  const char* names[2] = {"A", "B"};
  for (int i = 0; i < 2; ++i) {
    const Vec3 up(2.0 * r + 4.0 * r * i, 0.0, 0.0), low(4.0 * r * i, -D, 0.0);
    m.upper[i] = detail::addWheel(world, std::string("upper_") + names[i], r, spec.sheave_kg, up);
    world.addHinge({m.upper[i], m.upper_block, up, Vec3::UnitZ()});
    m.lower[i] = detail::addWheel(world, std::string("lower_") + names[i], r, spec.sheave_kg, low);
    m.lower_axles[i] = world.addHinge({m.lower[i], m.lower_block, low, Vec3::UnitZ()});
  }
  const double box = 0.1;
  m.counterweight = detail::addBox(world, "counterweight", Vec3::Constant(box), spec.counterweight_kg,
                                   Vec3(7.0 * r, -1.0 - box, 0.0));
  CableDef cable;
  cable.name = "rope";
  cable.links = {LinkDef::attachment(m.upper_block, Vec3(-4.0 * r, -0.25, 0.0)),
                 LinkDef::rolling(m.lower[0], 1),   // under: counter-clockwise
                 LinkDef::rolling(m.upper[0], -1),  // over: clockwise
                 LinkDef::rolling(m.lower[1], 1),
                 LinkDef::rolling(m.upper[1], -1),
                 LinkDef::attachment(m.counterweight, Vec3(0.0, box, 0.0))};
  m.cable = m.scene.cables->addCable(cable);
  return m;
}

}  // namespace reeve::machines
