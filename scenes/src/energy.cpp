// The energy ledger and its watch (reeve/scene/energy.h; DESIGN.md,
// "Energy ledger").
#include "reeve/scene/energy.h"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "reeve/engine/collide.h"

namespace reeve {

EnergyLedger energyLedger(const Scene& scene) {
  const WorldEnergy world = scene.world->energy();
  EnergyLedger e;
  e.kinetic_J = world.kinetic;
  e.potential_J = world.gravity;
  e.elastic_J = world.elastic + scene.cables->storedElasticEnergy();
  e.drive_work_J = world.drive_work;
  e.load_work_J = world.load_work;
  e.winch_work_J = scene.cables->winchWork();
  e.kinematic_work_J = world.kinematic_work;
  e.damping_J = world.damping_loss;
  e.contact_J = world.contact_loss;
  e.friction_J = scene.cables->frictionLoss();
  e.cable_damping_J = world.cable_damping_loss;
  return e;
}

EnergyWatch::EnergyWatch(const Scene& scene) : last_(energyLedger(scene)) {
  const World& world = *scene.world;
  // The scene's size: the box around every body and its shape.
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  double moving_mass = 0.0;
  for (BodyId b = 0; b < world.bodyCount(); ++b) {
    const double r = boundingRadius(world.bodyDef(b).shape);
    low = low.cwiseMin(world.body(b).x - Vec3::Constant(r));
    high = high.cwiseMax(world.body(b).x + Vec3::Constant(r));
    moving_mass += world.bodyMass(b);
  }
  const double size = world.bodyCount() > 0 ? (high - low).norm() : 0.0;
  potential_scale_J_ = moving_mass * world.settings().gravity.norm() * size;
  peak_kinetic_elastic_ = last_.kinetic_J + last_.elastic_J;
  start_balance_ = lowest_balance_ = last_.balance_J();
}

double energyTolerance(double h) { return kEnergyTolerance * std::max(1.0, h / kEnergyToleranceSubstep_s); }

std::optional<EnergyCreated> EnergyWatch::check(const Scene& scene) {
  const EnergyLedger now = energyLedger(scene);
  const double before = last_.balance_J(), after = now.balance_J();
  last_ = now;
  peak_kinetic_elastic_ = std::max(peak_kinetic_elastic_, now.kinetic_J + now.elastic_J);
  const double scale = peak_kinetic_elastic_ + std::abs(now.work_J()) + now.dissipated_J() + potential_scale_J_;
  scale_J_ = scale;
  const SolverSettings& settings = scene.world->settings();
  const double allowed = energyTolerance(1.0 / (scene.frame_rate_hz * settings.substeps)) * scale;
  std::optional<EnergyCreated> created;
  if (after - before > allowed)
    created = EnergyCreated{scene.world->time(), after - before, scale, true};
  else if (after - lowest_balance_ > allowed)
    created = EnergyCreated{scene.world->time(), after - lowest_balance_, scale, false};
  lowest_balance_ = created ? after : std::min(lowest_balance_, after);
  return created;
}

std::string energyCreatedMessage(const EnergyCreated& created) {
  char text[256];
  std::snprintf(text, sizeof text, "energy created at t = %.6g s: +%.4g J %s (%.2g of the scene's energy scale, %.4g J)",
                created.time_s, created.created_J, created.over_frame ? "in one frame" : "since its lowest point",
                created.created_J / created.scale_J, created.scale_J);
  return text;
}

}  // namespace reeve
