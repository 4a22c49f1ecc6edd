#include "common.h"

namespace reeve::machines::detail {

Scene emptyScene(const std::string& name, double g, const Budget& budget) {
  Scene scene;
  scene.name = name;
  SolverSettings settings;
  settings.gravity = Vec3(0.0, -g, 0.0);
  settings.substeps = budget.substeps;
  settings.iterations = budget.iterations;
  settings.solver = budget.solver;
  scene.world = std::make_unique<World>(settings);
  scene.cables = std::make_unique<CableSystem>(*scene.world);
  return scene;
}

BodyId addWheel(World& world, const std::string& name, double r, double mass, const Vec3& at,
                const Vec3& axis) {
  BodyDef def;
  def.name = name;
  def.shape = Shape::cylinder(r, 0.05);
  def.mass = mass;
  def.position = at;
  def.orientation = rotationBetween(Vec3::UnitZ(), axis.normalized());
  return world.addBody(def);
}

BodyId addBox(World& world, const std::string& name, const Vec3& half, double mass, const Vec3& at) {
  BodyDef def;
  def.name = name;
  def.shape = Shape::box(half);
  def.mass = mass;
  def.position = at;
  return world.addBody(def);
}

}  // namespace reeve::machines::detail
