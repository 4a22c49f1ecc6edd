// What the machine generators share: a Scene with an empty World and its
// CableSystem, and the bodies every machine is made of.
#pragma once

#include <memory>
#include <string>

#include "reeve/machines/machines.h"

namespace reeve::machines::detail {

/// An empty scene named `name`, gravity `g` m/s^2 along -y, the budget's
/// substeps and iterations, frames at 60 Hz.
inline Scene emptyScene(const std::string& name, double g, const Budget& budget) {
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

/// A dynamic wheel: a solid cylinder of radius `r` (m), 0.1 m thick along
/// local z, of `mass` (kg), turned so that local z is `axis`.
inline BodyId addWheel(World& world, const std::string& name, double r, double mass, const Vec3& at,
                       const Vec3& axis = Vec3::UnitZ()) {
  BodyDef def;
  def.name = name;
  def.shape = Shape::cylinder(r, 0.05);
  def.mass = mass;
  def.position = at;
  def.orientation = Quat::FromTwoVectors(Vec3::UnitZ(), axis.normalized());
  return world.addBody(def);
}

/// A dynamic box with half extents `half` (m) and `mass` (kg).
inline BodyId addBox(World& world, const std::string& name, const Vec3& half, double mass, const Vec3& at) {
  BodyDef def;
  def.name = name;
  def.shape = Shape::box(half);
  def.mass = mass;
  def.position = at;
  return world.addBody(def);
}

}  // namespace reeve::machines::detail
