// The XPBD world: bodies, joints, distance constraints and the substepped
// step of Müller et al. 2020, Alg. 2.
#pragma once

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "reeve/engine/body.h"
#include "reeve/engine/collide.h"
#include "reeve/engine/contact.h"
#include "reeve/engine/distance_constraint.h"
#include "reeve/engine/energy.h"
#include "reeve/engine/fixed_joint.h"
#include "reeve/engine/hinge_joint.h"
#include "reeve/engine/path_constraint.h"
#include "reeve/engine/prismatic_joint.h"
#include "reeve/engine/spherical_joint.h"
#include "reeve/engine/thread_pool.h"

namespace reeve {

/// How each iteration solves the joints and cables (contacts are always
/// Gauss-Seidel).
/// Under both, every wheel whose only joint is a rigid hinge to a static
/// body (or the world) through its centre of mass is a rotor: it turns
/// about its axle and nothing moves its centre (body.h), so its hinge has
/// no point or axis rows to solve.
/// - GaussSeidel: one row (a joint's block, a cable span) after another,
///   as the paper does (SCA 2018 sec. 3, SCA 2020). Converges only while
///   every wheel is about as heavy as the loads it carries, and needs about
///   one sweep per wheel for a load to travel along a cable.
/// - Direct: every joint row and cable span together, in one sparse linear
///   solve per iteration (direct_solver.h). Right at any mass ratio,
///   tension and cable length.
enum class SolverKind { GaussSeidel, Direct };

/// Where the direct solver takes each row's gradient, the direction it
/// moves the bodies along (issue 29, numerical damping; DESIGN.md):
/// - End: at the poses it is solving (XPBD as written, SCA 2020): the end
///   of the substep once converged. First order and dissipative: a 1 m
///   pendulum keeps 4 % of its swing energy after 100 periods at 10 x 2.
/// - Start: at the substep's start poses (SHAKE, Ryckaert et al. 1977),
///   with C still at the poses solved: symplectic, the same pendulum keeps
///   its swing energy to 1e-6. A row whose gradient turned by more than
///   0.2 (relative, in the W norm) over the substep keeps the End one: a
///   spool spinning a radian a substep, a snap; so does every row of an
///   island with contacts, which are swept between the iterations along
///   their normals at the poses solved (rows along start gradients fought
///   them, worse with more iterations). The energy ledger then
///   reads gravity half a substep back (energy.h). Not yet the default:
///   the ledger's closed-form tests, events and the stiff machines' few
///   iterations were built on the end (DESIGN.md).
enum class Projection { End, Start };

/// Solver knobs. A frame of length dt is split into `substeps` substeps of
/// h = dt / substeps, each with `iterations` solver iterations (sweeps or
/// solves, per `solver`) over all constraints. More substeps: smaller h,
/// stiffer and more accurate; more iterations: better convergence within
/// one substep.
struct SolverSettings {
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);  // m/s^2
  int substeps = 10;
  int iterations = 2;
  SolverKind solver = SolverKind::Direct;
  /// The direct solver's; Gauss-Seidel always projects at the End.
  Projection projection = Projection::End;
  /// The direct solver stops iterating within a substep once every row is
  /// met to this (m for positions, rad for angles) times min(1, (h / (1/600
  /// s))^2): the iterations left would change tensions by about tolerance x
  /// mass / h^2, 4e-7 N for 1 kg at h = 1/60 s and 4e-5 N at h = 1/600 s
  /// or any shorter substep. 0: always run every iteration (to time one).
  double tolerance = 1e-10;
  /// Speed guards: after each substep a body's linear speed (m/s) and
  /// angular speed (rad/s) are clamped to these, so a bad set-up cannot
  /// fling bodies out to infinity. Infinite by default (no effect).
  double max_linear_speed = std::numeric_limits<double>::infinity();
  double max_angular_speed = std::numeric_limits<double>::infinity();
};

/// Id of a constraint in the World's per-type arrays.
using HingeId = int;
using PrismaticId = int;
using SphericalId = int;
using FixedId = int;
using DistanceId = int;
using PathId = int;

struct Island;

/// The first non-finite value a World produced (World::firstNonFinite).
struct NonFiniteState {
  enum class Quantity { Position, Orientation, Velocity, AngularVelocity, Tension };
  BodyId body = 0;  ///< the body; for Tension, body a of the distance constraint
  BodyId other = kWorldBody;  ///< for Tension, body b of the constraint
  Quantity quantity = Quantity::Position;
  double time_s = 0.0;  ///< simulated time at the end of that substep, s
};
/// "position", "orientation", "velocity", "angular velocity", "tension".
const char* quantityName(NonFiniteState::Quantity quantity);
/// A non-finite value as a step finds it, island by island: the first is
/// the least (substep, then pass: 0 after integration, 1 after the solve,
/// then item: a body's id, or the body count plus a distance constraint's
/// index), as one scan of the whole World after each pass would find it.
struct NonFiniteFind {
  int substep = 0, pass = 0;
  long long item = 0;
  NonFiniteState state;
  bool operator<(const NonFiniteFind& o) const {
    return substep != o.substep ? substep < o.substep : pass != o.pass ? pass < o.pass : item < o.item;
  }
};


class World {
 public:
  /// Called once per substep after integration and before the position
  /// solve, with the substep h (s). The seam through which cable/ moves the
  /// anchors and rest lengths of its distance constraints (DESIGN.md).
  using SubstepHook = std::function<void(World&, double h)>;
  /// Which substep of a step an island is in: its index (0 first) and
  /// the simulated time (s) at its start. Islands that run whole steps
  /// (IslandHook::whole_steps) are at different substeps at one moment,
  /// so their hooks read the time here, not from World::time().
  struct SubstepClock {
    int substep = 0;
    double time_s = 0.0;
  };
  /// A substep hook whose work splits by island (cable/: each cable's
  /// update), at the same point of the substep. `before` runs on the
  /// caller's thread; then `island(w, h, i, clock)` once with i = -1
  /// (what is on no island: cables between static anchors) on the
  /// caller's thread, and once for each island i (0 <= i < islandCount()),
  /// side by side on the World's threads, right after that island's
  /// integration: it may touch only island i's bodies and constraints and
  /// its own records for island i, read static bodies, and must compute
  /// the same whichever thread runs it; it returns true when it left news
  /// for `after` (an event, a joint to add, a broken invariant). Then
  /// `after` on the caller's thread. Any part may be empty.
  ///
  /// With `whole_steps`, the hook lets each island run all the substeps
  /// of a step on its own, without the others (World::step: one join a
  /// step instead of two a substep). It then promises: `before` may run
  /// again before any substep of the same step and changes nothing the
  /// second time; the island part reads the time from `clock` alone and
  /// joins no island to another (coupleBodies); `after` handles only the
  /// news of updates that ended by its substep's end (World::time() + h),
  /// leaving later ones for a later `after`.
  struct IslandHook {
    SubstepHook before;
    std::function<bool(World&, double h, int island, const SubstepClock& clock)> island;
    SubstepHook after;
    bool whole_steps = false;
  };
  /// Called after each substep's position solve, with h (s). Returns true
  /// when it changed the constraints of this substep because the solve
  /// broke an assumption they were built on (cable/: a sticking friction
  /// link whose capstan bound the solve's tensions passed, a slipping one
  /// the solve slid against its friction); the substep is then solved
  /// again from the poses before the solve, at most kMaxResolves times.
  using ResolveCheck = std::function<bool(World&, double h)>;
  static constexpr int kMaxResolves = 2;

  explicit World(SolverSettings settings = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  /// Adds a body; throws std::invalid_argument for a dynamic body without
  /// a finite positive mass.
  BodyId addBody(const BodyDef& def);
  /// Adds a hinge from the current poses; throws std::invalid_argument for
  /// unknown or identical bodies, a zero axis, a negative compliance, a
  /// limit with lower > upper or outside [-pi, pi], a negative drive
  /// stiffness or damping, either on a velocity drive, damping without
  /// stiffness, a drive schedule whose times do not increase strictly, or
  /// anything not finite (but an infinite max torque). An angle drive's
  /// target may be any number of turns (HingeDrive).
  HingeId addHinge(const HingeDef& def);
  /// Adds a prismatic joint from the current poses; throws
  /// std::invalid_argument as addHinge (limits in m, any finite range).
  PrismaticId addPrismatic(const PrismaticDef& def);
  /// Adds a spherical joint from the current poses; throws
  /// std::invalid_argument as addHinge, and for a swing limit outside
  /// [0, pi].
  SphericalId addSpherical(const SphericalDef& def);
  /// Adds a fixed joint keeping the current relative pose; throws
  /// std::invalid_argument for unknown or identical bodies, a negative
  /// compliance or anything not finite.
  FixedId addFixed(const FixedDef& def);
  /// Gives dynamic body `id` a new mass (kg), scaling its inertia with it;
  /// throws std::invalid_argument unless the body is dynamic and the mass
  /// and scaled moments lie in [kMinMass, kMaxMass] (body.h).
  void setMass(BodyId id, double mass);
  DistanceId addDistance(const DistanceConstraint& c);
  PathId addPath(PathConstraint path);
  void addSubstepHook(SubstepHook hook);  // runs as an IslandHook's `after`
  void addSubstepHook(IslandHook hook);
  void addResolveCheck(ResolveCheck check);
  /// Declares that a substep hook may join `bodies` by constraints it
  /// makes or moves during a step (cable/: a cable's links, as its spans
  /// move from link to link and a jam adds a ball joint), so that they are
  /// always solved in one island. Throws std::invalid_argument for an
  /// unknown body (kWorldBody allowed).
  void coupleBodies(const std::vector<BodyId>& bodies);
  /// The islands the next step solves one by one (island.h): sets of
  /// moving and kinematic bodies that joints, distance constraints, paths,
  /// coupled bodies and contacts between colliders join, static bodies
  /// joining none. Each island's solve is its own: the direct solver
  /// stops iterating an island once its rows are met. Lowest body first.
  int islandCount();
  /// The bodies of island `i` (0 <= i < islandCount()), increasing.
  const std::vector<BodyId>& islandBodies(int i);
  /// The island of body `id` as islandCount() or the step now running
  /// built them; -1 for a static body, the world, or a body added since.
  int islandOfBody(BodyId id) const {
    return id >= 0 && id < static_cast<BodyId>(island_of_.size()) ? island_of_[id] : -1;
  }
  /// How many times the islands have been built: when it is unchanged, so
  /// is every islandOfBody.
  int islandsBuilt() const { return islands_built_; }

  /// Sets the ground plane {p : n . p = height_m} (n = ground.normal,
  /// normalized here), which touches every dynamic body (SCA 2020, sec.
  /// 3.5). Throws std::invalid_argument for a zero or non-finite normal, a
  /// non-finite height or an invalid material (contact_material.h).
  void setGround(const GroundPlane& ground);
  /// Bodies a and b never touch, whatever their contact bits (two links
  /// of one joint that overlap at it, as MuJoCo filters a parent and its
  /// child). Throws std::invalid_argument for an unknown body or a = b.
  void excludeContact(BodyId a, BodyId b);
  /// Whether colliding bodies a and b may touch (BodyDef::contact_type,
  /// contact_affinity; excludeContact).
  bool contactAllowed(BodyId a, BodyId b) const;
  /// Removes the ground plane.
  void removeGround() { ground_.reset(); }
  const std::optional<GroundPlane>& ground() const { return ground_; }
  /// True when a step looks for contacts: there is a ground plane or at
  /// least two bodies with BodyDef::collides. Otherwise a step does no
  /// collision work at all.
  bool hasContacts() const { return ground_.has_value() || colliders_.size() >= 2; }
  /// The contacts of the last substep (contact.h), fresh each substep.
  /// Normal force of one: contactNormalForce(c, lastSubstep()).
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// The same grouped by touching pair (ranges of contacts()).
  const std::vector<ContactManifold>& contactManifolds() const { return manifolds_; }
  /// Two bodies that overlapped as the scene placed them, by more than
  /// 1e-9 m, pushed apart as poses before the first step (not as speeds:
  /// initial_overlaps.cpp). `a` is kWorldBody for the ground.
  struct PlacedOverlap {
    BodyId a = kWorldBody, b = 0;
    double depth_m = 0.0;  ///< the deepest point's overlap before the push (m)
  };
  /// Those the first step() pushed apart before its first substep,
  /// deepest first; empty before it, or where none.
  const std::vector<PlacedOverlap>& placedOverlaps() const { return placed_overlaps_; }

  /// Advances by dt (s) with the current settings, or less when the
  /// interrupt flag is raised meanwhile (setInterruptFlag).
  void step(double dt);

  /// Lets step() stop early (issue 27): it reads `*flag` (an atomic a
  /// signal handler may write) after each solver iteration and each
  /// substep. Once it is non-zero the substep under way ends after the
  /// iteration in progress (velocities, contacts and checks as after any
  /// substep, so the world can step on), no further substep starts, and
  /// stepInterrupted() is true until the next step(). Where the islands
  /// run whole steps (IslandHook::whole_steps), each island ends its
  /// substep under way, and those behind are then stepped up to the one
  /// furthest on, so that all end at one time. nullptr, the default,
  /// never stops. The flag must outlive its use here.
  void setInterruptFlag(const std::atomic<int>* flag) { interrupt_ = flag; }
  /// Whether the interrupt flag cut the last step() short (an iteration or
  /// a substep left out; a flag raised during its last iteration cuts
  /// nothing); time() is then the end of the last substep it ran.
  bool stepInterrupted() const { return interrupted_; }
  /// Called after each substep of a step() with the substeps done and the
  /// substeps it has (a progress bar inside a long frame); empty: none.
  /// Where the islands run whole steps, `done` is the share of its islands'
  /// substeps the caller's thread has run, in substeps.
  void setSubstepProgress(std::function<void(int done, int substeps)> progress) {
    progress_ = std::move(progress);
  }

  /// Steps the islands (islandCount) on `threads` threads, the caller's
  /// included, while waiting threads spin between a substep's two runs; 1
  /// (the default) steps them one after another. Each thread takes the
  /// same islands every substep, and in each run does every pass on them:
  /// integration, the hooks' island parts and the finite checks, then the
  /// solve, velocities, the contacts' velocity pass and the ledger's
  /// flows (summed by island, in island order). What joins islands runs
  /// between on the caller's thread: the hooks' other parts, contact
  /// detection, the re-solves a ResolveCheck asks for. Where nothing does
  /// (no contacts, no ResolveCheck, no row or driven joint on no island,
  /// no braked drive, every hook IslandHook::whole_steps), each island
  /// runs all the substeps of a step in one run, and the threads join once
  /// a step; an island whose hook has news stops before that substep's
  /// solve, and goes on substep by substep with the World
  /// (runsWholeSteps). The threads start with the first step that has two
  /// islands or more, and share a run
  /// only while its islands' work, timed at each step, is at least
  /// `min_shared_run_us` (us; half that once shared; 0: always): below,
  /// a run's join costs more than the threads save. The results are the
  /// same bits for any number. Throws std::invalid_argument for threads
  /// below 1 or a negative or non-finite minimum.
  void setThreads(int threads, double min_shared_run_us = kMinSharedRunUs);
  static constexpr double kMinSharedRunUs = 20.0;
  int threads() const { return threads_; }
  /// Whether the last step's runs were shared between the threads.
  bool runsShared() const { return pool_ && share_runs_ && islands_.size() > 1; }
  /// Whether a step runs each island's substeps in one run (setThreads):
  /// the same bits as substep by substep. Read from the islands as the
  /// last step or islandCount() built them, and the hooks, checks, ground
  /// and drives as they are now.
  bool runsWholeSteps() const;

  SolverSettings& settings() { return settings_; }
  const SolverSettings& settings() const { return settings_; }

  int bodyCount() const { return static_cast<int>(bodies_.size()); }
  /// State of body `id`; kWorldBody gives the fixed world frame.
  BodyState& body(BodyId id) { return id == kWorldBody ? world_frame_ : bodies_[id]; }
  const BodyState& body(BodyId id) const {
    return id == kWorldBody ? world_frame_ : bodies_[id];
  }
  /// Definition of a real body (not kWorldBody).
  const BodyDef& bodyDef(BodyId id) const {
    assert(id >= 0 && id < bodyCount());
    return defs_[id];
  }
  /// Mass (kg) of body `id`; 0 for a static body and the world. A rotor's
  /// BodyState has zero inverse mass, this its real mass.
  double bodyMass(BodyId id) const { return id == kWorldBody ? 0.0 : mass_[id]; }
  /// The first body whose position, orientation or velocity is not
  /// finite now, if any (lowest index first).
  std::optional<BodyId> firstNonFiniteBody() const;
  /// What became non-finite first since the World was made, if anything:
  /// step() checks every body after integrating and after solving each
  /// substep, and every distance constraint's tension after each substep,
  /// so a non-finite value is caught in the substep it is born, before it
  /// spreads through the constraints. step() never throws: check this
  /// after it to stop a run naming the body and quantity.
  const std::optional<NonFiniteState>& firstNonFinite() const { return non_finite_; }
  /// Body named `name`, if any.
  std::optional<BodyId> findBody(const std::string& name) const;

  // Joints, by type, in the order added. Changing a joint's drive or limit
  // between steps is allowed (a drive's target, max torque); its body-local
  // geometry is what it was made with. Forces and torques are those of the
  // last substep, on the joint's body a (JointWrench); a rotor's hinge
  // (which has no point or axis rows) takes what the rotor's impulses and
  // weight leave for its axle, found when read from the state the last
  // substep left (so a pose or mass set since the step is seen there).
  const std::vector<HingeJoint>& hinges() const { return hinges_; }
  HingeJoint& hinge(HingeId id) { return hinges_.at(id); }
  const HingeJoint& hinge(HingeId id) const { return hinges_.at(id); }
  JointWrench hingeWrench(HingeId id) const;
  /// Hinge angle (rad) of body a relative to b, 0 when added, counted
  /// through whole turns (2 pi after one turn; HingeJoint::angle_total).
  double hingeAngle(HingeId id) const;
  /// Torque (N m) the hinge's drive put on body a about the axis over the
  /// last substep: lambda_drive / h^2; for a spring, -stiffness (angle -
  /// target) - damping x the angular velocity (HingeDrive; trapezoidal:
  /// with the angle averaged over three substep ends as the rule does).
  double hingeDriveTorque(HingeId id) const;

  const std::vector<PrismaticJoint>& prismatics() const { return prismatics_; }
  PrismaticJoint& prismatic(PrismaticId id) { return prismatics_.at(id); }
  const PrismaticJoint& prismatic(PrismaticId id) const { return prismatics_.at(id); }
  JointWrench prismaticWrench(PrismaticId id) const {
    return reeve::prismaticWrench(prismatics_.at(id), last_h_);
  }
  /// Slide (m) of body a relative to b along the axis, 0 when added.
  double prismaticSlide(PrismaticId id) const;
  /// Force (N) the drive put on body a along the axis over the last
  /// substep: lambda_drive / h^2; for a spring, -stiffness (slide -
  /// target) - damping x the slide's velocity (PrismaticDrive; trapezoidal:
  /// with the slide averaged as the rule does).
  double prismaticDriveForce(PrismaticId id) const;

  const std::vector<SphericalJoint>& sphericals() const { return sphericals_; }
  SphericalJoint& spherical(SphericalId id) { return sphericals_.at(id); }
  const SphericalJoint& spherical(SphericalId id) const { return sphericals_.at(id); }
  JointWrench sphericalWrench(SphericalId id) const {
    return reeve::sphericalWrench(sphericals_.at(id), last_h_);
  }
  /// Swing (rad, in [0, pi]) and twist (rad, in (-pi, pi]) of a spherical
  /// joint (spherical_joint.h).
  double swingAngle(SphericalId id) const;
  double twistAngle(SphericalId id) const;

  const std::vector<FixedJoint>& fixedJoints() const { return fixeds_; }
  FixedJoint& fixedJoint(FixedId id) { return fixeds_.at(id); }
  const FixedJoint& fixedJoint(FixedId id) const { return fixeds_.at(id); }
  JointWrench fixedWrench(FixedId id) const { return reeve::fixedWrench(fixeds_.at(id), last_h_); }

  int distanceCount() const { return static_cast<int>(distances_.size()); }
  DistanceConstraint& distance(DistanceId id) { return distances_[id]; }
  const DistanceConstraint& distance(DistanceId id) const { return distances_[id]; }
  /// Tension (N) of a distance constraint over the last substep: -lambda/h^2.
  double tension(DistanceId id) const;

  int pathCount() const { return static_cast<int>(paths_.size()); }
  PathConstraint& path(PathId id) { return paths_[id]; }
  const PathConstraint& path(PathId id) const { return paths_[id]; }
  /// Tension (N) of a path over the last substep, -lambda/h^2: that of
  /// every segment, or of a weight-1 segment of a weighted path (segment i
  /// pulls with weights[i] times it); 0 when disabled.
  double pathTension(PathId id) const;
  /// Current length (m) of a path: the sum of its segments, its rolling
  /// ends held where the last position solve left them on their wheels and
  /// the cable that solve wound off added (path_constraint.h: SolvePoint).
  double pathLength(PathId id) const;
  /// World position (m) of a body-local point (kWorldBody allowed).
  Vec3 worldPoint(BodyId id, const Vec3& local) const { return body(id).toWorld(local); }

  /// The World's side of the energy ledger (energy.h): the state's
  /// energies now and the work and losses summed over every substep so far.
  WorldEnergy energy() const;
  /// How far back (s) the ledger reads the potential: h / 2 of the last
  /// substep under the direct solver's start projection, where the stored
  /// velocity is the half step's (energy.h), else 0. The flows are then
  /// booked with the velocity at each substep's start (addWork; the cable
  /// system's friction likewise).
  double ledgerLag() const;

  double time() const { return time_; }        // s simulated so far
  double lastSubstep() const { return last_h_; }  // s
  /// Iterations the last step() ran, over all its substeps: substeps x
  /// iterations, or fewer when the direct solver met every row early.
  int lastStepIterations() const { return last_iterations_; }
  /// Times the last step() built a direct solve's row layout again only
  /// because a resting contact joined or left it (a body its cables hold
  /// set down on a static one, or lifted off: its contact rows), which
  /// allocates; 0 under Gauss-Seidel.
  int lastStepContactLayouts() const { return last_contact_layouts_; }

 private:
  /// Throws std::invalid_argument unless a and b are two different
  /// existing bodies (kWorldBody allowed).
  void checkJointBodies(const char* kind, BodyId a, BodyId b) const;
  /// Makes rotors of the wheels on fixed axles (SolverKind), and free
  /// bodies again of those that no longer are, when the bodies or joints
  /// changed since the last step.
  void refreshRotors();
  /// Rebuilds joint_graph_ from the joints (refreshRotors).
  void buildJointGraph();
  /// Sets assembly_ (and assembly_member_) to the moving bodies joined to
  /// `start` by joints other than edge `skip_edge` of joint_graph_,
  /// stopping at static and kinematic ones (ground); false if they reach
  /// `other` (a closed loop). Empty when start is ground.
  bool driveAssembly(BodyId start, BodyId other, int skip_edge) const;
  /// 1 / (kg m^2): driveAssembly(start, ...) as one rigid body, about the
  /// world axis `u` through `anchor`, with the loads its cables in `island`
  /// hang from it; 0 for none, -1 for a closed loop.
  double assemblyInverseInertia(const Island& island, BodyId start, BodyId other, int skip_edge, const Vec3& anchor,
                                const Vec3& u) const;
  /// 1 / kg: driveAssembly's total mass; 0 for none, -1 for a closed loop.
  double assemblyInverseMass(BodyId start, BodyId other, int skip_edge) const;
  /// What a capped angle drive on hinge `hinge` brakes in time for
  /// (prepareHingeJoint): the inverse inertias about its axis of the two
  /// sides it turns apart, each side every body joined to it by other
  /// joints, carried as if welded (an upper bound on the inertia, so the
  /// drive never brakes too late for what its joints carry; cables are
  /// not followed). 1 / (kg m^2); the two bodies alone in a closed loop.
  /// `island`: the hinge's.
  double brakingInverseInertia(const Island& island, int hinge) const;
  /// The same for a capped position drive on prismatic joint
  /// `prismatic`: 1 / kg, the two sides' total masses.
  double brakingInverseMass(int prismatic) const;
  /// A hinge made compliant or rigid since refreshRotors(): a rotor's
  /// hinge made compliant frees the wheel, a wheel's made rigid may make
  /// it a rotor.
  bool hingeRigidityChanged() const;
  /// At the start of a substep of h s: removes these joints' drives whose
  /// `until` has come (HingeDrive::until) and sets scheduled drives'
  /// targets.
  void updateDrives(const std::vector<int>& hinges, const std::vector<int>& prismatics, double start_s, double h);
  /// An island's bodies over the substep of h s starting at `start_s`.
  void integrate(const Island& island, double start_s, double h);
  /// Runs fn(i) for every island i, on the World's threads when it has
  /// them, each thread its run of islands (island_runs_).
  template <class Fn>
  void forEachIsland(const Fn& fn);
  /// The same by groups: fn(group, count) for groups of up to `size`
  /// (<= kMaxIslandGroup) islands a thread takes together.
  template <class Fn>
  void forEachIslandGroup(int size, const Fn& fn);
  static constexpr int kMaxIslandGroup = 16;
  static constexpr int kWholeStepGroup = 4;  // runIslandsWhole's, measured (DESIGN.md, "Whole steps")
  /// One substep of h s (World::time() its start) for the islands at it
  /// (Island::at), and what joins them; `catching_up`: of a whole step
  /// (stepWhole), whose iterations and interrupt are counted there.
  void substep(int s, double h, bool start_pairing, bool catching_up);
  /// A step of h s substeps whose islands each run their substeps in one
  /// run, until done, interrupted, or the hooks have news for the World;
  /// the islands stopped are then stepped with it, substep by substep.
  void stepWhole(double h, bool start_pairing);
  /// A group of islands' part of stepWhole, together substep by substep.
  void runIslandsWhole(const int* group, int count, double h, bool start_pairing);
  /// The first of a substep's two passes over island i: its bodies'
  /// velocities kept for the ledger (`start_pairing`), its integration,
  /// its finite check, the hooks' island parts, whether they moved a
  /// row to another island (Island::moved) and had news (Island::news).
  void startIsland(int i, const SubstepClock& clock, double h, bool start_pairing);
  /// The second: its position solve (when `solve`; else it was solved
  /// already, solvePositionsChecked), velocities, hinge angles, contacts'
  /// velocity pass, ledger flows, rotor wrenches, speed guard and finite
  /// check.
  void finishIsland(int i, const SubstepClock& clock, double h, bool solve, bool start_pairing);
  /// The braking inverse inertias of an island's drives (beginSolve).
  void prepareBraking(const Island& island);
  /// The caller's thread's share of a whole step done, to progress_.
  void reportProgress();
  /// `again`: the substep's solve done again (ResolveCheck). Prepares
  /// the rows, then one of the two methods' solves of the substep:
  /// beginSolve, each island's solveIsland, endSolve.
  void solvePositions(double h, bool again);
  /// What the islands' solves share, before them: the drives' braking
  /// inertias and the rows on no island.
  void beginSolve(double h);
  /// After them: the iterations run (the most of any island) and the
  /// interrupt.
  void endSolve();
  /// One island's part of solvePositions, on the rows of its constraints
  /// alone; then one of the two methods' solves of it:
  void solveIsland(Island& island, double h, bool again);
  void solveDirect(Island& island, double h, bool again);  // direct/direct_step.cpp
  void sweepGaussSeidel(Island& island, double h);         // gauss_seidel/gauss_seidel.cpp
  /// The distance constraints and paths on no island (nothing in them
  /// moves: a cable between two static anchors). A compliant one still
  /// pulls: with W = 0 a visit sets its tension to stretch / compliance
  /// (issue 28, item 8). Gauss-Seidel visits them each iteration, the
  /// direct method once.
  void solveLooseRows(double h);
  /// Rebuilds islands_ (islands.cpp) if a constraint was added or one's
  /// bodies changed since the last build.
  void refreshIslands();
  /// Whether distance constraint (path) i, or any of these, has bodies
  /// now on another island than the one it was filed on.
  bool distanceMoved(int i) const;
  bool pathMoved(int i) const;
  bool rowsMoved(const std::vector<int>& distances, const std::vector<int>& paths) const;
  void buildIslands();
  /// Cuts the islands into island_runs_, one run a thread, of about equal
  /// cost (island_cost_; counted bodies and constraints until measured).
  void cutIslandRuns();
  /// Takes each island's share of its threads' measured time (Island::ns),
  /// and cuts the runs again by those costs: which thread steps an
  /// island changes no result. Decides from the runs' measured work
  /// whether the next step's runs are shared at all (share_runs_).
  void balanceIslandRuns();
  /// Hands this substep's contact manifolds to their islands.
  void sortManifolds();
  /// The island of body a, or else of b; -1 when neither is on one.
  int islandOf(BodyId a, BodyId b) const;
  /// solvePositions, again while a ResolveCheck asks (kMaxResolves).
  void solvePositionsChecked(double h);
  /// The interrupt flag is raised (setInterruptFlag); read, not cleared.
  bool interruptRequested() const { return interrupt_ && interrupt_->load(std::memory_order_relaxed) != 0; }
  void updateVelocities(const Island& island, double h, WorldEnergy& flows);
  /// Adds this substep's work of the motor drives and applied loads
  /// (energy.h) on an island to `flows`, once velocities are known.
  void addWork(const Island& island, double h, bool start_pairing, WorldEnergy& flows);
  /// Credits what these damped distance constraints and paths took out
  /// over the substep (WorldEnergy::cable_damping_loss).
  void addConstraintDampingLoss(const std::vector<int>& distances, const std::vector<int>& paths, double h,
                                WorldEnergy& flows);
  /// The contacts' velocity pass on an island (SCA 2020, Alg. 2 line 24),
  /// crediting its loss.
  void contactVelocityPass(const Island& island, double h, WorldEnergy& flows);
  /// The work of an island's kinematic bodies over the substep.
  void addKinematicWork(const Island& island, double start_s, double h, bool start_pairing, WorldEnergy& flows);
  /// Kinetic energy (J) of body `id` now.
  double kineticEnergy(BodyId id) const;
  /// Work (J) kinematic body `id` has done on the rest over the substep of
  /// h s so far: -(impulse . v + angular_impulse . omega) / h, the
  /// impulses the constraints and contacts gave it (BodyState); 0 for any
  /// other body.
  double kinematicWork(BodyId id, double h) const;
  void limitSpeeds(const Island& island);
  /// Island i's first non-finite body state (and, after the solve, pass
  /// 1, distance constraint tension) at the end of the clock's substep,
  /// unless it found one before (Island::non_finite).
  void findNonFinite(Island& island, const SubstepClock& clock, int pass, double h) const;
  /// The first non-finite value the step found, of any island, to
  /// firstNonFinite() unless one is there.
  void recordNonFinite();
  /// Broad phase (sort and sweep of bounding spheres along x over the
  /// colliding bodies) and narrow phase (collide.h) into contacts_.
  void findContacts();
  /// Groups this substep's manifolds into FrictionPools (contact.h;
  /// friction_pools.cpp): a body's manifolds on bodies that move as one,
  /// normals within kPoolAngle; a manifold alone keeps pool -1.
  void poolFriction();
  /// Manifold m's FrictionPool, nullptr for none.
  FrictionPool* frictionPool(const ContactManifold& m) {
    return m.pool >= 0 ? &friction_pools_[static_cast<std::size_t>(m.pool)] : nullptr;
  }
  /// Manifold m's SupportGroup, nullptr for none.
  const SupportGroup* supportGroup(const ContactManifold& m) const {
    return m.group >= 0 ? &support_groups_[static_cast<std::size_t>(m.group)] : nullptr;
  }
  /// Once, at the first step: bodies that overlap as placed by more than
  /// 1e-9 m pushed apart along their contacts' normals as poses alone; the
  /// first substep would push them out at overlap / h
  /// (initial_overlaps.cpp).
  void settleInitialOverlaps();

  SolverSettings settings_;
  std::vector<BodyState> bodies_;
  std::vector<BodyDef> defs_;
  BodyState world_frame_;
  std::vector<HingeJoint> hinges_;
  std::vector<PrismaticJoint> prismatics_;
  std::vector<SphericalJoint> sphericals_;
  std::vector<FixedJoint> fixeds_;
  std::vector<DistanceConstraint> distances_;
  std::vector<PathConstraint> paths_;
  std::vector<IslandHook> hooks_;
  std::vector<ResolveCheck> resolve_checks_;
  /// What a position solve changes, kept from before it while a
  /// ResolveCheck may ask for it again: the poses, the contacts and the
  /// springs' previous errors (the joints' prepare functions move them on).
  struct SolveStart {
    std::vector<Vec3> x;
    std::vector<Quat> q;
    std::vector<double> hinge_spring, prismatic_spring;
    std::vector<Contact> contacts;
    std::vector<ContactManifold> manifolds;
    std::vector<FrictionPool> friction_pools;
  };
  SolveStart solve_start_;
  std::optional<GroundPlane> ground_;
  std::vector<BodyId> colliders_;       // bodies with BodyDef::collides, swept along x
  std::vector<std::pair<BodyId, BodyId>> excluded_contacts_;  // (lower, higher), sorted: excludeContact
  std::vector<double> bound_radius_;    // m, per body: boundingRadius of its shape
  std::vector<Contact> contacts_;       // this substep's; capacity kept between substeps
  std::vector<ContactManifold> manifolds_;  // ranges of contacts_, one per touching pair
  std::vector<ContactManifold> previous_manifolds_;  // the last substep's, sorted by pair (findContacts)
  std::vector<FrictionPool> friction_pools_;          // this substep's (poolFriction)
  std::vector<int> pool_order_;                       // poolFriction's scratch
  std::vector<Vec3> pool_points_;                     // poolFriction's scratch
  std::vector<Vec3> pool_hull_;  // the pools' hull vertices (FrictionPool::hull points into it)
  std::vector<SupportGroup> support_groups_;  // this substep's (poolFriction), over manifolds_
  std::vector<int> group_members_;            // their members (SupportGroup::members points into it)
  double time_ = 0.0;
  double last_h_ = 0.0;
  // The poses are a position solve's (its solve_turn holds what it turned
  // the bodies by): from a solve's start until the next integration.
  bool poses_solved_ = false;
  std::optional<NonFiniteState> non_finite_;
  std::optional<NonFiniteFind> non_finite_found_;  // this step's on no island, or of islands since rebuilt
  int last_iterations_ = 0;
  int last_contact_layouts_ = 0;  // lastStepContactLayouts
  const std::atomic<int>* interrupt_ = nullptr;  // setInterruptFlag
  bool interrupted_ = false;
  std::function<void(int, int)> progress_;
  // A whole step (stepWhole): each substep's start (s, from time_ by
  // adding h, as substep by substep), the iterations of each substep's
  // solves (the most of any island; islands' since rebuilt), where the
  // hooks' parts on no island are (as Island::at, started), and the
  // caller's thread's progress (reportProgress).
  std::vector<double> substep_start_;
  std::vector<int> substep_iterations_;
  int loose_at_ = 0;
  bool loose_started_ = false;
  std::thread::id step_thread_;
  long long progress_units_ = 0, progress_planned_ = 1;
  int progress_reported_ = 0;
  std::vector<int> body_progress_;  // buildIslands' scratch: per body, its island's at and started
  std::vector<double> mass_;  // kg per body, 0 when static
  WorldEnergy flows_;         // work and losses (energy.h) of islands since rebuilt and of loose rows; not its state fields
  // The ledger's start pairing (ledgerLag): the direct solver projecting at
  // the start.
  bool pairsAtStart() const;
  // Each body's velocities as the last substep began (v_n-1/2, before its
  // integration): under the start projection a flow's power is read at the
  // substep's start, with (v_n-1/2 + v_n+1/2) / 2 (addWork).
  std::vector<Vec3> pre_v_, pre_omega_;
  std::vector<std::unique_ptr<Island>> islands_;  // island.h; kept with their solvers between builds
  bool islands_dirty_ = true;                      // a body or constraint added since buildIslands()
  int islands_built_ = 0;                          // islandsBuilt()
  std::vector<int> island_of_;                     // per body: its island, -1 for none (static)
  std::vector<std::vector<BodyId>> couplings_;     // coupleBodies
  std::vector<int> loose_distances_, loose_paths_;  // on no island (solveLooseRows)
  std::vector<int> loose_hinges_, loose_prismatics_;  // between static bodies: only their drives are kept
  std::vector<int> distance_island_, path_island_;  // per constraint: its island at the build, -1 for none
  // Per path: its placement when pathMoved last found it on its island (0:
  // none since the build); each path's is written by its island's thread.
  mutable std::vector<long long> path_placement_;
  int threads_ = 1;                                 // setThreads
  std::unique_ptr<ThreadPool> pool_;                // threads_ of them, once there are two islands
  std::vector<int> island_runs_;  // thread t's islands: [island_runs_[t], island_runs_[t + 1])
  /// Per thread, on a line of its own: its run as a shared run goes
  /// (forEachIsland).
  struct alignas(64) ThreadRun {
    // Its run's islands not yet taken, [front, end) as end << 32 | front:
    // its thread takes the front, a thread done with its own the end.
    std::atomic<std::uint64_t> left{0};
    std::vector<int> ran;  // the islands it ran in its last run, its own and others' (their Island::ns)
  };
  std::unique_ptr<ThreadRun[]> thread_runs_;  // threads_ of them, made with the pool's first runs (cutIslandRuns)
  // Per island: what stepping it costs (ns a step, smoothed), as the
  // measured time of the threads that ran it over the islands each ran
  // (Island::ns, balanceIslandRuns); 0 until then.
  std::vector<double> island_cost_;
  // Some island holds contact manifolds (sortManifolds): without, the
  // caller's thread touches no island between the runs.
  bool island_manifolds_ = false;
  bool share_runs_ = false;       // the islands' runs are worth the threads (balanceIslandRuns)
  double min_shared_run_ns_ = 1e3 * kMinSharedRunUs;  // setThreads
  double serial_ns_ = 0.0;        // ns of runs not shared since the last balanceIslandRuns
  int timed_runs_ = 0;            // runs timed since then
  /// What a thread's islands reported in its last run (forEachIsland),
  /// each on a cache line of its own.
  struct alignas(64) RunNews {
    bool moved = false;        // Island::moved
    bool driven = false;       // Island::driven
    bool interrupted = false;  // Island::interrupted
    int iterations = 0;        // the most of Island::iterations
  };
  std::vector<RunNews> news_;  // per thread
  /// All threads' news together.
  RunNews gatherNews() const;
  // Per hinge and prismatic joint with a drive: brakingInverseInertia
  // (Mass) for this substep, taken before the islands' solves (its
  // scratch is the World's).
  std::vector<double> hinge_braking_, prismatic_braking_;
  bool rotors_dirty_ = true;  // bodies or joints added since refreshRotors()
  bool overlaps_settled_ = false;  // settleInitialOverlaps() has run (before the first step)
  std::vector<PlacedOverlap> placed_overlaps_;
  std::vector<char> hinge_rigid_;  // per hinge: its compliance was 0 at refreshRotors()
  // Per body, its joints' other bodies and edge numbers (hinges, then
  // prismatics, sphericals, fixed joints, each in order); world excluded.
  std::vector<std::vector<std::pair<BodyId, int>>> joint_graph_;
  // driveAssembly's and assemblyInverseInertia's scratch, kept between calls.
  mutable std::vector<BodyId> assembly_;
  mutable std::vector<char> assembly_member_;  // per body: in assembly_
  mutable std::vector<double> hung_lever2_;    // per body: m^2, hung from assembly_ at that lever squared (else 0)
  mutable std::vector<BodyId> hung_;           // the bodies hung_lever2_ holds a lever for
};

}  // namespace reeve
