#include "common.h"

namespace reeve::machines {

Atwood atwood(const AtwoodSpec& spec) {
  Atwood m;
  m.spec = spec;
  m.scene = detail::emptyScene("atwood (generated)", spec.gravity, spec.budget);
  m.scene.description = "Two boxes on a cable over one hinged wheel (reeve/machines/machines.h).";
  World& world = *m.scene.world;
  const double r = spec.radius_m, box = 0.1;
  if (spec.arm_kg > 0.0) {
    // A bar from the pivot (0, 1, 0) down to the wheel's axle at the origin.
    m.arm = detail::addBox(world, "arm", Vec3(0.02, 0.5, 0.02), spec.arm_kg, Vec3(0.0, 0.5, 0.0));
    world.addHinge({m.arm, kWorldBody, Vec3(0.0, 1.0, 0.0), Vec3::UnitZ()});
  }
  m.wheel = detail::addWheel(world, "wheel", r, spec.wheel_kg, Vec3::Zero());
  m.axle = world.addHinge({m.wheel, m.arm, Vec3::Zero(), Vec3::UnitZ()});
  m.light = detail::addBox(world, "light", Vec3::Constant(box), spec.light_kg, Vec3(-r, -spec.drop_m, 0.0));
  BodyDef heavy;
  heavy.name = "heavy";
  heavy.shape = Shape::box(Vec3::Constant(box));
  heavy.mass = spec.heavy_kg;
  heavy.position = Vec3(r, -spec.drop_m, 0.0);
  heavy.linear_velocity = Vec3(0.0, -spec.heavy_speed_m_per_s, 0.0);
  m.heavy = world.addBody(heavy);

  CableDef cable;
  cable.name = "rope";
  cable.links = {LinkDef::attachment(m.light, Vec3(0.0, box, 0.0)),
                 LinkDef::rolling(m.wheel, -1),  // over the top: clockwise
                 LinkDef::attachment(m.heavy, Vec3(0.0, box, 0.0))};
  cable.compliance = spec.compliance_m_per_N;
  const double hanging = spec.drop_m - box;  // each taut side
  if (spec.slack_m > 0.0) cable.rest_lengths = {hanging, hanging + spec.slack_m};
  m.cable = m.scene.cables->addCable(cable);
  return m;
}

}  // namespace reeve::machines
