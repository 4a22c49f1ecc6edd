// The World's side of the energy ledger (energy.h; DESIGN.md, "Energy
// ledger").
#include <algorithm>
#include <cmath>

#include "island.h"
#include "reeve/engine/world.h"

namespace reeve {
namespace {

// alpha |F|^2 / 2 + alpha |tau|^2 / 2 of a compliant joint whose rows gave
// body a the impulse `linear` (kg m) and angular impulse `angular` (kg m^2)
// over a substep of h s (a joint's compliance is m/N and rad/(N m) alike).
double jointElastic(double compliance, const Vec3& linear, const Vec3& angular, double h) {
  if (compliance == 0.0 || h == 0.0) return 0.0;
  const double h2 = h * h;
  return 0.5 * compliance * ((linear / h2).squaredNorm() + (angular / h2).squaredNorm());
}

// C^2 / (2 alpha) of a compliant length row stretched by C (m) past its
// rest length, of compliance alpha (m/N): from the poses, not the last
// lambda, so a cable that starts stretched holds its energy from the start.
double stretchElastic(double compliance, double stretch, bool unilateral) {
  if (compliance == 0.0 || (unilateral && stretch <= 0.0)) return 0.0;
  return 0.5 * stretch * stretch / compliance;
}

// What a damped row of compliance alpha (m/N) took out over a substep of h
// s: its tension beyond the spring's (N), -lambda / h^2 - C / alpha, times
// the length's change dL (m). A converged row pulls with C / alpha + beta
// dL / h, so this is beta dL^2 / h; a pull-only row the clamp released
// while it shortened gives up its spring's energy to nothing, also counted.
// Only a loss is credited.
double dampingLoss(double compliance, double lambda, double stretch, bool unilateral, double dL, double h) {
  const double spring = unilateral ? std::max(0.0, stretch) / compliance : stretch / compliance;
  return std::max(0.0, (-lambda / (h * h) - spring) * dL);
}

}  // namespace

void addFlows(WorldEnergy& to, const WorldEnergy& from) {
  to.drive_work += from.drive_work;
  to.load_work += from.load_work;
  to.kinematic_work += from.kinematic_work;
  to.damping_loss += from.damping_loss;
  to.contact_loss += from.contact_loss;
  to.cable_damping_loss += from.cable_damping_loss;
}

double World::kineticEnergy(BodyId id) const {
  if (id == kWorldBody) return 0.0;
  const BodyState& b = bodies_[id];
  const Vec3 w = b.q.conjugate() * b.omega;  // body-local, where the inertia is
  return 0.5 * mass_[id] * b.v.squaredNorm() + 0.5 * w.dot(b.inertia * w);
}

bool World::pairsAtStart() const {
  return settings_.solver == SolverKind::Direct && settings_.projection == Projection::Start;
}

double World::ledgerLag() const { return pairsAtStart() ? 0.5 * last_h_ : 0.0; }

WorldEnergy World::energy() const {
  // Under the start projection the step is symplectic (position Verlet with
  // SHAKE), and its velocity v = (x - x_prev) / h is the half step's: it
  // pairs with the potential half a step back, at x - v h / 2 (for a free
  // fall the pair is then exact; with the end's height a swing's energy
  // ripples by h omega / 2), and the flows are booked to match (addWork).
  // The end projection keeps the end pairing, for which its closed forms
  // are derived.
  const double back = ledgerLag();
  WorldEnergy e = flows_;
  for (const auto& island : islands_) addFlows(e, island->flows);  // in island order
  const double h = last_h_;
  for (BodyId id = 0; id < bodyCount(); ++id) {
    if (mass_[id] == 0.0) continue;
    e.kinetic += kineticEnergy(id);
    e.gravity -= mass_[id] * settings_.gravity.dot(bodies_[id].x - back * bodies_[id].v);
  }
  for (const DistanceConstraint& c : distances_)
    if (c.enabled)
      e.elastic += stretchElastic(c.compliance, currentLength(c, body(c.a), body(c.b)) - c.rest_length, c.unilateral);
  for (PathId id = 0; id < pathCount(); ++id) {
    const PathConstraint& p = paths_[id];
    // A capped path (a winch's pull, a breaking tension) is a spring in
    // series with a clutch that slips at the cap: its spring stretches no
    // more than compliance x cap; the rest is slip (a stall to pay out).
    if (!p.enabled) continue;
    const double stretch = pathLength(id) - p.rest_length;
    e.elastic += stretchElastic(
        p.compliance, std::isfinite(p.max_tension) ? std::min(stretch, p.compliance * p.max_tension) : stretch, true);
  }
  for (HingeId id = 0; id < static_cast<HingeId>(hinges_.size()); ++id) {
    const HingeJoint& j = hinges_[id];
    e.elastic += jointElastic(j.compliance, j.impulse_point, j.impulse_axis, h);
    if (j.drive.mode == HingeDrive::Mode::Angle && j.drive.stiffness > 0.0) {
      const double error = hingeAngle(id) - j.drive.target;  // through whole turns
      e.elastic += 0.5 * j.drive.stiffness * error * error;
    }
  }
  for (PrismaticId id = 0; id < static_cast<PrismaticId>(prismatics_.size()); ++id) {
    const PrismaticJoint& j = prismatics_[id];
    e.elastic += jointElastic(j.compliance, j.impulse_linear, j.impulse_angular, h);
    if (j.drive.mode == PrismaticDrive::Mode::Position && j.drive.stiffness > 0.0) {
      const double error = prismaticSlide(id) - j.drive.target;
      e.elastic += 0.5 * j.drive.stiffness * error * error;
    }
  }
  for (const SphericalJoint& j : sphericals_)
    e.elastic += jointElastic(j.compliance, j.impulse_linear, j.impulse_angular, h);
  for (const FixedJoint& j : fixeds_)
    e.elastic += jointElastic(j.compliance, j.impulse_linear, j.impulse_angular, h);
  return e;
}

double World::kinematicWork(BodyId id, double h) const {
  if (id == kWorldBody || !bodies_[id].kinematic) return 0.0;
  const BodyState& b = bodies_[id];
  return -(b.impulse.dot(b.v) + b.angular_impulse.dot(b.omega)) / h;
}

void World::addWork(const Island& island, double h, bool start, WorldEnergy& flows) {
  const double inv_h2 = 1.0 / (h * h);
  // Under the start projection a force acts at the substep's start (SHAKE's
  // kick at x_n), where the velocity is (v_n-1/2 + v_n+1/2) / 2: its work
  // over the substep is F . that h, the pairing the potential read at
  // x - v h / 2 gives gravity (a constant load then balances exactly). The
  // end projection books F over the substep's motion, v_n+1/2 h.
  const auto omega = [&](BodyId id) -> Vec3 {
    if (id == kWorldBody) return Vec3::Zero();
    return start ? 0.5 * (bodies_[id].omega + pre_omega_[id]) : bodies_[id].omega;
  };
  // A motor drive's torque (lambda_drive / h^2, on a about the axis) times
  // the turn of a relative to b over the substep, (w_a - w_b) . u h: the
  // velocities are those the positions gave, whole turns and all.
  for (const int i : island.hinges) {
    const HingeJoint& j = hinges_[i];
    if (j.drive.mode == HingeDrive::Mode::None || j.drive.stiffness > 0.0 || j.angle.lambda_drive == 0.0) continue;
    const Vec3 u = (body(j.a).q * j.frame.axis_a).normalized();
    flows.drive_work += j.angle.lambda_drive * inv_h2 * (omega(j.a) - omega(j.b)).dot(u) * h;
  }
  for (const PrismaticId id : island.prismatics) {
    const PrismaticJoint& j = prismatics_[id];
    if (j.drive.mode == PrismaticDrive::Mode::None || j.drive.stiffness > 0.0 || j.slide.lambda_drive == 0.0) continue;
    double slid = prismaticSlide(id) - j.slide.start;
    if (start) {  // and the slide over the substep before, from the poses one substep back at v_n-1/2
      const auto back = [&](BodyId b, Vec3& x, Quat& q) {
        const BodyState& s = body(b);
        if (b == kWorldBody || !(s.moves() || s.kinematic)) {  // static: x_prev is not kept
          x = s.x, q = s.q;
          return;
        }
        x = s.x_prev - h * pre_v_[b], q = s.q_prev;
        rotateExactly(q, -h * pre_omega_[b]);
      };
      Vec3 x_a, x_b;
      Quat q_a, q_b;
      back(j.a, x_a, q_a);
      back(j.b, x_b, q_b);
      slid = 0.5 * (slid + j.slide.start - reeve::prismaticSlide(j, x_a, q_a, x_b, q_b));
    }
    flows.drive_work += j.slide.lambda_drive * inv_h2 * slid;
  }
  for (const BodyId id : island.bodies) {
    const BodyState& b = bodies_[id];
    if (!b.moves()) continue;
    const Vec3 moved = start ? 0.5 * h * (b.v + pre_v_[id]) : Vec3(b.x - b.x_prev);
    if (b.applied_force.squaredNorm() > 0.0) flows.load_work += b.applied_force.dot(moved);
    if (b.applied_torque.squaredNorm() > 0.0) flows.load_work += b.applied_torque.dot(omega(id)) * h;
  }
}

void World::addConstraintDampingLoss(const std::vector<int>& distances, const std::vector<int>& paths, double h,
                                     WorldEnergy& flows) {
  for (const int i : distances) {
    const DistanceConstraint& c = distances_[i];
    if (!c.enabled || c.damping == 0.0 || c.compliance == 0.0) continue;
    const double length = currentLength(c, body(c.a), body(c.b));
    flows.cable_damping_loss +=
        dampingLoss(c.compliance, c.lambda, length - c.rest_length, c.unilateral, length - c.start_length, h);
  }
  for (const int i : paths) {
    const PathConstraint& p = paths_[i];
    if (!p.enabled || p.damping == 0.0 || p.compliance == 0.0) continue;
    const double length = pathLength(i);
    flows.cable_damping_loss +=
        dampingLoss(p.compliance, p.lambda, length - p.rest_length, true, length - p.start_length, h);
  }
}

}  // namespace reeve
