#include "reeve/engine/world.h"

#include <cassert>
#include <cmath>
#include <stdexcept>

namespace reeve {

World::World(SolverSettings settings) : settings_(settings) {}

BodyId World::addBody(const BodyDef& def) {
  bodies_.push_back(makeBodyState(def));
  defs_.push_back(def);
  return static_cast<BodyId>(bodies_.size() - 1);
}

void World::setMass(BodyId id, double mass) {
  BodyState& b = body(id);
  if (id == kWorldBody || b.inv_mass == 0.0 || !(mass > 0.0) || !std::isfinite(mass))
    throw std::invalid_argument("setMass: needs a dynamic body and a finite mass > 0 kg");
  const double scale = mass * b.inv_mass;
  b.inv_mass = 1.0 / mass;
  b.inertia *= scale;
  b.inv_inertia /= scale;
}

HingeId World::addHinge(const HingeDef& def) {
  const auto valid = [&](BodyId id) { return id == kWorldBody || (id >= 0 && id < bodyCount()); };
  if (!valid(def.body) || !valid(def.other) || def.body == def.other)
    throw std::invalid_argument("hinge: needs two different existing bodies");
  if (!(def.axis.norm() > 0.0)) throw std::invalid_argument("hinge: the axis must be a non-zero vector");
  hinges_.push_back(makeHingeJoint(def, body(def.body), body(def.other)));
  return static_cast<HingeId>(hinges_.size() - 1);
}

DistanceId World::addDistance(const DistanceConstraint& c) {
  assert(c.a >= kWorldBody && c.a < bodyCount() && c.b >= kWorldBody && c.b < bodyCount());
  distances_.push_back(c);
  return static_cast<DistanceId>(distances_.size() - 1);
}

PathId World::addPath(PathConstraint path) {
  assert(path.points.size() >= 2);
  paths_.push_back(std::move(path));
  return static_cast<PathId>(paths_.size() - 1);
}

double World::pathTension(PathId id) const {
  const PathConstraint& p = paths_[id];
  return p.enabled && last_h_ > 0.0 ? -p.lambda / (last_h_ * last_h_) : 0.0;
}

double World::pathLength(PathId id) const {
  const std::vector<PathPoint>& points = paths_[id].points;
  double length = 0.0;
  for (size_t i = 0; i + 1 < points.size(); ++i)
    length += (worldPoint(points[i + 1].body, points[i + 1].local) -
               worldPoint(points[i].body, points[i].local)).norm();
  return length;
}

void World::addSubstepHook(SubstepHook hook) { hooks_.push_back(std::move(hook)); }

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
  const double h = dt / settings_.substeps;
  for (int s = 0; s < settings_.substeps; ++s) {
    integrate(h);
    for (auto& hook : hooks_) hook(*this, h);
    solvePositions(h);
    updateVelocities(h);
    time_ += h;
  }
  last_h_ = h;
}

void World::integrate(double h) {
  const Vec3 g = settings_.gravity;
  for (BodyState& b : bodies_) {
    if (b.inv_mass == 0.0) continue;
    b.x_prev = b.x;
    b.v += h * g;
    b.x += h * b.v;
    b.q_prev = b.q;
    // Gyroscopic term, body frame: w += h I^-1 (-w x I w).
    Vec3 w = b.q.conjugate() * b.omega;
    w += h * b.inv_inertia.cwiseProduct(-w.cross(b.inertia.cwiseProduct(w)));
    b.omega = b.q * w;
    rotateExactly(b.q, h * b.omega);
  }
}

void World::solvePositions(double h) {
  const double inv_h2 = 1.0 / (h * h);
  for (HingeJoint& j : hinges_) {
    j.lambda_point = j.lambda_axis = 0.0;
    j.impulse_point.setZero();
    j.impulse_axis.setZero();
  }
  for (DistanceConstraint& c : distances_) c.lambda = 0.0;
  for (PathConstraint& p : paths_) p.lambda = 0.0;
  const BodyTable table{bodies_.data(), &world_frame_};
  for (int it = 0; it < settings_.iterations; ++it) {
    for (HingeJoint& j : hinges_)
      solveHingeJoint(j, body(j.a), body(j.b), j.compliance * inv_h2);
    for (DistanceConstraint& c : distances_)
      solveDistanceConstraint(c, body(c.a), body(c.b), c.compliance * inv_h2);
    for (PathConstraint& p : paths_) solvePathConstraint(p, table, p.compliance * inv_h2);
  }
}

void World::updateVelocities(double h) {
  for (BodyState& b : bodies_) {
    if (b.inv_mass == 0.0) continue;
    b.v = (b.x - b.x_prev) / h;
    b.omega = rotationVector(b.q * b.q_prev.conjugate()) / h;
    b.v *= std::exp(-b.linear_damping * h);
    b.omega *= std::exp(-b.angular_damping * h);
  }
}

}  // namespace reeve
