// Rigid bodies: a definition (what the user asks for) and the hot state the
// solver touches every substep.
#pragma once

#include <cstdint>

#include <string>
#include <vector>

#include "reeve/engine/contact_material.h"
#include "reeve/engine/keyframes.h"
#include "reeve/engine/math.h"
#include "reeve/engine/shape.h"

namespace reeve {

/// Index of a body in its World; kWorldBody stands for the fixed world frame.
using BodyId = int;
inline constexpr BodyId kWorldBody = -1;

/// One point of a kinematic body's motion: from `time` (s, simulated) its
/// centre moves at `velocity` (m/s, world) and it turns at
/// `angular_velocity` (rad/s, world), both linear in time up to the next
/// keyframe and held after the last.
struct MotionKeyframe {
  double time = 0.0;
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
};

/// What a user asks for. Exactly one of `density` (kg/m^3) or `mass` (kg)
/// is used: `mass` when positive, else density x volume. Static bodies
/// ignore both and never move; kinematic ones (a `motion`) ignore both and
/// move as told. `inertia`, when non-zero, replaces the shape's moments:
/// the principal moments (kg m^2) about the body's axes through its origin,
/// which is then its centre of mass whatever the shape (an imported model's
/// mass properties); it needs `mass`. They need not be a rigid body's (each
/// at most the sum of the other two): a MuJoCo joint's armature adds to
/// one of them.
struct BodyDef {
  std::string name;
  Shape shape;
  double density = 1000.0;
  double mass = 0.0;
  Vec3 inertia = Vec3::Zero();
  bool is_static = false;
  Vec3 position = Vec3::Zero();                // m, world
  Quat orientation = Quat::Identity();         // local -> world
  Vec3 linear_velocity = Vec3::Zero();         // m/s, world
  Vec3 angular_velocity = Vec3::Zero();        // rad/s, world
  /// Velocity decay rates (1/s): v *= exp(-rate h) each substep, e.g. air
  /// drag or bearing friction that lets a mechanism come to rest.
  double linear_damping = 0.0;
  double angular_damping = 0.0;
  /// Friction and restitution of the body's surface against the ground and
  /// other bodies (combined per pair, contact_material.h).
  ContactMaterial material;
  /// Takes part in body-body contacts (with every other colliding body).
  /// Contact with the ground plane does not need it: a World's ground
  /// touches every dynamic body.
  bool collides = false;
  /// Which colliding bodies it touches (MuJoCo's contype and conaffinity):
  /// bodies a and b touch where (a.contact_type & b.contact_affinity) |
  /// (b.contact_type & a.contact_affinity) is not 0; every pair by default.
  /// Pairs that never touch whatever their bits: World::excludeContact.
  std::uint32_t contact_type = 1, contact_affinity = 1;
  /// Non-empty: a kinematic body, moved along this schedule (times strictly
  /// increasing, values finite) whatever pushes on it: infinite mass to the
  /// solver, its velocity seen by cables, joints and contacts, the work it
  /// does counted by the energy ledger (World::step). Not with is_static.
  std::vector<MotionKeyframe> motion = {};
};

/// Solver state of one body (Müller et al. 2020, Alg. 2). Static bodies
/// have zero inverse mass and inertia, so corrections leave them in place
/// without a branch in the kernels. A rotor (the model of a wheel on a
/// fixed axle, SolverKind) has zero inverse mass and the
/// inverse inertia u u^T / I_u of its axle u alone: every kernel then turns
/// it about the axle and never moves its centre, again without a branch.
struct BodyState {
  Vec3 x = Vec3::Zero();          // position, m
  Quat q = Quat::Identity();      // orientation, local -> world
  Vec3 v = Vec3::Zero();          // m/s
  Vec3 omega = Vec3::Zero();      // rad/s, world
  Vec3 x_prev = Vec3::Zero();
  Quat q_prev = Quat::Identity();
  // Orientation right after this substep's integration, before the solve:
  // the velocity read-out adds the solve's small correction to the
  // integrated turn h omega, which may be many turns (a fast wheel).
  Quat q_pred = Quat::Identity();
  double inv_mass = 0.0;          // 1/kg
  // Inertia tensor about the centre of mass in body-local axes, kg m^2, and
  // its inverse; diagonal except for hulls, whose axes are the user's.
  Mat3 inv_inertia = Mat3::Zero();
  Mat3 inertia = Mat3::Zero();
  double linear_damping = 0.0;      // 1/s
  double angular_damping = 0.0;     // 1/s
  // A force (N, through the centre of mass) and a torque (N m) applied
  // every substep until changed, world: a user's or controller's push. A
  // rotor takes the torque about its axle only; static bodies ignore both.
  Vec3 applied_force = Vec3::Zero();
  Vec3 applied_torque = Vec3::Zero();
  // Body-local unit axle of a rotor; zero for every other body.
  Vec3 rotor_axis = Vec3::Zero();
  // What this substep's solve did to the body, world: the impulse (kg m)
  // and the angular impulse about its centre (kg m^2) the constraints and
  // contacts gave it, in the position solve and the contacts' velocity
  // pass (a velocity impulse p counts as p h; either way / h^2 is a force;
  // a rotor's axle takes them: its hinge's wrench),
  // and the rotation (rad) the solve turned it by, its corrections summed,
  // whole turns and all, with which the velocity read-out, hinge drives and
  // the cable bookkeeping take their angles round.
  Vec3 impulse = Vec3::Zero();
  Vec3 angular_impulse = Vec3::Zero();
  Vec3 solve_turn = Vec3::Zero();
  // Moved by its BodyDef::motion, not by forces: zero inverse mass and
  // inertia, as a static body, but v and omega are its motion's.
  bool kinematic = false;

  /// World point of the body-local point `local`.
  Vec3 toWorld(const Vec3& local) const { return x + q * local; }
  /// World point of `local` at this substep's start (x_prev, q_prev); a
  /// body that does not move is where it is.
  Vec3 toWorldAtSubstepStart(const Vec3& local) const {
    return moves() ? Vec3(x_prev + q_prev * local) : toWorld(local);
  }
  /// Body-local point of the world point `world`.
  Vec3 toLocal(const Vec3& world) const { return q.conjugate() * (world - x); }
  /// I^-1 v for a world-space vector v, with the current orientation.
  Vec3 applyInvInertia(const Vec3& v) const {
    return q * (inv_inertia * (q.conjugate() * v));
  }
  /// 1 / inv_mass: 0 for static bodies and rotors (World::bodyMass has a
  /// rotor's real mass).
  double mass() const { return inv_mass > 0.0 ? 1.0 / inv_mass : 0.0; }
  bool isRotor() const { return rotor_axis.squaredNorm() > 0.0; }
  /// False for static and kinematic bodies: whether constraints move it.
  bool moves() const { return inv_mass > 0.0 || isRotor(); }
  /// Whether a solve writes what it did to the body (impulse, turn): not
  /// to a static body, whose motion is nothing, and which islands solved
  /// side by side share (World::setThreads).
  bool takesImpulses() const { return kinematic || moves(); }
};

/// A kinematic body's velocities at time `t` (s) under `motion` (non-empty,
/// times increasing): linear between keyframes, the first's before it and
/// the last's after it. The returned keyframe's time is `t`.
MotionKeyframe motionAt(const std::vector<MotionKeyframe>& motion, double t);

/// Bounds on a dynamic body's mass (kg) and principal moments of inertia
/// (kg m^2): products of three of them (the inertia's determinant, which
/// its inverse and the gyroscopic step divide by) stay finite and normal
/// in double precision. A 1e300 kg body once gave NaN orientations within
/// a step; a 1e154 kg one an inverse inertia of 0 (its determinant
/// overflowed).
inline constexpr double kMinMass = 1e-100, kMaxMass = 1e100;
inline bool isRepresentableMass(double m) { return m >= kMinMass && m <= kMaxMass; }

/// Builds the solver state of `def`: mass from density unless given,
/// inertia of the solid shape. Throws std::invalid_argument when a dynamic
/// body's mass or a principal moment of inertia is outside [kMinMass,
/// kMaxMass] (or NaN), or its material is not valid (isValid in
/// contact_material.h).
BodyState makeBodyState(const BodyDef& def);

}  // namespace reeve
