// The energy ledger of a scene (issue 28; DESIGN.md, "Energy ledger"): the
// energy of the machine, the work put in and the losses taken out, and a
// watch that says when a frame created energy that nothing put in.
#pragma once

#include <optional>
#include <string>

#include "reeve/scene/scene.h"

namespace reeve {

/// All in joules. kinetic, potential and elastic are of the state now; the
/// rest are sums over every substep since the scene was loaded.
struct EnergyLedger {
  double kinetic_J = 0.0;    ///< bodies' translation and rotation (WorldEnergy::kinetic)
  double potential_J = 0.0;  ///< gravity, -sum m g . x (0 at the world origin)
  double elastic_J = 0.0;    ///< compliant cables (spans and the stretch wound on wheels), joints and springs
  double drive_work_J = 0.0;  ///< motor drives on hinges and prismatic joints
  double load_work_J = 0.0;   ///< applied forces and torques
  double winch_work_J = 0.0;  ///< winches reeling in (negative paying out under load)
  double kinematic_work_J = 0.0;  ///< kinematic bodies (a motion) pushing and pulling on the rest
  double damping_J = 0.0;     ///< taken out by body damping
  double contact_J = 0.0;     ///< taken out by the contacts' velocity pass
  double friction_J = 0.0;    ///< taken out by cable friction (CableSystem::frictionLoss)
  double cable_damping_J = 0.0;  ///< taken out by cable damping (WorldEnergy::cable_damping_loss)

  /// kinetic + potential + elastic.
  double total_J() const { return kinetic_J + potential_J + elastic_J; }
  /// Everything the actuators put in: drives, loads, winches, kinematic bodies.
  double work_J() const { return drive_work_J + load_work_J + winch_work_J + kinematic_work_J; }
  /// Everything measured as taken out: damping, contacts, cable friction
  /// and cable damping.
  double dissipated_J() const { return damping_J + contact_J + friction_J + cable_damping_J; }
  /// total - work + dissipated: constant for an exact integrator; it falls
  /// by the losses nothing measures (the integrator's own O(h) damping,
  /// contact friction in the position solve, a speed guard, a break) and rises
  /// only where energy was created.
  double balance_J() const { return total_J() - work_J() + dissipated_J(); }
};

/// The ledger of `scene` now.
EnergyLedger energyLedger(const Scene& scene);

/// Energy created beyond what rounding and the budget's own error allow.
struct EnergyCreated {
  double time_s = 0.0;    ///< end of the frame that showed it
  double created_J = 0.0; ///< the balance's rise (J): over that frame, or since its lowest point
  double scale_J = 0.0;   ///< the energy scale the tolerance is a fraction of (J)
  bool over_frame = true; ///< true: within one frame; false: since the balance's lowest point
};

/// Watches a scene's ledger frame by frame (issue 28). The balance
/// (EnergyLedger::balance_J) may fall, never rise: a rise of more than
/// energyTolerance(h) x the scene's energy scale, within one frame or
/// since its lowest point so far, is energy created. The scale is the
/// largest kinetic plus elastic energy seen, plus the work put in or taken
/// out so far, plus the weight of the moving bodies times the scene's size
/// (the potential energy they could trade).
class EnergyWatch {
 public:
  /// Starts from the scene's state now.
  explicit EnergyWatch(const Scene& scene);
  /// After a frame: the creation it showed, if any (each frame at most one
  /// finding; the lowest point is then reset, so one event is told once).
  std::optional<EnergyCreated> check(const Scene& scene);
  /// The ledger of the last check (or of the start).
  const EnergyLedger& ledger() const { return last_; }
  /// The energy scale (J) of the last check, of which the tolerance is a
  /// fraction.
  double scale_J() const { return scale_J_; }
  /// balance now minus at the start (J): the energy neither put in nor
  /// measured as taken out; <= 0 unless energy was created.
  double residual_J() const { return last_.balance_J() - start_balance_; }

 private:
  double potential_scale_J_ = 0.0;  // moving weight x scene size
  double peak_kinetic_elastic_ = 0.0;
  double start_balance_ = 0.0;
  double lowest_balance_ = 0.0;
  double scale_J_ = 0.0;
  EnergyLedger last_;
};

/// Fraction of the energy scale the balance may rise at substeps of
/// kEnergyToleranceSubstep_s and below (rounding, and the ripple of
/// positions, velocities and elastic energy within a substep)...
inline constexpr double kEnergyTolerance = 1e-3;
inline constexpr double kEnergyToleranceSubstep_s = 1.0 / 600.0;
/// ... and at a longer substep h (s) in proportion to h: the budget's own
/// O(h) error (DESIGN.md, "Energy ledger", measured on the shipped scenes).
double energyTolerance(double h);

/// "energy created at t = T s: +X J in one frame (the scale is S J)", as
/// `reeve run` warns.
std::string energyCreatedMessage(const EnergyCreated& created);

}  // namespace reeve
