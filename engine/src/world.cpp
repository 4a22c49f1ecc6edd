#include "reeve/engine/world.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/LU>

#include "direct/direct_solver.h"
#include "island.h"
#include "reeve/engine/thread_pool.h"

namespace reeve {
namespace {

// Takes the next island of a run's [front, end) (World::ThreadRun::left):
// its front one, or its end one; -1 when none is left. Every island is
// taken once, by one thread or the other.
int takeIsland(std::atomic<std::uint64_t>& left, bool front) {
  std::uint64_t range = left.load(std::memory_order_relaxed);
  while (true) {
    const auto first = static_cast<std::uint32_t>(range), end = static_cast<std::uint32_t>(range >> 32);
    if (first >= end) return -1;
    const std::uint64_t rest = front ? range + 1 : range - (std::uint64_t{1} << 32);
    if (left.compare_exchange_weak(range, rest, std::memory_order_relaxed)) return static_cast<int>(front ? first : end - 1);
  }
}

// The velocities at the substep's start of the bodies on no island (an
// island's pass keeps its own: startIsland), for the ledger's start
// pairing (energy.cpp). pre_v and pre_omega grow with the world.
void keepLooseVelocities(const std::vector<BodyState>& bodies, const std::vector<int>& island_of,
                         std::vector<Vec3>& pre_v, std::vector<Vec3>& pre_omega) {
  if (pre_v.size() != bodies.size()) pre_v.resize(bodies.size()), pre_omega.resize(bodies.size());
  for (std::size_t id = 0; id < bodies.size(); ++id)
    if (island_of[id] < 0) pre_v[id] = bodies[id].v, pre_omega[id] = bodies[id].omega;
}

// The body's pose and velocities are all finite: 0 x each is 0 but for an
// infinity or a NaN, which makes the sum NaN (one test, not thirteen).
bool finiteState(const BodyState& b) {
  // Summed as a tree, not a chain of 13 additions: a body's test is four
  // additions deep, and the next body's overlaps it.
  const double* q = b.q.coeffs().data();
  const double x = (0.0 * b.x[0] + 0.0 * b.x[1]) + (0.0 * b.x[2] + 0.0 * b.v[0]);
  const double v = (0.0 * b.v[1] + 0.0 * b.v[2]) + (0.0 * b.omega[0] + 0.0 * b.omega[1]);
  const double w = (0.0 * b.omega[2] + 0.0 * q[0]) + (0.0 * q[1] + 0.0 * q[2]);
  return (x + v) + (w + 0.0 * q[3]) == 0.0;
}

// Checks of joint definitions at the boundary (World::add...): a clear
// std::invalid_argument naming the joint type, never a NaN in the solver.
[[noreturn]] void reject(const char* kind, const std::string& what) {
  throw std::invalid_argument(std::string(kind) + ": " + what);
}

void checkVector(const char* kind, const char* name, const Vec3& v, bool nonzero) {
  if (!v.allFinite()) reject(kind, std::string("the ") + name + " must be finite");
  if (nonzero && !(v.norm() > 0.0)) reject(kind, std::string("the ") + name + " must be a non-zero vector");
}

void checkCompliance(const char* kind, double compliance) {
  if (!(compliance >= 0.0) || !std::isfinite(compliance))
    reject(kind, "the compliance must be finite and >= 0");
}

// `bound`: the largest |lower|, |upper| allowed (pi for angles).
void checkLimit(const char* kind, const JointLimit& limit, double bound) {
  if (!limit.enabled) return;
  if (!std::isfinite(limit.lower) || !std::isfinite(limit.upper))
    reject(kind, "the limit bounds must be finite");
  if (limit.lower > limit.upper) reject(kind, "the limit needs lower <= upper");
  if (std::abs(limit.lower) > bound || std::abs(limit.upper) > bound)
    reject(kind, "angle limits must lie within [-pi, pi] rad");
}

void checkDrive(const char* kind, double target, double max_effort, double until,
                const std::vector<DriveKeyframe>& schedule) {
  if (!std::isfinite(target)) reject(kind, "the drive target must be finite");
  // isnan first: an ordered comparison with NaN raises FE_INVALID.
  if (std::isnan(until) || until <= 0.0) reject(kind, "the drive's end time (until) must be > 0 s");
  if (std::isnan(max_effort)) reject(kind, "the drive's maximum force or torque must be a number");
  if (!timesIncrease(schedule)) reject(kind, "the drive schedule's times must be finite and increase strictly");
  for (const DriveKeyframe& k : schedule)
    if (!std::isfinite(k.target)) reject(kind, "the drive schedule's targets must be finite");
}

// A drive's spring or damper (HingeDrive, PrismaticDrive): stiffness and
// damping finite and >= 0; stiffness only on an angle or position drive,
// whose damping needs it (a velocity drive's damping is a damper alone);
// trapezoidal integration only with a stiffness.
void checkSpring(const char* kind, double stiffness, double damping, bool position_drive, bool velocity_drive,
                 bool trapezoidal) {
  // isfinite first: an ordered comparison with NaN raises FE_INVALID.
  if (!std::isfinite(stiffness) || stiffness < 0.0) reject(kind, "the drive's stiffness must be finite and >= 0");
  if (!std::isfinite(damping) || damping < 0.0) reject(kind, "the drive's damping must be finite and >= 0");
  if (stiffness > 0.0 && !position_drive) reject(kind, "stiffness is for an angle or position drive only");
  if (damping > 0.0 && !position_drive && !velocity_drive) reject(kind, "damping is for a drive (it has none)");
  if (damping > 0.0 && position_drive && stiffness == 0.0)
    reject(kind, "an angle or position drive's damping needs a stiffness > 0");
  if (trapezoidal && stiffness == 0.0) reject(kind, "trapezoidal integration is for a spring (a stiffness > 0)");
}

constexpr double kPi = std::numbers::pi;
constexpr double kAny = std::numeric_limits<double>::infinity();

// [v]x: the matrix of v x (.).
Mat3 skew(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// Body-frame angular velocity after the gyroscopic term over h: one Newton
// step of implicit Euler on I (w' - w) + h w' x I w' = 0 (Catto, GDC 2015),
// from w:  w' = w - J^-1 h (w x I w),  J = I + h ([w]x I - [I w]x).
// The explicit update w += h I^-1 (-w x I w) gains energy on thin bodies
// spinning off their axes and overflows once h |w| nears 1.
// A single Newton step is not safe everywhere: J is singular where a body
// with three different moments spins near its middle axis with h |w| of
// order 1, and next to that the step adds energy. The free motion keeps
// both the energy w.I w / 2 and |I w|, so the result is scaled down until
// it gains neither, and a J too near singular leaves w as it is.
Vec3 gyroscopicStep(const Mat3& inertia, const Vec3& w, double h) {
  const Vec3 Iw = inertia * w;
  const Vec3 torque = w.cross(Iw);  // 0 for a spin about a principal axis, or any spin of a cube
  if (torque.squaredNorm() == 0.0) return w;
  const Mat3 J = inertia + h * (skew(w) * inertia - skew(Iw));
  const double det = J.determinant();
  if (!(std::abs(det) > 1e-9 * inertia.determinant())) return w;
  const Vec3 next = w - J.inverse() * (h * torque);
  const double energy = w.dot(Iw), momentum = Iw.squaredNorm();
  const Vec3 next_Iw = inertia * next;
  const double scale = std::min({1.0, std::sqrt(energy / next.dot(next_Iw)), std::sqrt(momentum / next_Iw.squaredNorm())});
  return scale * next;
}

}  // namespace

World::World(SolverSettings settings) : settings_(settings) {}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

BodyId World::addBody(const BodyDef& def) {
  bodies_.push_back(makeBodyState(def));
  mass_.push_back(bodies_.back().mass());
  rotors_dirty_ = islands_dirty_ = true;
  defs_.push_back(def);
  bound_radius_.push_back(boundingRadius(def.shape));
  const BodyId id = static_cast<BodyId>(bodies_.size() - 1);
  if (def.collides) colliders_.push_back(id);
  return id;
}

void World::setGround(const GroundPlane& ground) {
  checkVector("ground", "normal", ground.normal, true);
  if (!std::isfinite(ground.height_m)) reject("ground", "the height must be finite");
  if (!isValid(ground.material))
    reject("ground", "frictions must be finite and >= 0, restitution in [0, 1]");
  ground_ = ground;
  ground_->normal.normalize();
}

void World::findContacts() {
  // Room up front for a crowded substep (8 contacts and 2 touching pairs
  // a body), so that a step allocates nothing once the first frame ran:
  // beyond that the arrays grow, which is only a new high-water mark.
  const std::size_t touching = colliders_.size() + (ground_ ? bodies_.size() : 0);
  if (contacts_.capacity() < 8 * touching) contacts_.reserve(8 * touching);
  for (std::vector<ContactManifold>* m : {&manifolds_, &previous_manifolds_})
    if (m->capacity() < 2 * touching) m->reserve(2 * touching);
  contacts_.clear();
  // The last substep's manifolds, by pair (either way round), whose
  // friction anchors a pair that still sticks keeps (anchorFriction).
  const auto key = [](const ContactManifold& m) { return std::minmax(m.a, m.b); };
  const auto before = [&](const ContactManifold& p, const ContactManifold& q) { return key(p) < key(q); };
  previous_manifolds_.swap(manifolds_);
  manifolds_.clear();
  std::sort(previous_manifolds_.begin(), previous_manifolds_.end(), before);
  // Bounds grow by the largest contact margin a body can have (collide.h).
  constexpr double grow = 1.0 + kContactMarginFraction;
  const auto group = [&](std::size_t first) {
    if (contacts_.size() == first) return;
    ContactManifold m;
    m.first = static_cast<int>(first);
    m.count = static_cast<int>(contacts_.size() - first);
    const Contact& c = contacts_[first];
    m.a = c.a;
    m.b = c.b;
    const BodyState &a = c.a == kWorldBody ? world_frame_ : bodies_[c.a], &b = bodies_[c.b];
    describePatch(m, contacts_.data(), a, b);
    const auto found = std::lower_bound(previous_manifolds_.begin(), previous_manifolds_.end(), m, before);
    const bool kept = found != previous_manifolds_.end() && key(*found) == key(m);
    const Shape& shape_b = defs_[c.b].shape;
    anchorFriction(m, contacts_.data(), kept ? &*found : nullptr, a, b,
                   contactMargin(c.a == kWorldBody ? shape_b : defs_[c.a].shape, shape_b));
    if (kept) {
      m.last_pressure = found->pressure;
      m.last_stuck = found->stuck;
    }
    manifolds_.push_back(m);
  };
  if (ground_) {
    for (BodyId id = 0; id < bodyCount(); ++id) {
      const BodyState& b = bodies_[id];
      if (!b.moves() ||
          ground_->normal.dot(b.x) - ground_->height_m > grow * bound_radius_[id])
        continue;
      const std::size_t first = contacts_.size();
      collideGround(*ground_, id, defs_[id].shape, b, defs_[id].material, contacts_);
      group(first);
    }
  }
  if (colliders_.size() < 2) return;
  // Sort and sweep along x; insertion sort, as the order barely changes
  // between substeps (and it allocates nothing).
  const auto low = [&](BodyId id) { return bodies_[id].x.x() - grow * bound_radius_[id]; };
  for (std::size_t i = 1; i < colliders_.size(); ++i)
    for (std::size_t j = i; j > 0 && low(colliders_[j - 1]) > low(colliders_[j]); --j)
      std::swap(colliders_[j - 1], colliders_[j]);
  for (std::size_t i = 0; i < colliders_.size(); ++i) {
    const BodyId a = colliders_[i];
    const double high = bodies_[a].x.x() + grow * bound_radius_[a];
    for (std::size_t j = i + 1; j < colliders_.size() && low(colliders_[j]) <= high; ++j) {
      const BodyId b = colliders_[j];
      const BodyState &sa = bodies_[a], &sb = bodies_[b];
      if (!sa.moves() && !sb.moves()) continue;
      if (!contactAllowed(a, b)) continue;
      const double reach = grow * (bound_radius_[a] + bound_radius_[b]);
      if ((sb.x - sa.x).squaredNorm() > reach * reach) continue;
      const std::size_t first = contacts_.size();
      collideBodies(a, defs_[a].shape, sa, b, defs_[b].shape, sb,
                    combine(defs_[a].material, defs_[b].material), contacts_);
      group(first);
    }
  }
}

void World::excludeContact(BodyId a, BodyId b) {
  if (a < 0 || b < 0 || a >= bodyCount() || b >= bodyCount() || a == b)
    throw std::invalid_argument("excludeContact: needs two different bodies of this world");
  const std::pair<BodyId, BodyId> pair{std::min(a, b), std::max(a, b)};
  const auto at = std::lower_bound(excluded_contacts_.begin(), excluded_contacts_.end(), pair);
  if (at == excluded_contacts_.end() || *at != pair) excluded_contacts_.insert(at, pair);
}

bool World::contactAllowed(BodyId a, BodyId b) const {
  const BodyDef &da = defs_[a], &db = defs_[b];
  if (((da.contact_type & db.contact_affinity) | (db.contact_type & da.contact_affinity)) == 0) return false;
  const std::pair<BodyId, BodyId> pair{std::min(a, b), std::max(a, b)};
  return excluded_contacts_.empty() || !std::binary_search(excluded_contacts_.begin(), excluded_contacts_.end(), pair);
}

void World::setMass(BodyId id, double mass) {
  if (id == kWorldBody || id < 0 || id >= bodyCount() || mass_[id] == 0.0 || !isRepresentableMass(mass))
    throw std::invalid_argument("setMass: needs a dynamic body and a mass between 1e-100 and 1e100 kg");
  BodyState& b = bodies_[id];
  const double scale = mass / mass_[id];
  const Vec3 moments = b.inertia.diagonal() * scale;
  if (!isRepresentableMass(moments.minCoeff()) || !isRepresentableMass(moments.maxCoeff()))
    throw std::invalid_argument("setMass: the moments of inertia would leave 1e-100..1e100 kg m^2");
  mass_[id] = mass;
  b.inertia *= scale;
  b.inv_mass = 1.0 / mass;
  b.inv_inertia = b.inertia.inverse();
  b.rotor_axis.setZero();
  // A rotor is made again at the next step, and the islands, which know
  // whether a body of theirs may be massless beside another (island.h).
  rotors_dirty_ = islands_dirty_ = true;
}

bool World::hingeRigidityChanged() const {
  for (std::size_t i = 0; i < hinges_.size(); ++i)
    if ((hinges_[i].compliance == 0.0) != static_cast<bool>(hinge_rigid_[i])) return true;
  return false;
}

void World::refreshRotors() {
  rotors_dirty_ = false;
  buildJointGraph();
  hinge_rigid_.resize(hinges_.size());
  for (std::size_t i = 0; i < hinges_.size(); ++i) hinge_rigid_[i] = hinges_[i].compliance == 0.0;
  for (BodyId id = 0; id < bodyCount(); ++id) {
    BodyState& b = bodies_[id];
    if (mass_[id] == 0.0) continue;
    b.inv_mass = 1.0 / mass_[id];
    b.inv_inertia = b.inertia.inverse();
    b.rotor_axis.setZero();
  }
  // A rotor's only joint is a rigid hinge to a static body (or the world)
  // whose axle passes through its centre of mass.
  std::vector<int> joints(bodies_.size(), 0);
  const auto count = [&](BodyId a, BodyId b) {
    for (const BodyId id : {a, b})
      if (id != kWorldBody) ++joints[id];
  };
  for (const HingeJoint& j : hinges_) count(j.a, j.b);
  for (const PrismaticJoint& j : prismatics_) count(j.a, j.b);
  for (const SphericalJoint& j : sphericals_) count(j.a, j.b);
  for (const FixedJoint& j : fixeds_) count(j.a, j.b);
  for (const HingeJoint& j : hinges_) {
    const bool a_moves = j.a != kWorldBody && mass_[j.a] > 0.0;
    const bool b_moves = j.b != kWorldBody && mass_[j.b] > 0.0;
    // Not on a kinematic body: that carries the axle along.
    if (a_moves == b_moves || j.compliance != 0.0 || body(j.a).kinematic || body(j.b).kinematic) continue;
    const BodyId id = a_moves ? j.a : j.b;
    const Vec3 anchor = a_moves ? j.frame.anchor_a : j.frame.anchor_b;
    const Vec3 axis = (a_moves ? j.frame.axis_a : j.frame.axis_b).normalized();
    if (joints[id] != 1 || (anchor - anchor.dot(axis) * axis).norm() > 1e-9 * std::max(1.0, anchor.norm()))
      continue;
    BodyState& b = bodies_[id];
    b.rotor_axis = axis;
    b.inv_mass = 0.0;
    b.inv_inertia = axis * axis.transpose() / axis.dot(b.inertia * axis);
    // Onto its axle, in case it sagged off while its hinge was compliant
    // (a rotor stays where it is made).
    const BodyState& other = body(a_moves ? j.b : j.a);
    const Vec3 other_axis = other.q * (a_moves ? j.frame.axis_b : j.frame.axis_a).normalized();
    b.q = (rotationBetween(b.q * axis, other_axis) * b.q).normalized();
    b.x = other.toWorld(a_moves ? j.frame.anchor_b : j.frame.anchor_a) - b.q * anchor;
    const Vec3 u = b.q * axis;
    b.v.setZero();
    b.omega = u * u.dot(b.omega);
  }
}

void World::checkJointBodies(const char* kind, BodyId a, BodyId b) const {
  const auto valid = [&](BodyId id) { return id == kWorldBody || (id >= 0 && id < bodyCount()); };
  if (!valid(a) || !valid(b) || a == b) reject(kind, "needs two different existing bodies");
}

HingeId World::addHinge(const HingeDef& def) {
  checkJointBodies("hinge", def.body, def.other);
  checkVector("hinge", "axis", def.axis, true);
  checkVector("hinge", "anchor", def.anchor, false);
  checkCompliance("hinge", def.compliance);
  checkLimit("hinge", def.limit, kPi);
  checkDrive("hinge", def.drive.target, def.drive.max_torque, def.drive.until, def.drive.schedule);
  checkSpring("hinge", def.drive.stiffness, def.drive.damping, def.drive.mode == HingeDrive::Mode::Angle,
              def.drive.mode == HingeDrive::Mode::Velocity, def.drive.integration == HingeDrive::Integration::Trapezoidal);
  rotors_dirty_ = islands_dirty_ = true;
  hinges_.push_back(makeHingeJoint(def, body(def.body), body(def.other)));
  return static_cast<HingeId>(hinges_.size() - 1);
}

PrismaticId World::addPrismatic(const PrismaticDef& def) {
  checkJointBodies("prismatic joint", def.body, def.other);
  checkVector("prismatic joint", "axis", def.axis, true);
  checkVector("prismatic joint", "anchor", def.anchor, false);
  checkCompliance("prismatic joint", def.compliance);
  checkLimit("prismatic joint", def.limit, kAny);
  checkDrive("prismatic joint", def.drive.target, def.drive.max_force, def.drive.until, def.drive.schedule);
  checkSpring("prismatic joint", def.drive.stiffness, def.drive.damping,
              def.drive.mode == PrismaticDrive::Mode::Position, def.drive.mode == PrismaticDrive::Mode::Velocity,
              def.drive.integration == PrismaticDrive::Integration::Trapezoidal);
  rotors_dirty_ = islands_dirty_ = true;
  prismatics_.push_back(makePrismaticJoint(def, body(def.body), body(def.other)));
  return static_cast<PrismaticId>(prismatics_.size() - 1);
}

SphericalId World::addSpherical(const SphericalDef& def) {
  checkJointBodies("spherical joint", def.body, def.other);
  checkVector("spherical joint", "axis", def.axis, true);
  checkVector("spherical joint", "anchor", def.anchor, false);
  checkCompliance("spherical joint", def.compliance);
  checkLimit("spherical joint", def.twist_limit, kPi);
  if (def.swing_limit.enabled && !(def.swing_limit.max >= 0.0 && def.swing_limit.max <= kPi))
    reject("spherical joint", "the swing limit must lie within [0, pi] rad");
  if (def.twist_limit.enabled && !(def.swing_limit.enabled && def.swing_limit.max <= kMaxSwingWithTwist))
    reject("spherical joint", "a twist limit needs a swing limit of at most pi/2 rad (the twist is ill-defined "
                              "as the swing nears pi)");
  rotors_dirty_ = islands_dirty_ = true;
  sphericals_.push_back(makeSphericalJoint(def, body(def.body), body(def.other)));
  return static_cast<SphericalId>(sphericals_.size() - 1);
}

FixedId World::addFixed(const FixedDef& def) {
  checkJointBodies("fixed joint", def.body, def.other);
  checkVector("fixed joint", "anchor", def.anchor, false);
  checkCompliance("fixed joint", def.compliance);
  rotors_dirty_ = islands_dirty_ = true;
  fixeds_.push_back(makeFixedJoint(def, body(def.body), body(def.other)));
  return static_cast<FixedId>(fixeds_.size() - 1);
}

JointWrench World::hingeWrench(HingeId id) const {
  const HingeJoint& j = hinges_.at(id);
  const double h = last_h_;
  const bool on_a = body(j.a).isRotor();
  if (!(h > 0.0) || (!on_a && !body(j.b).isRotor())) return reeve::hingeWrench(j, h);
  // A rotor's centre stays put and it turns only about its axle, so the
  // axle took the rest of what the constraints gave it, and its weight:
  // the impulse F = -(impulse + m g h^2) at the anchor (arm rho from the
  // centre) and the angular impulse off the axle -(angular_impulse +
  // rho x F); along the axle the hinge's drive and limit rows act, whose
  // part the solve left in impulse_axis. From the rotor's state, which the
  // last substep left (read when asked: a step does not pay for it).
  const BodyId id_r = on_a ? j.a : j.b;
  const BodyState& r = bodies_[id_r];
  const Vec3 u = r.q * r.rotor_axis;
  const Vec3& anchor = on_a ? j.frame.anchor_a : j.frame.anchor_b;
  const Vec3 F = -(r.impulse + mass_[id_r] * h * h * settings_.gravity);
  Vec3 L = -r.angular_impulse;
  if (!anchor.isZero()) L -= Vec3(r.q * anchor).cross(F);  // most axles pass through the centre
  L -= u * u.dot(L);
  const Vec3 point = on_a ? F : Vec3(-F), axis = j.impulse_axis + (on_a ? L : Vec3(-L));
  return {point / (h * h), axis / (h * h)};  // as reeve::hingeWrench
}

double World::hingeAngle(HingeId id) const {
  const HingeJoint& j = hinges_.at(id);
  return hingeAngleTotal(j, body(j.a).q, body(j.b).q);
}

double World::hingeDriveTorque(HingeId id) const {
  return last_h_ > 0.0 ? hinges_.at(id).angle.lambda_drive / (last_h_ * last_h_) : 0.0;
}

double World::prismaticSlide(PrismaticId id) const {
  const PrismaticJoint& j = prismatics_.at(id);
  const BodyState &a = body(j.a), &b = body(j.b);
  return reeve::prismaticSlide(j, a.x, a.q, b.x, b.q);
}

double World::prismaticDriveForce(PrismaticId id) const {
  return last_h_ > 0.0 ? prismatics_.at(id).slide.lambda_drive / (last_h_ * last_h_) : 0.0;
}

double World::swingAngle(SphericalId id) const {
  const SphericalJoint& j = sphericals_.at(id);
  return reeve::swingAngle(j, body(j.a).q, body(j.b).q);
}

double World::twistAngle(SphericalId id) const {
  const SphericalJoint& j = sphericals_.at(id);
  return reeve::twistAngle(j, body(j.a).q, body(j.b).q);
}

DistanceId World::addDistance(const DistanceConstraint& c) {
  assert(c.a >= kWorldBody && c.a < bodyCount() && c.b >= kWorldBody && c.b < bodyCount());
  distances_.push_back(c);
  islands_dirty_ = true;
  return static_cast<DistanceId>(distances_.size() - 1);
}

PathId World::addPath(PathConstraint path) {
  assert(path.points.size() >= 2);
  paths_.push_back(std::move(path));
  islands_dirty_ = true;
  return static_cast<PathId>(paths_.size() - 1);
}

double World::pathTension(PathId id) const {
  const PathConstraint& p = paths_[id];
  return p.enabled && last_h_ > 0.0 ? -p.lambda / (last_h_ * last_h_) : 0.0;
}

double World::pathLength(PathId id) const {
  // As the solves measure it: the rolling ends held where the last solve
  // left them, until the next substep's integration (path_constraint.h).
  const PathConstraint& path = paths_[id];
  const std::vector<PathPoint>& points = path.points;
  const std::size_t n = points.size();
  const bool stores = settings_.solver == SolverKind::Direct;
  // A point that slides (a slipping wrap's) is held as the solve holds
  // it, and pays nothing out, at an end too.
  const auto endPoint = [&](const PathPoint& point) {
    SolvePoint p = solvePoint(body(point.body), point, poses_solved_, stores);
    if (point.slides) p.axis.setZero(), p.turn = 0.0;
    return p;
  };
  const SolvePoint first = endPoint(points[0]), last = endPoint(points[n - 1]);
  const auto position = [&](std::size_t i) {
    const BodyState& b = body(points[i].body);
    if (i == 0 || i + 1 == n) return Vec3(b.x + (i == 0 ? first.arm : last.arm));
    return Vec3(b.x + (points[i].slides ? solvePoint(b, points[i], poses_solved_).arm : Vec3(b.q * points[i].local)));
  };
  double length = 0.0;
  for (size_t i = 0; i + 1 < n; ++i) length += segmentScale(path, i) * (position(i + 1) - position(i)).norm();
  if (first.turn != 0.0 || first.paid != 0.0)
    length += segmentScale(path, 0) * first.payOut(-(position(1) - position(0)).normalized());
  if (last.turn != 0.0 || last.paid != 0.0)
    length += segmentScale(path, n - 2) * last.payOut((position(n - 1) - position(n - 2)).normalized());
  return length;
}

void World::addSubstepHook(SubstepHook hook) { hooks_.push_back({nullptr, nullptr, std::move(hook)}); }
void World::addSubstepHook(IslandHook hook) { hooks_.push_back(std::move(hook)); }

void World::addResolveCheck(ResolveCheck check) { resolve_checks_.push_back(std::move(check)); }

std::optional<BodyId> World::findBody(const std::string& name) const {
  for (size_t i = 0; i < defs_.size(); ++i)
    if (defs_[i].name == name) return static_cast<BodyId>(i);
  return std::nullopt;
}

double World::tension(DistanceId id) const {
  return last_h_ > 0.0 ? -distances_[id].lambda / (last_h_ * last_h_) : 0.0;
}

void World::step(double dt) {
  assert(settings_.substeps > 0 && settings_.iterations > 0);
  settleInitialOverlaps();
  if (rotors_dirty_ || hingeRigidityChanged()) refreshRotors();
  refreshIslands();
  if (pool_ && islands_.size() > 1) balanceIslandRuns();
  last_iterations_ = 0;
  interrupted_ = false;
  const double h = dt / settings_.substeps;
  const bool start_pairing = pairsAtStart();  // the ledger's (energy.cpp)
  hinge_braking_.resize(hinges_.size());
  prismatic_braking_.resize(prismatics_.size());
  loose_at_ = 0;
  loose_started_ = false;
  for (auto& island : islands_) {
    island->at = 0;
    island->started = island->cut = false;
    island->substep_iterations.clear();
    island->contact_layouts = 0;
  }
  substep_iterations_.clear();
  if (runsWholeSteps()) {
    stepWhole(h, start_pairing);
  } else {
    for (int s = 0; s < settings_.substeps && !interrupted_; ++s) {
      substep(s, h, start_pairing, false);
      if (progress_) progress_(s + 1, settings_.substeps);
      if (!interrupted_ && s + 1 < settings_.substeps) interrupted_ = interruptRequested();
    }
  }
  last_contact_layouts_ = 0;
  for (const auto& island : islands_) last_contact_layouts_ += island->contact_layouts;
  recordNonFinite();
  last_h_ = h;
}

bool World::runsWholeSteps() const {
  // Nothing may join the islands within a step, nor run between their
  // passes on the caller's thread.
  if (islands_.empty() || !resolve_checks_.empty() || hasContacts()) return false;
  if (!loose_distances_.empty() || !loose_paths_.empty() || !loose_hinges_.empty() || !loose_prismatics_.empty())
    return false;
  if (!std::all_of(hooks_.begin(), hooks_.end(), [](const IslandHook& hook) { return hook.whole_steps; }))
    return false;
  // A braked drive's inertia is found over its assembly in the World's
  // scratch (drive_assembly.cpp), on the caller's thread (beginSolve).
  for (const HingeJoint& j : hinges_)
    if (j.drive.mode == HingeDrive::Mode::Angle && j.drive.stiffness == 0.0 && j.drive.max_torque > 0.0 &&
        std::isfinite(j.drive.max_torque))
      return false;
  for (const PrismaticJoint& j : prismatics_)
    if (j.drive.mode == PrismaticDrive::Mode::Position && j.drive.stiffness == 0.0 && j.drive.max_force > 0.0 &&
        std::isfinite(j.drive.max_force))
      return false;
  return true;
}

void World::substep(int s, double h, bool start_pairing, bool catching_up) {
  const SubstepClock clock{s, time_};
  // Each island's passes run together, on its thread (forEachIsland);
  // what joins islands or is on none runs between, on this one. An island
  // not at this substep (Island::at: a whole step ran it on) sits out.
  if (start_pairing && !catching_up) keepLooseVelocities(bodies_, island_of_, pre_v_, pre_omega_);
  updateDrives(loose_hinges_, loose_prismatics_, clock.time_s, h);
  poses_solved_ = false;
  for (auto& hook : hooks_)
    if (hook.before) hook.before(*this, h);
  if (loose_at_ == s) {
    if (!loose_started_)
      for (auto& hook : hooks_)
        if (hook.island) hook.island(*this, h, -1, clock);
    loose_at_ = s + 1;
    loose_started_ = false;
  }
  forEachIsland([&](int i) {
    Island& island = *islands_[i];
    if (island.at != s) {
      island.moved = island.driven = island.interrupted = false;
      island.iterations = 0;
    } else if (!island.started) {
      startIsland(i, clock, h, start_pairing);
    }
  });
  for (auto& hook : hooks_)
    if (hook.after) hook.after(*this, h);
  if (rotors_dirty_) refreshRotors();  // a hook added a joint (a cable's jam) to a rotor
  // The joint, or a span moved on to a new body (each island checked its
  // own rows).
  if (!hooks_.empty()) {
    islands_dirty_ = islands_dirty_ || gatherNews().moved || rowsMoved(loose_distances_, loose_paths_);
    if (islands_dirty_) buildIslands();
  }
  const bool contacts = hasContacts();
  if (contacts) {
    findContacts();
    poolFriction();
  } else if (!contacts_.empty()) {  // the ground was removed
    contacts_.clear();
    manifolds_.clear();
    previous_manifolds_.clear();
    friction_pools_.clear();
    support_groups_.clear();
  }
  sortManifolds();
  // A ResolveCheck reads every island's solve: the solves run first, on
  // their own.
  const bool checked = !resolve_checks_.empty();
  if (checked) solvePositionsChecked(h);
  else beginSolve(h);
  forEachIsland([&](int i) {
    if (islands_[i]->at == s) finishIsland(i, clock, h, !checked, start_pairing);
  });
  if (!checked && !catching_up) endSolve();
  addConstraintDampingLoss(loose_distances_, loose_paths_, h, flows_);
  for (const int i : loose_distances_) {
    const DistanceConstraint& d = distances_[i];
    const NonFiniteFind find{s, 1, bodyCount() + i, NonFiniteState{d.a, d.b, NonFiniteState::Quantity::Tension, time_ + h}};
    if (!std::isfinite(d.lambda / (h * h)) && (!non_finite_found_ || find < *non_finite_found_)) non_finite_found_ = find;
  }
  time_ += h;
}

void World::stepWhole(double h, bool start_pairing) {
  const int substeps = settings_.substeps;
  substep_start_.resize(substeps + 1);
  substep_start_[0] = time_;
  for (int s = 0; s < substeps; ++s) substep_start_[s + 1] = substep_start_[s] + h;
  substep_iterations_.assign(substeps, 0);
  for (auto& island : islands_) island->substep_iterations.assign(substeps, 0);
  if (start_pairing) keepLooseVelocities(bodies_, island_of_, pre_v_, pre_omega_);
  poses_solved_ = false;
  for (auto& hook : hooks_)
    if (hook.before) hook.before(*this, h);
  step_thread_ = std::this_thread::get_id();
  progress_units_ = 0;
  progress_reported_ = 0;
  const bool shared = runsShared();
  progress_planned_ = std::max<long long>(
      1, static_cast<long long>(shared ? island_runs_[1] - island_runs_[0] : islands_.size()) * substeps);
  forEachIslandGroup(kWholeStepGroup, [&](const int* group, int count) {
    runIslandsWhole(group, count, h, start_pairing);
  });
  // Cut short by the interrupt flag: those behind are stepped up to the
  // island furthest on, so that all end at one time.
  int target = substeps;
  bool cut = false;
  for (const auto& island : islands_) cut |= island->cut;
  if (cut) {
    target = 0;
    for (const auto& island : islands_) target = std::max(target, island->at + (island->started ? 1 : 0));
  }
  // What is on no island (nothing in it moves), up to its news.
  for (; loose_at_ < target; ++loose_at_) {
    const SubstepClock clock{loose_at_, substep_start_[loose_at_]};
    bool news = false;
    for (auto& hook : hooks_)
      if (hook.island) news |= hook.island(*this, h, -1, clock);
    if (news) {
      loose_started_ = true;
      break;
    }
  }
  int from = loose_at_;
  for (const auto& island : islands_) from = std::min(from, island->at);
  for (int s = from; s < target; ++s) {
    time_ = substep_start_[s];
    substep(s, h, start_pairing, true);
  }
  if (from >= target) {  // the hooks' substep ends, as the last substep's
    time_ = substep_start_[target - 1];
    for (auto& hook : hooks_)
      if (hook.after) hook.after(*this, h);
  }
  time_ = substep_start_[target];
  poses_solved_ = true;
  for (const auto& island : islands_) {
    for (int s = 0; s < substeps; ++s)
      substep_iterations_[s] = std::max(substep_iterations_[s], island->substep_iterations[s]);
    interrupted_ |= island->cut;
  }
  for (int s = 0; s < target; ++s) last_iterations_ += substep_iterations_[s];
  interrupted_ |= target < substeps;
  if (progress_ && progress_reported_ < target) progress_(target, substeps);
}

void World::runIslandsWhole(const int* group, int count, double h, bool start_pairing) {
  // Substep by substep over the group, each pass over all its islands: a
  // pass's code stays in the core's instruction cache from island to
  // island, as substep by substep (one island's whole substep does not fit
  // in a 32 KB L1: cachegrind counts 22 times the misses one island at a
  // time, 3 times in groups of 8; DESIGN.md, "Whole steps").
  int running[kMaxIslandGroup], live = 0;
  for (int k = 0; k < count; ++k) running[live++] = group[k];
  const int substeps = settings_.substeps;
  const bool reports = progress_ && std::this_thread::get_id() == step_thread_;
  const auto keep = [&](auto&& goes_on) {  // drops the islands that stop, in order
    int kept = 0;
    for (int k = 0; k < live; ++k)
      if (goes_on(*islands_[running[k]])) running[kept++] = running[k];
    live = kept;
  };
  for (int s = 0; s < substeps && live > 0; ++s) {
    const SubstepClock clock{s, substep_start_[s]};
    for (int k = 0; k < live; ++k) startIsland(running[k], clock, h, start_pairing);
    // News for the World: stopped before this substep's solve.
    keep([](const Island& island) { return !island.news && !island.moved; });
    for (int k = 0; k < live; ++k) {
      Island& island = *islands_[running[k]];
      if (island.driven) prepareBraking(island);
      finishIsland(running[k], clock, h, true, start_pairing);
      if (reports) reportProgress();
    }
    // A flag raised during the last substep cuts nothing.
    const bool flagged = s + 1 < substeps && interruptRequested();
    keep([&](Island& island) { return !(island.cut |= flagged); });
  }
}

void World::reportProgress() {
  const int substeps = settings_.substeps;
  const auto done = static_cast<int>(std::min<long long>(substeps, ++progress_units_ * substeps / progress_planned_));
  if (done > progress_reported_) progress_(progress_reported_ = done, substeps);
}

template <class Fn>
void World::forEachIsland(const Fn& fn) {
  forEachIslandGroup(1, [&](const int* group, int) { fn(group[0]); });
}

template <class Fn>
void World::forEachIslandGroup(int size, const Fn& fn) {
  assert(size >= 1 && size <= kMaxIslandGroup);
  const int n = static_cast<int>(islands_.size());
  // What the islands report, gathered by the thread that ran them: the
  // caller then reads one line a thread, not each island's.
  const auto fold = [](RunNews& news, const Island& island) {
    news.moved |= island.moved;
    news.driven |= island.driven;
    news.interrupted |= island.interrupted;
    news.iterations = std::max(news.iterations, island.iterations);
  };
  if (!pool_ || n < 2 || !share_runs_) {
    std::fill(news_.begin(), news_.end(), RunNews{});
    const bool timed = pool_ && n > 1;  // to see whether the threads would pay (balanceIslandRuns)
    const auto start = timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
    int group[kMaxIslandGroup];
    for (int first = 0; first < n; first += size) {
      const int count = std::min(size, n - first);
      for (int k = 0; k < count; ++k) group[k] = first + k;
      fn(group, count);
      for (int k = 0; k < count; ++k) fold(news_[0], *islands_[first + k]);
    }
    if (timed) {
      serial_ns_ += std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
      ++timed_runs_;
    }
    return;
  }
  // Each thread its own run of islands of about equal measured work, the
  // same every substep, so that an island's data stays in its core's cache
  // (ThreadPool::runEach); done with it, a thread takes the islands the
  // others have not yet begun, from their runs' ends: a core slower than
  // the other, or islands dearer this substep than measured, hold no thread
  // up for a whole run.
  for (int t = 0; t < threads_; ++t)
    thread_runs_[t].left.store(static_cast<std::uint64_t>(island_runs_[t + 1]) << 32 | island_runs_[t],
                               std::memory_order_relaxed);  // published by runEach
  pool_->runEach([&](int t) {
    const auto start = std::chrono::steady_clock::now();
    ThreadRun& mine = thread_runs_[t];
    RunNews& news = news_[t];
    news = RunNews{};
    mine.ran.clear();
    int group[kMaxIslandGroup], count = 0;
    const auto flush = [&] {
      if (count == 0) return;
      fn(group, count);
      for (int k = 0; k < count; ++k) {
        mine.ran.push_back(group[k]);
        fold(news, *islands_[group[k]]);
      }
      count = 0;
    };
    // Its own run in groups that shrink as it runs out (a quarter of what
    // is left, so that no group holds the other threads up at the end);
    // the others' islands one at a time.
    int want = 1;
    const auto shrink = [&] {
      const std::uint64_t left = mine.left.load(std::memory_order_relaxed);
      const auto rest = static_cast<int>(static_cast<std::uint32_t>(left >> 32) - static_cast<std::uint32_t>(left));
      want = std::clamp(rest / 4, 1, size);
    };
    shrink();
    for (int i; (i = takeIsland(mine.left, true)) >= 0;)
      if ((group[count++] = i, count >= want)) flush(), shrink();
    flush();
    for (int k = 1; k < threads_; ++k)
      for (int i; (i = takeIsland(thread_runs_[(t + k) % threads_].left, false)) >= 0;) {
        group[count++] = i;
        flush();
      }
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    for (const int i : mine.ran) islands_[i]->ns += ns / static_cast<double>(mine.ran.size());
  });
  ++timed_runs_;
}

World::RunNews World::gatherNews() const {
  RunNews all;
  for (const RunNews& news : news_) {
    all.moved |= news.moved;
    all.driven |= news.driven;
    all.interrupted |= news.interrupted;
    all.iterations = std::max(all.iterations, news.iterations);
  }
  return all;
}

void World::startIsland(int i, const SubstepClock& clock, double h, bool start_pairing) {
  Island& island = *islands_[i];
  if (start_pairing)
    for (const BodyId id : island.bodies) pre_v_[id] = bodies_[id].v, pre_omega_[id] = bodies_[id].omega;
  updateDrives(island.hinges, island.prismatics, clock.time_s, h);
  island.driven = std::any_of(island.hinges.begin(), island.hinges.end(),
                              [&](int j) { return hinges_[j].drive.mode != HingeDrive::Mode::None; }) ||
                  std::any_of(island.prismatics.begin(), island.prismatics.end(),
                              [&](int j) { return prismatics_[j].drive.mode != PrismaticDrive::Mode::None; });
  integrate(island, clock.time_s, h);
  findNonFinite(island, clock, 0, h);  // born before any constraint spreads it
  island.moved = island.news = false;
  for (auto& hook : hooks_)
    if (hook.island) island.news |= hook.island(*this, h, i, clock);
  if (!hooks_.empty()) island.moved = rowsMoved(island.distances, island.paths);
  island.started = true;
}

void World::finishIsland(int i, const SubstepClock& clock, double h, bool solve, bool start_pairing) {
  Island& island = *islands_[i];
  WorldEnergy& flows = island.flows;
  if (solve) solveIsland(island, h, false);
  updateVelocities(island, h, flows);
  for (const int j : island.hinges) trackHingeAngle(hinges_[j], body(hinges_[j].a), body(hinges_[j].b), h);
  addWork(island, h, start_pairing, flows);
  addConstraintDampingLoss(island.distances, island.paths, h, flows);
  contactVelocityPass(island, h, flows);
  addKinematicWork(island, clock.time_s, h, start_pairing, flows);
  limitSpeeds(island);  // last, so no later pass can push past the guard
  findNonFinite(island, clock, 1, h);
  island.cut |= island.interrupted;
  if (clock.substep < static_cast<int>(island.substep_iterations.size()))
    island.substep_iterations[clock.substep] = island.iterations;
  island.at = clock.substep + 1;
  island.started = false;
}

void World::contactVelocityPass(const Island& island, double h, WorldEnergy& flows) {
  // SCA 2020, Alg. 2 line 24: the velocity pass of the contacts, with
  // restitution off below 2 |g| h.
  const double rest_speed = 2.0 * settings_.gravity.norm() * h;
  for (const int i : island.manifolds) {
    const ContactManifold& m = manifolds_[i];
    const Contact& c = contacts_[m.first];
    const double before = kineticEnergy(c.a) + kineticEnergy(c.b);
    const double driven = kinematicWork(c.a, h) + kinematicWork(c.b, h);
    solveContactVelocities(m, contacts_.data(), body(c.a), body(c.b), h, rest_speed, frictionPool(m));
    // What a kinematic body put in (a conveyor dragging a box) is work,
    // not a loss. Only a loss is credited: a pass that added energy shows
    // in the balance.
    const double put_in = kinematicWork(c.a, h) + kinematicWork(c.b, h) - driven;
    flows.contact_loss += std::max(0.0, before + put_in - kineticEnergy(c.a) - kineticEnergy(c.b));
  }
}

void World::addKinematicWork(const Island& island, double start_s, double h, bool start_pairing, WorldEnergy& flows) {
  for (const BodyId id : island.bodies) {
    if (!bodies_[id].kinematic) continue;  // no work: kinematicWork's 0
    if (!start_pairing) {
      flows.kinematic_work += kinematicWork(id, h);
      continue;
    }
    // Under the start projection with its motion's velocity at the
    // substep's start, where addWork books a force (the middle's, which
    // integrate() moves it by, differs on a ramp or a swing).
    const MotionKeyframe m = motionAt(defs_[id].motion, start_s);
    const BodyState& b = bodies_[id];
    flows.kinematic_work -= (b.impulse.dot(m.velocity) + b.angular_impulse.dot(m.angular_velocity)) / h;
  }
}

void World::updateDrives(const std::vector<int>& hinges, const std::vector<int>& prismatics, double start_s,
                         double h) {
  // Released half a substep early, so that rounding in the time cannot keep a
  // drive one substep too long. A scheduled velocity is the ramp's value at
  // the substep's middle (its mean over the substep), a scheduled position
  // the value at its end (where the solve puts the joint): a ramp is then
  // followed exactly.
  const double middle = start_s + 0.5 * h, end = start_s + h;
  for (const int i : hinges) {
    HingeDrive& d = hinges_[i].drive;
    if (d.mode != HingeDrive::Mode::None && middle >= d.until) d = HingeDrive{};
    if (!d.schedule.empty()) d.target = scheduledTarget(d.schedule, d.mode == HingeDrive::Mode::Velocity ? middle : end);
  }
  for (const int i : prismatics) {
    PrismaticDrive& d = prismatics_[i].drive;
    if (d.mode != PrismaticDrive::Mode::None && middle >= d.until) d = PrismaticDrive{};
    if (!d.schedule.empty())
      d.target = scheduledTarget(d.schedule, d.mode == PrismaticDrive::Mode::Velocity ? middle : end);
  }
}

void World::integrate(const Island& island, double start_s, double h) {
  const Vec3 g = settings_.gravity;
  for (const BodyId id : island.bodies) {
    BodyState& b = bodies_[id];
    if (b.kinematic) {
      // Its motion's velocities at the substep's middle, so that a ramp
      // moves it by exactly the ramp's integral.
      const MotionKeyframe m = motionAt(defs_[id].motion, start_s + 0.5 * h);
      b.x_prev = b.x;
      b.q_prev = b.q;
      b.v = m.velocity;
      b.omega = m.angular_velocity;
      b.x += h * b.v;
      rotateExactly(b.q, h * b.omega);
      b.q_pred = b.q;
      continue;
    }
    if (!b.moves()) continue;
    // An applied torque's turn, where there is one (two rotations and a
    // product a body and substep where there is not).
    const bool torqued = !b.applied_torque.isZero();
    if (b.isRotor()) {  // no gravity, no gyroscopic torque: it turns about its axle
      b.x_prev = b.x;
      b.q_prev = b.q;
      // omega = u (u . omega), u the axle in the world, in scalars (math.h).
      const Scalars3 u = rotated(b.q, b.rotor_axis);
      const Vec3 w = torqued ? Vec3(b.omega + h * b.applyInvInertia(b.applied_torque)) : b.omega;
      const double spin = u.x * w.x() + u.y * w.y() + u.z * w.z();
      b.omega = Vec3(u.x * spin, u.y * spin, u.z * spin);
      rotateExactly(b.q, h * b.omega);
      b.q_pred = b.q;
      continue;
    }
    b.x_prev = b.x;
    b.v += h * (g + b.inv_mass * b.applied_force);
    b.x += h * b.v;
    b.q_prev = b.q;
    if (torqued) b.omega += h * b.applyInvInertia(b.applied_torque);
    b.omega = b.q * gyroscopicStep(b.inertia, b.q.conjugate() * b.omega, h);
    rotateExactly(b.q, h * b.omega);
    b.q_pred = b.q;
  }
}

void World::setThreads(int threads, double min_shared_run_us) {
  if (threads < 1) throw std::invalid_argument("World::setThreads: expected at least 1 thread, got " + std::to_string(threads));
  if (!std::isfinite(min_shared_run_us) || min_shared_run_us < 0.0)
    throw std::invalid_argument("World::setThreads: expected a finite minimum run >= 0 us, got " +
                                std::to_string(min_shared_run_us));
  min_shared_run_ns_ = 1e3 * min_shared_run_us;
  share_runs_ = min_shared_run_ns_ == 0.0;  // else as measured, from the next step
  if (threads == threads_) return;
  threads_ = threads;
  pool_.reset();          // started again by buildIslands() if there are islands to share
  thread_runs_.reset();   // made again for the threads by cutIslandRuns()
  islands_dirty_ = true;  // their runs (island_runs_) are cut for the threads
}

void World::solvePositions(double h, bool again) {
  beginSolve(h);
  forEachIsland([&](int i) { solveIsland(*islands_[i], h, again); });
  endSolve();
}

void World::beginSolve(double h) {
  poses_solved_ = true;
  // The braking inverse inertia (mass) is a drive's: a joint without one
  // does not read it.
  // Only islands with a drive are read (Island::driven): the others'
  // joints stay in their threads' caches.
  hinge_braking_.resize(hinges_.size());
  prismatic_braking_.resize(prismatics_.size());
  if (!gatherNews().driven) return solveLooseRows(h);
  for (const auto& island : islands_)
    if (island->driven) prepareBraking(*island);
  solveLooseRows(h);
}

void World::prepareBraking(const Island& island) {
  for (const int i : island.hinges)
    if (hinges_[i].drive.mode != HingeDrive::Mode::None) hinge_braking_[i] = brakingInverseInertia(island, i);
  for (const int i : island.prismatics)
    if (prismatics_[i].drive.mode != PrismaticDrive::Mode::None) prismatic_braking_[i] = brakingInverseMass(i);
}

void World::endSolve() {
  const RunNews news = gatherNews();
  last_iterations_ += news.iterations;
  interrupted_ |= news.interrupted;
}

void World::solveIsland(Island& island, double h, bool again) {
  // Static bodies take no impulses (BodyState::takesImpulses): theirs stay 0.
  for (const BodyId id : island.bodies) {
    BodyState& b = bodies_[id];
    b.impulse = b.angular_impulse = b.solve_turn = Vec3::Zero();
  }
  for (const int i : island.hinges) {
    HingeJoint& j = hinges_[i];
    prepareHingeJoint(j, body(j.a), body(j.b), h, hinge_braking_[i]);
  }
  for (const int i : island.prismatics) {
    PrismaticJoint& j = prismatics_[i];
    preparePrismaticJoint(j, body(j.a), body(j.b), h, prismatic_braking_[i]);
  }
  for (const int i : island.sphericals) prepareSphericalJoint(sphericals_[i]);
  for (const int i : island.fixeds) prepareFixedJoint(fixeds_[i]);
  const BodyTable table{bodies_.data(), &world_frame_};
  // The damping's dC is the length's change since the substep's start,
  // with the anchors the substep hook has just set.
  for (const int i : island.distances) {
    DistanceConstraint& c = distances_[i];
    c.lambda = 0.0;
    if (c.damping > 0.0) c.start_length = startLength(c, body(c.a), body(c.b));
  }
  for (const int i : island.paths) {
    PathConstraint& p = paths_[i];
    p.lambda = 0.0;
    if (p.damping > 0.0) p.start_length = pathStartLength(p, table) + p.fed;
  }
  island.iterations = 0;
  island.interrupted = false;
  // The solve itself: direct/direct_step.cpp, gauss_seidel/gauss_seidel.cpp.
  if (settings_.solver == SolverKind::Direct) solveDirect(island, h, again);
  else sweepGaussSeidel(island, h);
}

void World::solveLooseRows(double h) {
  const double inv_h2 = 1.0 / (h * h);
  const BodyTable table{bodies_.data(), &world_frame_};
  for (const int i : loose_distances_) {
    DistanceConstraint& c = distances_[i];
    c.lambda = 0.0;
    if (c.damping > 0.0) c.start_length = startLength(c, body(c.a), body(c.b));
  }
  for (const int i : loose_paths_) {
    PathConstraint& p = paths_[i];
    p.lambda = 0.0;
    if (p.damping > 0.0) p.start_length = pathStartLength(p, table) + p.fed;
  }
  // A rigid row with W = 0 does nothing; a compliant one is met in one
  // visit (its lambda -C / alpha~), which later visits keep.
  const bool direct = settings_.solver == SolverKind::Direct;
  for (int visit = 0; visit < (direct ? 1 : settings_.iterations); ++visit) {
    for (const int i : loose_distances_) {
      DistanceConstraint& c = distances_[i];
      if (!direct || (c.enabled && c.compliance > 0.0))
        solveDistanceConstraint(c, body(c.a), body(c.b), c.compliance * inv_h2, h);
    }
    for (const int i : loose_paths_) {
      PathConstraint& p = paths_[i];
      if (!direct || (p.enabled && p.compliance > 0.0)) solvePathConstraint(p, table, p.compliance * inv_h2, h);
    }
  }
}

void World::solvePositionsChecked(double h) {
  if (resolve_checks_.empty()) return solvePositions(h, false);
  SolveStart& start = solve_start_;
  start.x.resize(bodies_.size());
  start.q.resize(bodies_.size());
  for (size_t i = 0; i < bodies_.size(); ++i) {
    start.x[i] = bodies_[i].x;
    start.q[i] = bodies_[i].q;
  }
  start.hinge_spring.clear();
  for (const HingeJoint& j : hinges_) start.hinge_spring.push_back(j.spring_previous);
  start.prismatic_spring.clear();
  for (const PrismaticJoint& j : prismatics_) start.prismatic_spring.push_back(j.spring_previous);
  start.contacts = contacts_;
  start.manifolds = manifolds_;
  start.friction_pools = friction_pools_;
  solvePositions(h, false);
  for (int again = 0; again < kMaxResolves && !interrupted_; ++again) {
    bool changed = false;
    for (auto& check : resolve_checks_) changed |= check(*this, h);
    if (!changed) return;
    for (size_t i = 0; i < bodies_.size(); ++i) {
      bodies_[i].x = start.x[i];
      bodies_[i].q = start.q[i];
    }
    for (size_t i = 0; i < hinges_.size(); ++i) hinges_[i].spring_previous = start.hinge_spring[i];
    for (size_t i = 0; i < prismatics_.size(); ++i) prismatics_[i].spring_previous = start.prismatic_spring[i];
    contacts_ = start.contacts;
    manifolds_ = start.manifolds;  // the same size: the same storage, which support_groups_ point at
    friction_pools_ = start.friction_pools;
    solvePositions(h, true);
  }
}

void World::updateVelocities(const Island& island, double h, WorldEnergy& flows) {
  for (const BodyId id : island.bodies) {
    BodyState& b = bodies_[id];
    if (!b.moves()) continue;
    b.v = (b.x - b.x_prev) / h;
    // Not rotationVector(q q_prev^-1) / h, which is wrapped to half a turn
    // per substep: the integrated omega plus the solve's correction, that
    // too taken round as far as the solver turned the body (solve_turn).
    Vec3 correction = rotationVector(b.q * b.q_pred.conjugate());
    if (b.solve_turn.squaredNorm() > 0.25 * kPi * kPi) {
      const double turned = b.solve_turn.norm();
      const Vec3 n = b.solve_turn / turned;
      const double along = correction.dot(n);
      correction += n * (turned + wrapAngle(along - turned) - along);
    }
    b.omega += correction / h;
    if (b.linear_damping == 0.0 && b.angular_damping == 0.0) continue;
    const double before = kineticEnergy(id);
    b.v *= std::exp(-b.linear_damping * h);
    b.omega *= std::exp(-b.angular_damping * h);
    flows.damping_loss += std::max(0.0, before - kineticEnergy(id));
  }
}

void World::limitSpeeds(const Island& island) {
  if (std::isinf(settings_.max_linear_speed) && std::isinf(settings_.max_angular_speed)) return;  // the default
  for (const BodyId id : island.bodies) {
    BodyState& b = bodies_[id];
    if (const double v = b.v.norm(); v > settings_.max_linear_speed) b.v *= settings_.max_linear_speed / v;
    if (const double w = b.omega.norm(); w > settings_.max_angular_speed) b.omega *= settings_.max_angular_speed / w;
  }
}

const char* quantityName(NonFiniteState::Quantity quantity) {
  switch (quantity) {
    case NonFiniteState::Quantity::Position: return "position";
    case NonFiniteState::Quantity::Orientation: return "orientation";
    case NonFiniteState::Quantity::Velocity: return "velocity";
    case NonFiniteState::Quantity::AngularVelocity: return "angular velocity";
    case NonFiniteState::Quantity::Tension: return "tension";
  }
  return "?";
}

void World::findNonFinite(Island& island, const SubstepClock& clock, int pass, double h) const {
  using Q = NonFiniteState::Quantity;
  if (non_finite_ || island.non_finite) return;  // only the first is kept
  const double end_s = clock.time_s + h;
  const auto body = std::find_if(island.bodies.begin(), island.bodies.end(),
                                 [&](BodyId id) { return !finiteState(bodies_[id]); });
  if (body != island.bodies.end()) {
    const BodyState& b = bodies_[*body];
    const Q quantity = !b.x.allFinite()              ? Q::Position
                       : !b.q.coeffs().allFinite()   ? Q::Orientation
                       : !b.v.allFinite()            ? Q::Velocity
                                                     : Q::AngularVelocity;
    island.non_finite = NonFiniteFind{clock.substep, pass, *body, NonFiniteState{*body, kWorldBody, quantity, end_s}};
    return;
  }
  if (pass == 0) return;
  const auto row = std::find_if(island.distances.begin(), island.distances.end(),
                                [&](int i) { return !std::isfinite(distances_[i].lambda / (h * h)); });
  if (row == island.distances.end()) return;
  const DistanceConstraint& d = distances_[*row];
  island.non_finite =
      NonFiniteFind{clock.substep, pass, bodyCount() + *row, NonFiniteState{d.a, d.b, Q::Tension, end_s}};
}

void World::recordNonFinite() {
  std::optional<NonFiniteFind> first = std::exchange(non_finite_found_, std::nullopt);
  for (auto& island : islands_)
    if (island->non_finite) {
      if (!first || *island->non_finite < *first) first = island->non_finite;
      island->non_finite.reset();
    }
  if (first && !non_finite_) non_finite_ = first->state;
}

std::optional<BodyId> World::firstNonFiniteBody() const {
  for (BodyId id = 0; id < bodyCount(); ++id)
    if (!finiteState(bodies_[id])) return id;
  return std::nullopt;
}

}  // namespace reeve
