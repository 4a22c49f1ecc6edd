// The World's side of the energy ledger (issue 28; DESIGN.md, "Energy
// ledger"): the energy of the bodies and of the compliant rows now, and
// the work and losses the engine can measure, summed over every substep.
// The cable system adds its own (winches, friction: CableEnergy), and the
// scene layer balances them (reeve/scene/energy.h).
#pragma once

namespace reeve {

/// All in joules. The first three are of the state now; the rest are sums
/// over every substep since the World was made.
///
/// Signs: work is what an actuator put into the bodies (negative when it
/// took energy out, a motor braking); a loss is what a mechanism took out
/// (>= 0 for every physical one: a negative loss is energy that mechanism
/// created, and the ledger reports it as such, never as a credit).
struct WorldEnergy {
  /// sum m |v|^2 / 2 + w . I w / 2 over dynamic bodies (a rotor: its spin
  /// about its axle; its centre does not move).
  double kinetic = 0.0;
  /// -sum m g . x: gravitational potential, 0 at the world origin. Under
  /// the direct solver's start projection at x - v h / 2 (h the last
  /// substep), the height that pairs with the half step's velocity v in
  /// its symplectic step (a free fall's energy is then exact).
  double gravity = 0.0;
  /// Energy held by compliant rows: C^2 / (2 alpha) of every distance
  /// constraint and path of compliance alpha (m/N) stretched by C (m) past
  /// its rest length now; alpha F^2 / 2 of compliant joints' point and axis
  /// rows with the last substep's force F; stiffness e^2 / 2 of every
  /// spring drive (e = angle or slide minus its target).
  double elastic = 0.0;
  /// Work of the motor drives (velocity drives, rigid angle and position
  /// drives): per substep, their torque (force) times the turn (slide) of
  /// body a relative to b over it. Spring drives count as elastic instead.
  /// Under the direct solver's start projection every work below is booked
  /// with the velocity at the substep's start, the mean of the one before
  /// and after it (World::ledgerLag).
  double drive_work = 0.0;
  /// Work of the applied forces and torques (BodyState::applied_force,
  /// applied_torque): per substep F . dx + tau . w h.
  double load_work = 0.0;
  /// Work of the kinematic bodies (BodyDef::motion) on the rest: per
  /// substep, minus the impulse the constraints and contacts gave each,
  /// dotted with its velocity, over h (a drum swept round paying out
  /// against a load puts in T r omega h).
  double kinematic_work = 0.0;
  /// Kinetic energy taken out by body damping (exactly: before and after
  /// each substep's decay), >= 0.
  double damping_loss = 0.0;
  /// Kinetic energy taken out by the contacts' velocity pass (dynamic
  /// friction, restitution), exactly: before and after it.
  double contact_loss = 0.0;
  /// Energy taken out by the damping of distance constraints and paths
  /// (cables, DistanceConstraint::damping): per substep, the tension beyond
  /// the spring's, T - C / alpha, times the length's change over it, where
  /// positive; beta (dL/dt)^2 h once the row is met.
  double cable_damping_loss = 0.0;
};

}  // namespace reeve
