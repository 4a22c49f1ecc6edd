#include "direct_solver.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <Eigen/OrderingMethods>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>

#include "joint_row_sets.h"
#include "reeve/engine/correction.h"
#include "reeve/engine/world.h"

namespace reeve {
namespace {

using joint_rows::JointRowSet;
using joint_rows::kInf;
using joint_rows::Vec6;

// A pivot this small against the terms it is the difference of marks a row
// that depends on earlier ones (sparse_ldlt.h): rounding leaves such a
// pivot near 1e-16 of them (the last span of a belt over rotors, however
// uneven their masses). A light wheel between heavy loads leaves the ratio
// of their masses: 1e-6 for a 1e-6 kg wheel under 1 kg loads, 5e-13 for a
// 1e-9 kg wheel under 1000 kg, both kept.
constexpr double kDropTolerance = 1e-13;
constexpr double kRoundingPivot = 1e-15;
// Active-set passes per iteration; almost always one or two are enough.
constexpr int kMaxPasses = 8;
// A body with more rows than this is a hub (direct_solver.h): its rows
// would fill more of the matrix than its own motion does. So is one with
// more cable spans than this that move it alone (leaves): four cables to
// one point are already redundant, which a hub's leaves resolve by the
// least norm (leastNormLeaves) and the rows' matrix cannot.
constexpr int kHubRows = 12;
constexpr int kHubCableLeaves = 3;
// delta (direct_solver.h) of a row on a hub, relative to its hub part of
// J W J^T, and for a leaf times its hub's leaf count (K leaves share its
// load). It only has to lift pivots above rounding; the refinement takes
// the error from delta to delta^2 a step, slowly where the system's own
// scale is below delta: at 1e-5 the hand's 3 g knuckles under a kilonewton
// tendon were not converged after four steps, at 2e-6 and below they
// are. Rounding in a rigid redundant row's value (1e-16 m) becomes a
// tension of 1e-16 m / (delta h^2); leastNormLeaves removes it from a
// hub's leaves (a rigid star of 4096 cables: 8e-6 of the closed form at
// 10 x 2 at any delta from 1e-6 to 1e-5, where before it grew with K).
constexpr double kHubRegularization = 1e-6;
// Refinement steps at most per solve (factorAndSolve).
constexpr int kMaxRefinements = 4;

// The number of rows of a joint with `bilateral` locked rows and the
// given drive and limits (JointRowSet's layout).
int jointRowCount(int bilateral, bool driven, bool limited) { return bilateral + (driven ? 1 : 0) + (limited ? 2 : 0); }

bool moves(const World& world, BodyId id) { return world.body(id).moves(); }
// A row lists the bodies it moves and the kinematic ones it pushes on: a
// kinematic body's entries weigh nothing (W = 0) and couple no rows, but
// record the impulse it took (the work it does: World::addKinematicWork).
bool listed(const World& world, BodyId id) { return moves(world, id) || world.body(id).kinematic; }

}  // namespace

void DirectSolver::describe(World& world, std::vector<int>& sig) const {
  sig.clear();
  const auto joint = [&](Source source, int index, BodyId a, BodyId b, int rows) {
    if (!moves(world, a) && !moves(world, b)) return;
    sig.insert(sig.end(), {static_cast<int>(source), index, rows, listed(world, a) ? a : kWorldBody,
                           listed(world, b) ? b : kWorldBody});
  };
  for (int i = 0; i < static_cast<int>(world.hinges().size()); ++i) {
    const HingeJoint& j = world.hinges()[i];
    const bool rotor = world.body(j.a).isRotor() || world.body(j.b).isRotor();
    joint(Source::Hinge, i, j.a, j.b,
          jointRowCount(rotor ? 0 : 5, j.drive.mode != HingeDrive::Mode::None, j.limit.enabled));
  }
  for (int i = 0; i < static_cast<int>(world.prismatics().size()); ++i) {
    const PrismaticJoint& j = world.prismatics()[i];
    joint(Source::Prismatic, i, j.a, j.b,
          jointRowCount(5, j.drive.mode != PrismaticDrive::Mode::None, j.limit.enabled));
  }
  for (int i = 0; i < static_cast<int>(world.sphericals().size()); ++i) {
    const SphericalJoint& j = world.sphericals()[i];
    joint(Source::Spherical, i, j.a, j.b,
          jointRowCount(3, false, j.twist_limit.enabled) + (j.swing_limit.enabled ? 1 : 0));
  }
  for (int i = 0; i < static_cast<int>(world.fixedJoints().size()); ++i) {
    const FixedJoint& j = world.fixedJoints()[i];
    joint(Source::Fixed, i, j.a, j.b, 6);
  }
  for (int i = 0; i < world.distanceCount(); ++i) {
    const DistanceConstraint& c = world.distance(i);
    if (c.enabled) joint(Source::Distance, i, c.a, c.b, 1);
  }
  for (int i = 0; i < world.pathCount(); ++i) {
    const PathConstraint& p = world.path(i);
    if (!p.enabled || !p.weights.empty()) continue;  // weighted paths: World::solvePositions
    const std::size_t head = sig.size();
    sig.insert(sig.end(), {static_cast<int>(Source::Path), i, 1});
    for (const PathPoint& point : p.points)
      if (listed(world, point.body) && std::find(sig.begin() + head + 3, sig.end(), point.body) == sig.end())
        sig.push_back(point.body);
    if (std::none_of(sig.begin() + head + 3, sig.end(), [&](int id) { return moves(world, id); })) {
      sig.resize(head);  // nothing in it moves
      continue;
    }
    sig.insert(sig.begin() + head + 3, static_cast<int>(sig.size() - head - 3));  // body count
  }
}

void DirectSolver::build(World& world) {
  // Rows and their entries from the signature, joints as [source, index,
  // rows, a, b] (kWorldBody for a body that does not move), paths as
  // [source, index, 1, count, bodies...].
  rows_.clear();
  entries_.clear();
  bodies_.clear();
  body_index_.assign(world.bodyCount(), -1);
  const auto bodyIndex = [&](BodyId id) {
    if (body_index_[id] < 0) {
      body_index_[id] = static_cast<int>(bodies_.size());
      bodies_.push_back(id);
    }
    return body_index_[id];
  };
  for (std::size_t k = 0; k < signature_.size();) {
    const auto source = static_cast<Source>(signature_[k]);
    const int index = signature_[k + 1], count = signature_[k + 2];
    std::vector<BodyId> moving;
    if (source == Source::Path) {
      moving.assign(signature_.begin() + k + 4, signature_.begin() + k + 4 + signature_[k + 3]);
      k += 4 + signature_[k + 3];
    } else {
      for (const BodyId id : {signature_[k + 3], signature_[k + 4]})
        if (id != kWorldBody) moving.push_back(id);
      k += 5;
    }
    for (int r = 0; r < count; ++r) {
      Row row{source, index, static_cast<int>(entries_.size()), static_cast<int>(moving.size()), 0, 0, 0, 0};
      for (const BodyId id : moving) {
        Entry e;
        e.body = bodyIndex(id);
        e.row = static_cast<int>(rows_.size());
        entries_.push_back(e);
      }
      rows_.push_back(row);
    }
  }
  const int n = static_cast<int>(rows_.size());
  // The moving bodies' rows; a body with many is a hub, its motion an
  // unknown after the rows.
  std::vector<std::vector<int>> on_body(bodies_.size());
  for (int r = 0; r < n; ++r)
    for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e)
      if (!world.body(bodies_[entries_[e].body]).kinematic) on_body[entries_[e].body].push_back(e);
  hubs_.clear();
  hub_of_.assign(bodies_.size(), -1);
  int unknowns = n;
  std::vector<int> moving(n, 0);  // per row: its moving bodies
  for (const auto& list : on_body)
    for (const int e : list) ++moving[entries_[e].row];
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    int cable_leaves = 0;
    for (const int e : on_body[b]) {
      const Source source = rows_[entries_[e].row].source;
      cable_leaves += moving[entries_[e].row] == 1 && (source == Source::Path || source == Source::Distance);
    }
    if (static_cast<int>(on_body[b].size()) <= kHubRows && cable_leaves <= kHubCableLeaves) continue;
    const int dofs = world.body(bodies_[b]).isRotor() ? 1 : 6;
    hub_of_[b] = static_cast<int>(hubs_.size());
    hubs_.push_back({static_cast<int>(b), dofs, unknowns, 0});
    unknowns += dofs;
  }
  // Rows that share a moving body that is not a hub are coupled; a hub's
  // rows are coupled to its motion, and its motion within itself. Order
  // them all to keep the factor sparse (approximate minimum degree).
  std::vector<Eigen::Triplet<double>> triplets;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const auto& list = on_body[b];
    if (hub_of_[b] < 0) {
      for (const int e1 : list)
        for (const int e2 : list) triplets.emplace_back(entries_[e1].row, entries_[e2].row, 1.0);
      continue;
    }
    const Hub& hub = hubs_[hub_of_[b]];
    for (const int e : list)
      for (int d = 0; d < hub.dofs; ++d) {
        triplets.emplace_back(entries_[e].row, hub.first + d, 1.0);
        triplets.emplace_back(hub.first + d, entries_[e].row, 1.0);
      }
    for (int i = 0; i < hub.dofs; ++i)
      for (int j = 0; j < hub.dofs; ++j) triplets.emplace_back(hub.first + i, hub.first + j, 1.0);
  }
  Eigen::SparseMatrix<double> pattern(unknowns, unknowns);
  pattern.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::AMDOrdering<int> amd;
  Eigen::AMDOrdering<int>::PermutationType order;
  amd(pattern, order);  // order.indices()[k]: the unknown eliminated k-th
  // The rows first, the hubs after them all: then a hub's block is -M_h -
  // J_h^T S^-1 J_h, negative terms only (S, the rows' block, is positive
  // definite), whatever the masses. AMD puts hubs last or nearly anyway
  // (the same cost on the scaling bench), but a light hub eliminated before
  // its rows would add its -M (1e-6 kg m^2 for a knuckle) to J W J^T of
  // 1e6 and lose it.
  std::vector<int> sequence(order.indices().data(), order.indices().data() + unknowns);
  std::stable_partition(sequence.begin(), sequence.end(), [n](int u) { return u < n; });
  position_.assign(unknowns, 0);
  for (int k = 0; k < unknowns; ++k) position_[sequence[k]] = k;
  for (int r = 0; r < n; ++r) rows_[r].position = position_[r];
  // One matrix term per pair of entries on a body, per entry on a hub and
  // dof, and per pair of a hub's dofs.
  pairs_.clear();
  couplings_.clear();
  mass_slots_.clear();
  std::vector<std::pair<int, int>> upper;
  const auto add = [&](int u1, int u2) {
    const int p = position_[u1], q = position_[u2];
    upper.emplace_back(std::min(p, q), std::max(p, q));
  };
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const auto& list = on_body[b];
    if (hub_of_[b] >= 0) continue;
    for (std::size_t i = 0; i < list.size(); ++i)
      for (std::size_t j = i; j < list.size(); ++j) {
        pairs_.push_back({list[i], list[j], 0});
        add(entries_[list[i]].row, entries_[list[j]].row);
      }
  }
  for (int h = 0; h < static_cast<int>(hubs_.size()); ++h)
    for (const int e : on_body[hubs_[h].body])
      for (int d = 0; d < hubs_[h].dofs; ++d) {
        couplings_.push_back({e, h, d, 0});
        add(entries_[e].row, hubs_[h].first + d);
      }
  for (int h = 0; h < static_cast<int>(hubs_.size()); ++h) {
    const Hub& hub = hubs_[h];
    for (int i = 0; i < hub.dofs; ++i)
      for (int j = i; j < hub.dofs; ++j) {
        mass_slots_.push_back({h, i, j, 0});
        add(hub.first + i, hub.first + j);
      }
  }
  for (int r = 0; r < n; ++r) add(r, r);  // a row on hubs alone has no pair
  const std::vector<int> slot = ldlt_.analyze(unknowns, upper);
  std::vector<char> negative(unknowns, 0);
  for (const Hub& hub : hubs_)
    for (int d = 0; d < hub.dofs; ++d) negative[position_[hub.first + d]] = 1;
  ldlt_.setNegativePivots(std::move(negative));
  for (Row& row : rows_) row.diagonal = ldlt_.diagonalSlot(row.position);
  std::vector<std::vector<Slot>> coupled(n);
  std::size_t next = 0;
  for (Pair& pair : pairs_) {
    pair.slot = slot[next++];
    const int r1 = entries_[pair.e1].row, r2 = entries_[pair.e2].row;
    if (r1 == r2) continue;
    coupled[r1].push_back({pair.slot, r2});
    coupled[r2].push_back({pair.slot, r1});
  }
  for (Coupling& c : couplings_) {
    c.slot = slot[next++];
    coupled[entries_[c.entry].row].push_back({c.slot, hubs_[c.hub].first + c.dof});
  }
  for (MassSlot& m : mass_slots_) m.slot = slot[next++];
  // A hub's leaves: rows that move it alone (the other end static or
  // kinematic), which share its load side by side.
  leaf_entries_.clear();
  for (Hub& hub : hubs_) {
    hub.first_leaf = static_cast<int>(leaf_entries_.size());
    for (const int e : on_body[hub.body])
      if (moving[entries_[e].row] == 1) leaf_entries_.push_back(e);
    hub.leaves = static_cast<int>(leaf_entries_.size()) - hub.first_leaf;
  }
  slots_.clear();
  for (int r = 0; r < n; ++r) {
    auto& list = coupled[r];
    std::sort(list.begin(), list.end(), [](const Slot& x, const Slot& y) { return x.value < y.value; });
    list.erase(std::unique(list.begin(), list.end(), [](const Slot& x, const Slot& y) { return x.value == y.value; }),
               list.end());
    rows_[r].slots_begin = static_cast<int>(slots_.size());
    slots_.insert(slots_.end(), list.begin(), list.end());
    rows_[r].slots_end = static_cast<int>(slots_.size());
  }
  for (std::vector<double>* v : {&C_, &alpha_, &lo_, &hi_, &lambda_, &dlambda_, &delta_, &length_}) v->assign(n, 0.0);
  for (std::vector<double>* v : {&x_, &rhs_}) v->assign(unknowns, 0.0);
  hub_motion_.assign(unknowns - n, 0.0);
  hub_inertia_.assign(hubs_.size(), Mat3::Zero());
  keep_.assign(unknowns, 0);
  state_.assign(n, State::Free);
  pulled_.assign(n, false);
  drive_of_.assign(n, -1);
  mirror_.assign(n, nullptr);
  dir_.assign(n, Vec6::Zero());
  linear_a_.assign(n, nullptr);
  angular_a_.assign(n, nullptr);
  full_.assign(ldlt_.values().size(), 0.0);
  const std::size_t m = bodies_.size();
  frames_.assign(m, BodyFrame{});
  dx_.assign(m, Vec3::Zero());
  dphi_.assign(m, Vec3::Zero());
}

void DirectSolver::prepare(World& world, double h, bool again) {
  describe(world, scratch_);
  if (scratch_ != signature_) {
    signature_ = scratch_;  // a copy: scratch_ keeps its capacity for the next substeps
    build(world);
  }
  // What stays put over the substep: inverse masses, rotors' axles (they
  // turn about them), and the paths' bounds and lambdas (their compliance
  // term with their value, evaluatePath: damping changes it).
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    BodyState& b = world.body(bodies_[i]);
    BodyFrame& f = frames_[i];
    f.state = &b;  // the World's bodies stay where they are while it steps
    f.inv_mass = b.inv_mass;
    f.inv_axial = b.isRotor() ? b.rotor_axis.dot(b.inv_inertia * b.rotor_axis) : 0.0;
    f.axle = b.q * b.rotor_axis;
  }
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const Row& row = rows_[r];
    if (row.source != Source::Path && row.source != Source::Distance) continue;
    bool unilateral = true;
    lo_[r] = -kInf;
    if (row.source == Source::Path) {
      PathConstraint& p = world.path(row.index);
      mirror_[r] = &p.lambda;
      if (std::isfinite(p.max_tension)) lo_[r] = -p.max_tension * h * h;  // a winch's pull, at most
    } else {
      DistanceConstraint& c = world.distance(row.index);
      mirror_[r] = &c.lambda;
      unilateral = c.unilateral;
    }
    hi_[r] = unilateral ? 0.0 : kInf;
    linear_a_[r] = angular_a_[r] = nullptr;
  }
  // A cable that pulled at the end of the last substep starts this one in
  // the active set, even if it is exactly taut (C = 0) after integration:
  // otherwise a long taut cable would join in one span per pass.
  if (!again)
    for (std::size_t r = 0; r < rows_.size(); ++r) pulled_[r] = lambda_[r] < 0.0;
  std::fill(lambda_.begin(), lambda_.end(), 0.0);
}

void DirectSolver::evaluateBodies() {
  for (BodyFrame& f : frames_) {
    const BodyState& b = *f.state;
    f.R = b.q.toRotationMatrix();
    if (f.inv_axial == 0.0) f.inv_inertia = f.R * b.inv_inertia * f.R.transpose();
  }
}

void DirectSolver::weigh(Entry& e) const {
  // W J: a rotor's angular part is u u^T / I_u (prepare()).
  const BodyFrame& f = frames_[e.body];
  e.wlin = f.inv_mass * e.lin;
  e.wang = f.inv_axial > 0.0 ? Vec3(f.axle * (f.inv_axial * f.axle.dot(e.ang))) : Vec3(f.inv_inertia * e.ang);
}

SolvePoint DirectSolver::endPoint(const World& world, const PathPoint& point, int slot) const {
  if (point.roll_axis.isZero()) {
    SolvePoint p;
    p.arm = slot >= 0 ? Vec3(frames_[slot].R * point.local) : Vec3(world.body(point.body).q * point.local);
    return p;
  }
  return solvePoint(world.body(point.body), point, true);
}

void DirectSolver::evaluateSpan(const World& world, int r, const PathPoint& p0, const PathPoint& p1) {
  // A plain span: C = |p1 - p0| - rest, gradient -u at p0 and u at p1.
  const Row& row = rows_[r];
  const int s0 = p0.body == kWorldBody ? -1 : body_index_[p0.body];
  const int s1 = p1.body == kWorldBody ? -1 : body_index_[p1.body];
  const SolvePoint e0 = endPoint(world, p0, s0), e1 = endPoint(world, p1, s1);
  const Vec3 &a0 = e0.arm, &a1 = e1.arm;
  const Vec3& x0 = s0 >= 0 ? frames_[s0].state->x : world.body(p0.body).x;
  const Vec3& x1 = s1 >= 0 ? frames_[s1].state->x : world.body(p1.body).x;
  const Vec3 d = (x1 + a1) - (x0 + a0);
  const double l = d.norm();
  const Vec3 u = l >= 1e-12 ? Vec3(d / l) : Vec3::Zero();
  int e = row.first_entry;
  if (s0 >= 0) {
    entries_[e].lin = -u;
    entries_[e].ang = u.cross(a0);
    ++e;
  }
  if (s1 >= 0) {
    if (s1 == s0) {  // both ends on one body
      entries_[e - 1].lin.setZero();
      entries_[e - 1].ang += a1.cross(u);
    } else {
      entries_[e].lin = u;
      entries_[e].ang = a1.cross(u);
    }
  }
  for (e = row.first_entry; e < row.first_entry + row.entry_count; ++e) weigh(entries_[e]);
  C_[r] = l + e0.payOut(-u) + e1.payOut(u);  // minus the rest length, by the caller
}

void DirectSolver::evaluatePath(const World& world, int r, double h) {
  // C = sum of segment lengths - rest, dC/dp_i = u_{i-1} - u_i (a distance
  // constraint is a two-point path, pull-only if unilateral).
  const Row& row = rows_[r];
  double compliance, damping, start_length;
  if (row.source == Source::Path) {
    const PathConstraint& p = world.path(row.index);
    if (p.points.size() == 2) evaluateSpan(world, r, p.points[0], p.points[1]);
    else evaluateRun(world, r, p.points.data(), p.points.size());
    length_[r] = C_[r];
    C_[r] -= p.rest_length;
    compliance = p.compliance, damping = p.damping, start_length = p.start_length - p.rest_length;
  } else {
    const DistanceConstraint& c = world.distance(row.index);
    evaluateSpan(world, r, PathPoint{c.a, c.local_a}, PathPoint{c.b, c.local_b});
    length_[r] = C_[r];
    C_[r] -= c.rest_length;
    compliance = c.compliance, damping = c.damping, start_length = c.start_length - c.rest_length;
  }
  // Taut (C >= 0: a cable exactly at its rest length touches too), or
  // already pulling: in the active set.
  const bool unilateral = hi_[r] == 0.0;
  state_[r] = !unilateral || C_[r] >= 0.0 || lambda_[r] < 0.0 || pulled_[r] ? State::Free : State::Off;
  // Damping (correction.h: dampedRow) on a row in the set, as Gauss-Seidel
  // damps a row taut or pulling; its gradient is C's, so the system keeps
  // its matrix J W J^T and only C and alpha~ change. start_length is the
  // start's C here: dC = C - (start length - rest length).
  const double alpha_tilde = compliance / (h * h);
  if (damping == 0.0 || state_[r] != State::Free) {
    alpha_[r] = alpha_tilde;
    return;
  }
  const DampedRow damped = dampedRow(C_[r], alpha_tilde, alpha_tilde * h * damping, C_[r] - start_length);
  C_[r] = damped.C;
  alpha_[r] = damped.alpha_tilde;
}

void DirectSolver::evaluateRun(const World& world, int r, const PathPoint* points, std::size_t count) {
  // A run through pinholes: a body holding several points gets the sum of
  // their gradients.
  const Row& row = rows_[r];
  if (run_.arm.size() < count) {  // grown to the longest path, then kept
    run_.arm.resize(count);
    run_.pos.resize(count);
    run_.entry.resize(count);
  }
  std::vector<Vec3>&arm = run_.arm, &pos = run_.pos;
  std::vector<int>& entry = run_.entry;
  SolvePoint ends[2];
  for (std::size_t i = 0; i < count; ++i) {
    const BodyId id = points[i].body;
    const int slot = id == kWorldBody ? -1 : body_index_[id];
    const SolvePoint p = endPoint(world, points[i], slot);
    if (i == 0 || i + 1 == count) ends[i == 0 ? 0 : 1] = p;  // rolling ends are a run's ends
    arm[i] = p.arm;
    pos[i] = world.body(id).x + arm[i];
    entry[i] = -1;
    for (int e = row.first_entry; slot >= 0 && e < row.first_entry + row.entry_count; ++e)
      if (entries_[e].body == slot) entry[i] = e;
  }
  for (int e = row.first_entry; e < row.first_entry + row.entry_count; ++e) {
    entries_[e].lin.setZero();
    entries_[e].ang.setZero();
  }
  double length = 0.0;
  Vec3 prev_u = Vec3::Zero();
  for (std::size_t i = 0; i < count; ++i) {
    Vec3 u = Vec3::Zero();
    if (i + 1 < count) {
      const Vec3 d = pos[i + 1] - pos[i];
      const double l = d.norm();
      length += l;
      if (l >= 1e-12) u = d / l;
    }
    if (entry[i] >= 0) {
      const Vec3 grad = prev_u - u;
      entries_[entry[i]].lin += grad;
      entries_[entry[i]].ang += arm[i].cross(grad);
    }
    prev_u = u;
  }
  for (int e = row.first_entry; e < row.first_entry + row.entry_count; ++e) weigh(entries_[e]);
  C_[r] = length;  // minus the rest length, by the caller
  if (ends[0].turn != 0.0) C_[r] += ends[0].payOut(-(pos[1] - pos[0]).normalized());
  if (ends[1].turn != 0.0) C_[r] += ends[1].payOut((pos[count - 1] - pos[count - 2]).normalized());
}

int DirectSolver::evaluateJoint(World& world, int r, double h) {
  const double inv_h2 = 1.0 / (h * h);
  // All the joint's rows at once.
  const Row& first = rows_[r];
  JointRowSet set;
  BodyId a, b;
  Vec3 *linear_a, *angular_a;
  double compliance;
  switch (first.source) {
    case Source::Hinge: {
      HingeJoint& j = world.hinge(first.index);
      joint_rows::hingeRowSet(j, world.body(j.a), world.body(j.b), h, set);
      a = j.a, b = j.b, linear_a = &j.impulse_point, angular_a = &j.impulse_axis, compliance = j.compliance;
      break;
    }
    case Source::Prismatic: {
      PrismaticJoint& j = world.prismatic(first.index);
      joint_rows::prismaticRowSet(j, world.body(j.a), world.body(j.b), set);
      a = j.a, b = j.b, linear_a = &j.impulse_linear, angular_a = &j.impulse_angular, compliance = j.compliance;
      break;
    }
    case Source::Spherical: {
      SphericalJoint& j = world.spherical(first.index);
      joint_rows::sphericalRowSet(j, world.body(j.a), world.body(j.b), set);
      a = j.a, b = j.b, linear_a = &j.impulse_linear, angular_a = &j.impulse_angular, compliance = j.compliance;
      break;
    }
    default: {
      FixedJoint& j = world.fixedJoint(first.index);
      joint_rows::fixedRowSet(j, world.body(j.a), world.body(j.b), set);
      a = j.a, b = j.b, linear_a = &j.impulse_linear, angular_a = &j.impulse_angular, compliance = j.compliance;
      break;
    }
  }
  const int count = set.bilateral.count + set.clamped_count;
  assert(r + count <= static_cast<int>(rows_.size()));
  assert(rows_[r + count - 1].source == first.source && rows_[r + count - 1].index == first.index);
  const bool a_moves = listed(world, a), b_moves = listed(world, b);
  for (int k = 0; k < count; ++k, ++r) {
    const bool bilateral = k < set.bilateral.count;
    const int c = k - set.bilateral.count;
    const Vec6 s = bilateral ? Vec6(set.bilateral.dirs.col(k)) : set.clamped[c].dir;
    // Row C along s = [s_p; s_w]: b's anchor along s_p, a's rotation
    // relative to b about s_w (joint_rows.h), so
    //   J_a = [-s_p; -(r_a x s_p) + s_w],  J_b = [s_p; r_b x s_p - s_w].
    const Vec3 sp = s.head<3>(), sw = s.tail<3>();
    int e = rows_[r].first_entry;
    if (a_moves) {
      entries_[e].lin = -sp;
      entries_[e].ang = sw - set.r_a.cross(sp);
      ++e;
    }
    if (b_moves) {
      entries_[e].lin = sp;
      entries_[e].ang = set.r_b.cross(sp) - sw;
    }
    for (e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e) weigh(entries_[e]);
    dir_[r] = s;
    linear_a_[r] = linear_a;
    angular_a_[r] = angular_a;
    if (bilateral) {
      C_[r] = set.bilateral.values[k];
      // The compliance term's lambda is the joint's impulse so far along
      // this row's present direction, as joint_rows::solveRows takes it: a
      // row's direction may turn within the substep (a hinge's axis rows).
      lambda_[r] = s.head<3>().dot(-*linear_a) + s.tail<3>().dot(*angular_a);
      alpha_[r] = compliance * inv_h2;
      lo_[r] = -kInf;
      hi_[r] = kInf;
      mirror_[r] = nullptr;
      state_[r] = State::Free;
    } else {
      const joint_rows::ClampedRow& clamped = set.clamped[c];
      C_[r] = clamped.C;
      alpha_[r] = clamped.alpha;  // a spring drive's; 0 for the rest
      lo_[r] = clamped.lo;
      hi_[r] = clamped.hi;
      mirror_[r] = clamped.lambda;
      lambda_[r] = *clamped.lambda;
      state_[r] = set.active[c] ? State::Free : State::Off;
    }
  }
  if (set.drive >= 0) driveAgainstLimit(r - set.clamped_count, set);
  return count;
}

void DirectSolver::driveAgainstLimit(int first_clamped, const JointRowSet& set) {
  // A rigid drive and a limit on one coordinate are one direction twice: a
  // limit in touch makes them dependent, and the factorization would keep
  // either. The limit wins, as in Gauss-Seidel (joint_rows.h). Linearized,
  // the drive asks the coordinate to change by -C_d and a lower limit
  // allows no less than -C_l (an upper one no more than -C_u): a drive
  // asking past the limit pushes with all it has (an unlimited one with
  // what it has so far) and the limit takes the rest; a drive asking to
  // stay within it does the moving alone, and the limit joins in again
  // (solveActiveSet) only if the drive cannot. A spring's drive row is
  // compliant, so not dependent on the limit: the two are solved together
  // and the spring pulls with its stiffness times its stretch at the limit.
  const int d = first_clamped + set.drive;
  const bool rigid = alpha_[d] == 0.0;
  for (const int limit : {set.lower, set.upper}) {
    if (limit < 0) continue;
    const int l = first_clamped + limit;
    drive_of_[l] = rigid ? d : -1;
    if (!rigid || state_[l] != State::Free) continue;
    const bool lower = limit == set.lower;
    const bool past = lower ? C_[d] > C_[l] : C_[d] < C_[l];
    if (!past) {
      state_[l] = State::Off;
      continue;
    }
    const double bound = lower ? lo_[d] : hi_[d];
    state_[d] = State::Fixed;
    dlambda_[d] = std::isfinite(bound) ? bound - lambda_[d] : 0.0;
  }
}

void DirectSolver::evaluate(World& world, double h) {
  evaluateBodies();
  const int n = static_cast<int>(rows_.size());
  for (int r = 0; r < n;) {
    if (rows_[r].source == Source::Path || rows_[r].source == Source::Distance) {
      evaluatePath(world, r, h);
      ++r;
    } else {
      r += evaluateJoint(world, r, h);
    }
  }
}

void DirectSolver::bodyMotion() {
  // dx = W J^T dlambda, but for hubs: their own unknowns.
  std::fill(dx_.begin(), dx_.end(), Vec3::Zero());
  std::fill(dphi_.begin(), dphi_.end(), Vec3::Zero());
  for (const Entry& e : entries_) {
    if (hub_of_[e.body] >= 0) continue;
    const double dl = dlambda_[e.row];
    dx_[e.body] += dl * e.wlin;
    dphi_[e.body] += dl * e.wang;
  }
  const int n = static_cast<int>(rows_.size());
  for (const Hub& hub : hubs_) {
    const double* m = &hub_motion_[hub.first - n];
    if (hub.dofs == 1) {
      dphi_[hub.body] = frames_[hub.body].axle * m[0];
      continue;
    }
    dx_[hub.body] = Vec3(m[0], m[1], m[2]);
    dphi_[hub.body] = Vec3(m[3], m[4], m[5]);
  }
}

double DirectSolver::hubMass(int h, int i, int j) const {
  const Hub& hub = hubs_[h];
  const BodyFrame& f = frames_[hub.body];
  if (hub.dofs == 1) return 1.0 / f.inv_axial;
  if (i < 3) return i == j ? 1.0 / f.inv_mass : 0.0;
  return j < 3 ? 0.0 : hub_inertia_[h](i - 3, j - 3);
}

double DirectSolver::hubGradient(const Entry& e, int dof) const {
  const Hub& hub = hubs_[hub_of_[e.body]];
  if (hub.dofs == 1) return e.ang.dot(frames_[hub.body].axle);
  return dof < 3 ? e.lin[dof] : e.ang[dof - 3];
}

void DirectSolver::readSolution() {
  const int n = static_cast<int>(rows_.size());
  for (int r = 0; r < n; ++r) dlambda_[r] = x_[rows_[r].position];
  for (std::size_t u = 0; u < hub_motion_.size(); ++u) hub_motion_[u] = x_[position_[n + u]];
  bodyMotion();
}

void DirectSolver::solveActiveSet(double tolerance) {
  const int n = static_cast<int>(rows_.size());
  std::fill(full_.begin(), full_.end(), 0.0);
  for (const Pair& p : pairs_) {
    const Entry &e1 = entries_[p.e1], &e2 = entries_[p.e2];
    full_[p.slot] += e1.lin.dot(e2.wlin) + e1.ang.dot(e2.wang);
  }
  // Hubs: J_h, -M_h, and each row's delta from its hub part of J W J^T.
  for (std::size_t h = 0; h < hubs_.size(); ++h) {
    const BodyFrame& f = frames_[hubs_[h].body];
    hub_inertia_[h] = f.R * f.state->inertia * f.R.transpose();
  }
  for (const Coupling& c : couplings_) full_[c.slot] = hubGradient(entries_[c.entry], c.dof);
  for (const MassSlot& m : mass_slots_) full_[m.slot] = -hubMass(m.hub, m.i, m.j);
  std::fill(delta_.begin(), delta_.end(), 0.0);
  for (const Entry& e : entries_)
    if (hub_of_[e.body] >= 0) delta_[e.row] += kHubRegularization * (e.lin.dot(e.wlin) + e.ang.dot(e.wang));
  for (const Hub& hub : hubs_)  // a leaf's share of its hub's load
    for (int l = hub.first_leaf; l < hub.first_leaf + hub.leaves; ++l) delta_[entries_[leaf_entries_[l]].row] *= hub.leaves;
  for (int r = 0; r < n; ++r) delta_[r] = std::max(0.0, delta_[r] - alpha_[r]);
  std::vector<double>& A = ldlt_.values();
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    // The free rows' system: fixed rows move to the right-hand side, and
    // fixed and off rows become identity rows (x = their known dlambda).
    std::copy(full_.begin(), full_.end(), A.begin());
    bool all_free = true;
    for (int r = 0; r < n; ++r) {
      const Row& row = rows_[r];
      if (state_[r] == State::Free) {
        A[row.diagonal] += alpha_[r] + delta_[r];
        x_[row.position] = -C_[r] - alpha_[r] * lambda_[r];
        continue;
      }
      all_free = false;
      for (int s = row.slots_begin; s < row.slots_end; ++s) A[slots_[s].value] = 0.0;
      A[row.diagonal] = 1.0;
      if (state_[r] == State::Off) dlambda_[r] = 0.0;
      x_[row.position] = dlambda_[r];
    }
    for (std::size_t u = n; u < position_.size(); ++u) x_[position_[u]] = 0.0;  // a hub's: M dx_h = J_h^T dlambda
    if (!all_free)
      for (int r = 0; r < n; ++r) {
        if (state_[r] != State::Fixed) continue;
        for (int s = rows_[r].slots_begin; s < rows_[r].slots_end; ++s) {
          const int other = slots_[s].other_row;
          if (other >= n || state_[other] == State::Free)
            x_[position_[other]] -= full_[slots_[s].value] * dlambda_[r];
        }
      }
    const bool released = factorAndSolve(tolerance);
    if (pass + 1 == kMaxPasses) {  // out of passes: every lambda within its bounds all the same
      for (int r = 0; r < n; ++r)
        dlambda_[r] = std::clamp(lambda_[r] + dlambda_[r], lo_[r], hi_[r]) - lambda_[r];
      bodyMotion();
      break;
    }
    bool changed = released, capped = false;
    for (int r = 0; r < n; ++r) {
      if (state_[r] == State::Free) {
        const double total = lambda_[r] + dlambda_[r];
        if (total > hi_[r] || total < lo_[r]) {
          state_[r] = State::Fixed;
          dlambda_[r] = std::clamp(total, lo_[r], hi_[r]) - lambda_[r];
          changed = true;
          capped |= total > hi_[r] ? hi_[r] != 0.0 : lo_[r] != 0.0;
        }
      } else if (state_[r] == State::Off) {
        // Would the others' motion violate this one-sided row?
        double predicted = C_[r];
        for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e)
          predicted += entries_[e].lin.dot(dx_[entries_[e].body]) + entries_[e].ang.dot(dphi_[entries_[e].body]);
        if ((hi_[r] == 0.0 && predicted > 0.0) || (lo_[r] == 0.0 && predicted < 0.0)) {
          state_[r] = State::Free;
          changed = true;
          // A limit its drive could not keep to: the drive keeps what it
          // did this pass, the limit the rest (driveAgainstLimit).
          if (const int d = drive_of_[r]; d >= 0 && state_[d] == State::Free) {
            state_[d] = State::Fixed;
            dlambda_[d] = std::clamp(lambda_[d] + dlambda_[d], lo_[d], hi_[d]) - lambda_[d];
          }
        }
      }
    }
    // A drive held at its maximum force or torque from now on: the one-sided
    // rows the uncapped drive let go slack (fixed at 0) are solved again
    // against the capped one. Fixed for good, the span that a motor lifting
    // a load over a wheel on its axle slackened in the first pass stayed
    // slack and the load fell (issue 28, item 7). Each drive caps once, so
    // this cannot cycle.
    if (capped)
      for (int r = 0; r < n; ++r)
        if (state_[r] == State::Fixed && (lambda_[r] + dlambda_[r] == 0.0) && (lo_[r] == 0.0 || hi_[r] == 0.0))
          state_[r] = State::Free;
    if (!changed) break;
  }
}

bool DirectSolver::factorAndSolve(double tolerance) {
  // A row dropped as dependent that the solution leaves unmet may not be
  // dependent, only very light (a pivot of 1e-13 of its terms can be
  // either): solve again with it kept, unless its pivot is at the level of
  // rounding (1e-15 of its terms), which no very light body comes near
  // (1e-12 times lighter gives 5e-13); kept, it is still dropped there,
  // as another row may now be the dependent one. A truly dependent row is
  // met by the others' motion (a belt's last span) or cannot be (then no
  // solve can).
  const int n = static_cast<int>(rows_.size());
  std::copy(x_.begin(), x_.end(), rhs_.begin());
  std::fill(keep_.begin(), keep_.end(), 0);
  int unmet = -1;  // a row truly dependent and left unmet
  double unmet_residual = 0.0;
  for (int round = 0;; ++round) {
    const int dropped = ldlt_.factor(kDropTolerance, keep_, kRoundingPivot);
    ldlt_.solve(x_.data());
    readSolution();
    if (dropped == 0 || round == 2) break;
    bool rescued = false;
    unmet = -1;
    for (int r = 0; r < n; ++r) {
      const int k = rows_[r].position;
      if (state_[r] != State::Free || !ldlt_.dropped(k)) continue;
      const bool rounding = !(ldlt_.pivotRatio(k) > kRoundingPivot);
      double residual = C_[r] + alpha_[r] * lambda_[r];
      for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e)
        residual += entries_[e].lin.dot(dx_[entries_[e].body]) + entries_[e].ang.dot(dphi_[entries_[e].body]);
      if (std::abs(residual) > std::max(tolerance, 1e-6 * std::abs(C_[r]))) {
        if (rounding) {
          if (unmet < 0) unmet = r, unmet_residual = residual;
          continue;
        }
        keep_[k] = 1;
        rescued = true;
      }
    }
    if (!rescued) break;
    std::copy(rhs_.begin(), rhs_.end(), x_.begin());
  }
  // Refinement converges as delta / (delta + the system's own scale) a
  // step: fast where the rows are stiff, slowly along a light hub between
  // heavy loads (a 3 g knuckle under a kilonewton tendon).
  if (!hubs_.empty()) {
    for (int step = 0; step < kMaxRefinements; ++step)
      if (!(refine() > tolerance)) break;
    for (const Hub& hub : hubs_) leastNormLeaves(hub);
  }
  return unmet >= 0 && releaseAlongDependency(unmet, unmet_residual);
}

bool DirectSolver::releaseAlongDependency(int r, double residual) {
  // Row r depends on others (rounding's pivot) and they leave it unmet:
  // no motion can meet it with these rows held. Along the dependency z
  // (A z = 0, z_r = 1) the lambdas shift with no motion at all; pulling
  // row r its way, t z with t = -sign(residual), brings some one-sided
  // rows to their bound 0 (a stop that would have to pull, a cable that
  // would have to push). The first to get there is not needed: it lets go
  // and the next pass solves without it (the ratio test of a pivoting
  // method). Without this a stack on its stop, a cable tight over it and a
  // drive pulling that cable made a dependent set that kept the stop and
  // dropped the cable, for ever (the gym's press at one substep).
  std::fill(x_.begin(), x_.end(), 0.0);
  x_[rows_[r].position] = 1.0;
  ldlt_.solveTransposed(x_.data());
  const double t = residual > 0.0 ? -1.0 : 1.0;
  int best = -1;
  double best_ratio = kInf;
  for (int j = 0; j < static_cast<int>(rows_.size()); ++j) {
    if (j == r || state_[j] != State::Free) continue;
    const double total = lambda_[j] + dlambda_[j], shift = t * x_[rows_[j].position];
    double ratio;
    if (lo_[j] == 0.0 && shift < 0.0 && total > 0.0) ratio = total / -shift;
    else if (hi_[j] == 0.0 && shift > 0.0 && total < 0.0) ratio = -total / shift;
    else continue;
    if (ratio < best_ratio) best_ratio = ratio, best = j;
  }
  if (best < 0) return false;
  state_[best] = State::Fixed;
  dlambda_[best] = -lambda_[best];
  return true;
}

void DirectSolver::leastNormLeaves(const Hub& hub) {
  // Rigid cables that move the hub alone and are more than it has
  // freedoms for share its load as equal elastic cables would, stiffened
  // without bound: compliance in proportion to length L_k, so their
  // tensions minimize sum L_k dlambda_k^2 with the same wrench on the hub,
  // g = sum g_k dlambda_k (g_k = J_h of cable k):
  //   G = sum g_k g_k^T / L_k,   dlambda_k = g_k^T G^+ g / L_k.
  // The hub's motion stays as solved. What goes is the part of dlambda
  // that moves nothing: the solve's choice among equal answers, and
  // rounding in redundant rows divided by delta.
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  const auto gradient = [&](const Entry& e) {
    Vec6 g = Vec6::Zero();
    for (int d = 0; d < hub.dofs; ++d) g[d] = hubGradient(e, d);
    return g;
  };
  const auto shared = [&](int r) {
    return (rows_[r].source == Source::Path || rows_[r].source == Source::Distance) && state_[r] == State::Free &&
           alpha_[r] == 0.0 && length_[r] > 0.0;
  };
  Mat6 G = Mat6::Zero();
  Vec6 wrench = Vec6::Zero();
  int count = 0;
  for (int l = hub.first_leaf; l < hub.first_leaf + hub.leaves; ++l) {
    const Entry& e = entries_[leaf_entries_[l]];
    if (!shared(e.row)) continue;
    const Vec6 g = gradient(e);
    G += g * g.transpose() / length_[e.row];
    wrench += g * dlambda_[e.row];
    ++count;
  }
  if (count < 2) return;
  const Eigen::SelfAdjointEigenSolver<Mat6> eigen(G);
  const Vec6& values = eigen.eigenvalues();
  const double floor = 1e-12 * values.cwiseAbs().maxCoeff();
  Vec6 y = eigen.eigenvectors().transpose() * wrench;
  for (int i = 0; i < 6; ++i) y[i] = values[i] > floor ? y[i] / values[i] : 0.0;
  y = eigen.eigenvectors() * y;
  for (int l = hub.first_leaf; l < hub.first_leaf + hub.leaves; ++l) {
    const Entry& e = entries_[leaf_entries_[l]];
    if (shared(e.row)) dlambda_[e.row] = gradient(e).dot(y) / length_[e.row];
  }
}

double DirectSolver::refine() {
  // The factor solved the rows with delta on their diagonal; the residual
  // of the system without it, solved with the same factor, corrects the
  // solution (iterative refinement): the error falls from delta / (J W J^T)
  // to its square. The hubs' equations held already.
  const int n = static_cast<int>(rows_.size());
  std::fill(x_.begin(), x_.end(), 0.0);
  double largest = 0.0;
  for (int r = 0; r < n; ++r) {
    if (state_[r] != State::Free || delta_[r] == 0.0) continue;
    double residual = -C_[r] - alpha_[r] * (lambda_[r] + dlambda_[r]);
    for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e)
      residual -= entries_[e].lin.dot(dx_[entries_[e].body]) + entries_[e].ang.dot(dphi_[entries_[e].body]);
    x_[rows_[r].position] = residual;
    largest = std::max(largest, std::abs(residual));
  }
  if (largest == 0.0) return 0.0;
  ldlt_.solve(x_.data());
  for (int r = 0; r < n; ++r) dlambda_[r] += x_[rows_[r].position];
  for (std::size_t u = 0; u < hub_motion_.size(); ++u) hub_motion_[u] += x_[position_[n + u]];
  bodyMotion();
  return largest;
}

bool DirectSolver::converged(double tolerance) const {
  if (!(tolerance > 0.0)) return false;
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    if (state_[r] == State::Off) {  // met unless violated (a limit its drive is to lift off)
      if ((hi_[r] == 0.0 && C_[r] > tolerance) || (lo_[r] == 0.0 && C_[r] < -tolerance)) return false;
      continue;
    }
    if (state_[r] != State::Free) continue;
    const double residual = C_[r] + alpha_[r] * lambda_[r];
    // A row held at a bound is met when it asks to go further.
    if ((lambda_[r] >= hi_[r] && residual <= 0.0) || (lambda_[r] <= lo_[r] && residual >= 0.0)) continue;
    if (std::abs(residual) > tolerance) return false;
  }
  return true;
}

bool DirectSolver::iterate(World& world, double h) {
  if (rows_.empty()) return false;
  evaluate(world, h);
  // A residual C left in a substep h is a force error of about C m / h^2:
  // the tolerance, met at h = 1/600 s (4e-5 N per kg), shrinks with h^2
  // below that, or at 10,000 substeps of a 60 Hz frame a 1:100 Atwood
  // machine's solve stopped before it started and reported no tension.
  // (Tolerance 0, to time every iteration, still meets rows to 1e-10 m.)
  constexpr double kToleranceStep = 1.0 / 600.0;  // s
  const double scale = std::min(1.0, (h / kToleranceStep) * (h / kToleranceStep));
  const double tolerance = world.settings().tolerance * scale;
  if (converged(tolerance)) return false;
  solveActiveSet(tolerance > 0.0 ? tolerance : 1e-10 * scale);
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    BodyState& b = *frames_[i].state;
    // The exact rotation: a light wheel may turn radians in one solve, and
    // the first-order rotateBy() would turn it less than the solve asked.
    if (frames_[i].inv_mass > 0.0) b.x += dx_[i];
    rotateExactly(b.q, dphi_[i]);
    b.solve_turn += dphi_[i];
  }
  for (const Entry& e : entries_) {
    BodyState& b = *frames_[e.body].state;
    b.impulse += dlambda_[e.row] * e.lin;
    b.angular_impulse += dlambda_[e.row] * e.ang;
  }
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const double dl = dlambda_[r];
    if (dl == 0.0) continue;
    lambda_[r] += dl;
    if (mirror_[r]) *mirror_[r] = lambda_[r];
    if (linear_a_[r]) {  // a joint row: its impulse on a (joint_rows::solveRows)
      *linear_a_[r] -= dl * dir_[r].head<3>();
      *angular_a_[r] += dl * dir_[r].tail<3>();
    }
  }
  return true;
}

}  // namespace reeve
