// The direct solver's layout (describe, build), its substep (prepare)
// and its iteration (iterate): linearize (rows.cpp), solve the active set
// (active_set.cpp, hubs.cpp), move the bodies.
#include "direct_solver.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include <Eigen/Eigenvalues>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include "reeve/engine/correction.h"
#include "../island.h"
#include "../line_up.h"
#include "reeve/engine/world.h"

namespace reeve {
namespace {

// +1 where the symmetric 3 x 3 matrix K is positive semidefinite (its
// principal minors all >= 0: Sylvester), -1 where -K is, else 0.
// Near a singular K rounding may decide either way; |K| and +-K then differ
// by that rounding alone.
double semidefinite(const Mat3& K) {
  const auto positive = [](const Mat3& m) {
    return m(0, 0) >= 0.0 && m(1, 1) >= 0.0 && m(2, 2) >= 0.0 && m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0) >= 0.0 &&
           m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1) >= 0.0 && m(0, 0) * m(2, 2) - m(0, 2) * m(2, 0) >= 0.0 &&
           m.determinant() >= 0.0;
  };
  if (positive(K)) return 1.0;
  if (positive(-K)) return -1.0;
  return 0.0;
}

// A lower bound on the least eigenvalue of a symmetric 3 x 3 matrix
// (Gershgorin's discs; exact for a body's diagonal inertia): kg m^2.
double leastMomentBound(const Mat3& inertia) {
  double least = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i)
    least = std::min(least, inertia(i, i) - std::abs(inertia(i, (i + 1) % 3)) - std::abs(inertia(i, (i + 2) % 3)));
  return least;
}

// (I + V diag(k) V^T)^-1: the world inertia with |K|'s eigenvalues k added
// along K's eigenvectors V (newtonStep, warmStiffness).
Mat3 stiffenedInverse(const Mat3& inertia, const Mat3& V, const Vec3& k) {
  return (inertia + V * k.asDiagonal() * V.transpose()).inverse();
}

// A body turned further than this (rad) within one solve takes XPBD's
// steps (newtonStep).
constexpr double kNewtonTurn = 0.2;
// Newton's residual is met when its motion is below this fraction of what
// the solve moved the bodies in the substep (iterate()): 1e-2 let the
// hand's other fingers drift 1.1e-5 rad as one closed (its test allows
// 1e-5); 1e-3 runs the hand at 1 x 20 in 6.0 iterations a frame (7.7
// before extrapolation()).
constexpr double kNewtonRelative = 1e-3;
// The contraction a step's size must show against the last's for it to be
// extrapolated (extrapolation()): below the least the gain is under 11 %;
// above the most (omega = 5) the iteration is not yet in its linear tail.
constexpr double kAitkenLeast = 0.1;
constexpr double kAitkenMost = 0.8;
// A geometric tail: the step's ratio agrees with the last one measured to
// this fraction, and the step is under this fraction of what the solve has
// moved the bodies in the substep (a wrong extrapolation then costs little).
constexpr double kAitkenSteady = 0.25;
constexpr double kAitkenTail = 0.05;
// startPoint lifts an island only where gravity's fall in a substep, g h^2,
// is at least this fraction of its shortest span. The first solve from x~
// is linearized to about (g h^2) / span of its motion: the hand at 10 x 2
// (2.7e-5 m over 3 cm spans) needed a second solve for Newton's residual
// (kNewtonRelative), and the lift takes it away; far below, the lift
// changes no solve count, only the rounding of x~ + lift - lift (5e-8 of
// an Atwood machine's tension at 24,000 substeps a second, against 1e-8
// from x~).
constexpr double kStartSag = 1e-4;
// startPoint starts a body from the whole of the last substep's solve,
// turn included, where that solve's acceleration repeated the one before
// to this fraction of its size (a steady motion, not an event).
constexpr double kStartSteady = 0.5;
// A solve whose largest step (m, rad) is below this fraction of the
// tolerance moved nothing a row can tell (iterate()).
constexpr double kStalled = 1e-3;

// Rounds of stiffenTurns() and a solve in an iteration: a body in other
// rows (a spool hinged to a cart) may turn past again after the first.
constexpr int kLineUpRounds = 3;
// stiffenMoves: a span whose fixed ends the step carries past their
// closest approach at a share s* below this gained almost nothing from the
// step (s* ~ its shortening over the sideways motion's second-order
// lengthening): the step is another row's, and stiffening by s* made a 5 g
// bead 1e13 times heavier (its load's span right below it, the other span
// swinging it sideways; 4.7e13 N, 3.9e11 J booked against a lowering
// anchor).
constexpr double kLeastMoveShare = 0.01;
// A turn whose secant is within this of its model is taken as the model.
constexpr double kSecantSlack = 1e-3;
// A store's end, tied once it runs out, lines up with its span a quarter
// turn on from the tangent point it left by (stiffenStores).
constexpr double kQuarterTurn = std::numbers::pi / 2.0;

using joint_rows::kInf;
using joint_rows::Vec6;

// A body with more rows than this is a hub (direct_solver.h): its rows
// would fill more of the matrix than its own motion does, and cost more
// than the hub's refinement steps. At 12 the hand's knuckles (21 rows,
// 3 g under heavy tendons) were hubs and the hand took 0.28 ms a frame at
// 1 x 20 where its rows take 0.13 (refining there needs several steps).
// So is one with
// more cable spans than this that move it alone (leaves): four cables to
// one point are already redundant, which a hub's leaves resolve by the
// least norm (leastNormLeaves) and the rows' matrix cannot.
constexpr int kHubRows = 24;
constexpr int kHubCableLeaves = 3;
// Projection::Start: the largest relative turn of a row's gradient over
// the substep that keeps it (chooseStartRows). A pendulum at 1 x 10 turns
// its 0.05; a 1 cm spool at 6 m/s, 1. At 0.3 and 0.4 a double pendulum at
// 1 x 10 keeps its energy (4e-2 of 2 m g L; -44 % at 0.2), but a tie point
// riding round a spool at 2 iterations makes energy (spool.json).
constexpr double kStartTurnLimit = 0.2;

// The number of rows of a joint with `bilateral` locked rows and the
// given drive and limits (JointRowSet's layout).
int jointRowCount(int bilateral, bool driven, bool limited) { return bilateral + (driven ? 1 : 0) + (limited ? 2 : 0); }

bool moves(const World& world, BodyId id) { return world.body(id).moves(); }

// A path whose points are all fixed on one body (a rope between two
// friction pinholes of one plate, sticking): no motion of the body
// changes its length, its gradient is zero but for rounding, and its
// tension is not the solve's to find. As a row it divided rounding by
// rounding: 5e4 N in a rope laced through four holes of a 1 kg plate,
// which flew 1.8 m in the first frame (DESIGN, "Fifty-third session").
bool chordOfOneBody(const PathConstraint& p) {
  return std::all_of(p.points.begin(), p.points.end(), [&](const PathPoint& q) {
    return q.body == p.points[0].body && q.roll_axis.isZero();
  });
}
bool listed(const World& world, BodyId id) { return direct::listed(world.body(id)); }

}  // namespace

std::size_t DirectSolver::describe(World& world, const Island& island, std::vector<int>& sig) const {
  sig.clear();
  const auto joint = [&](Source source, int index, BodyId a, BodyId b, int rows) {
    // A rotor's hinge without a drive or limit has no row (its axle is
    // the rotor's inverse inertia, body.h), and so no place in the layout.
    if (rows == 0 || (!moves(world, a) && !moves(world, b))) return;
    sig.insert(sig.end(), {static_cast<int>(source), index, rows, listed(world, a) ? a : kWorldBody,
                           listed(world, b) ? b : kWorldBody});
  };
  for (const int i : island.hinges) {
    const HingeJoint& j = world.hinges()[i];
    const bool rotor = world.body(j.a).isRotor() || world.body(j.b).isRotor();
    joint(Source::Hinge, i, j.a, j.b,
          jointRowCount(rotor ? 0 : 5, j.drive.mode != HingeDrive::Mode::None, j.limit.enabled));
  }
  for (const int i : island.prismatics) {
    const PrismaticJoint& j = world.prismatics()[i];
    joint(Source::Prismatic, i, j.a, j.b,
          jointRowCount(5, j.drive.mode != PrismaticDrive::Mode::None, j.limit.enabled));
  }
  for (const int i : island.sphericals) {
    const SphericalJoint& j = world.sphericals()[i];
    joint(Source::Spherical, i, j.a, j.b,
          jointRowCount(3, false, j.twist_limit.enabled) + (j.swing_limit.enabled ? 1 : 0));
  }
  for (const int i : island.fixeds) {
    const FixedJoint& j = world.fixedJoints()[i];
    joint(Source::Fixed, i, j.a, j.b, 6);
  }
  for (const int i : island.distances) {
    const DistanceConstraint& c = world.distance(i);
    if (c.enabled) joint(Source::Distance, i, c.a, c.b, 1);
  }
  for (const int i : island.paths) {
    const PathConstraint& p = world.path(i);
    if (!p.enabled || !p.weights.empty()) continue;  // weighted paths: World::solvePositions
    if (chordOfOneBody(p)) continue;
    if (p.points.size() == 2) {  // a span (most paths): the loop below, unrolled
      const BodyId a = p.points[0].body, b = p.points[1].body;
      const bool on_a = listed(world, a), on_b = listed(world, b) && !(on_a && b == a);
      if (!(on_a && moves(world, a)) && !(on_b && moves(world, b))) continue;  // nothing in it moves
      sig.insert(sig.end(), {static_cast<int>(Source::Path), i, 1, int{on_a} + int{on_b}});
      if (on_a) sig.push_back(a);
      if (on_b) sig.push_back(b);
      continue;
    }
    const std::size_t head = sig.size();
    sig.insert(sig.end(), {static_cast<int>(Source::Path), i, 1, 0});  // 0: the body count, below
    // Its bodies in the order of their first points: sorted by body, each
    // body's first point kept, then sorted back by point (a search of the
    // bodies listed so far, per point, grew as points x bodies: a rope
    // through 1024 beads' holes).
    path_bodies_.clear();
    for (int k = 0; k < static_cast<int>(p.points.size()); ++k)
      if (listed(world, p.points[k].body)) path_bodies_.emplace_back(p.points[k].body, k);
    std::sort(path_bodies_.begin(), path_bodies_.end());
    path_bodies_.erase(std::unique(path_bodies_.begin(), path_bodies_.end(),
                                   [](const auto& x, const auto& y) { return x.first == y.first; }),
                       path_bodies_.end());
    std::sort(path_bodies_.begin(), path_bodies_.end(),
              [](const auto& x, const auto& y) { return x.second < y.second; });
    bool moving = false;
    for (const auto& [body, point] : path_bodies_) {
      sig.push_back(body);
      moving = moving || moves(world, body);
    }
    if (!moving) sig.resize(head);  // nothing in it moves
    else sig[head + 3] = static_cast<int>(sig.size() - head - 4);
  }
  const std::size_t contacts_begin = sig.size();
  describeContacts(world, island, sig);
  return contacts_begin;
}

void DirectSolver::describeContacts(const World& world, const Island& island, std::vector<int>& sig) const {
  if (island.manifolds.empty()) return;  // most islands, every substep: nothing to list
  // The bodies the cables above move (paths as [source, index, 1, count,
  // bodies...], distances as joints, [source, index, rows, a, b]).
  row_bodies_.clear();
  for (std::size_t k = 0; k < sig.size();) {
    const auto source = static_cast<Source>(sig[k]);
    if (source == Source::Path) {
      row_bodies_.insert(row_bodies_.end(), sig.begin() + k + 4, sig.begin() + k + 4 + sig[k + 3]);
      k += 4 + sig[k + 3];
    } else {
      if (source == Source::Distance) row_bodies_.insert(row_bodies_.end(), {sig[k + 3], sig[k + 4]});
      k += 5;
    }
  }
  if (row_bodies_.empty()) return;
  std::sort(row_bodies_.begin(), row_bodies_.end());
  // A manifold joins as [Contact, its place in island.manifolds, rows, a,
  // b] where one body is one those cables move and the other is static
  // (not kinematic: its schedule moves it), its points stay on their
  // bodies (a curved pair's move as they roll: remeasureCurvedContact, in
  // the sweep alone), and it touched in the last substep too (resting: an
  // impact is the sweep's). Between two moving bodies the sweep's friction
  // pools and level holds share the load (contact.h). A body only joints
  // hold keeps the sweep: MuJoCo's humanoid, its feet 12 points a
  // manifold, blew up at its landing with them in the solve (DESIGN,
  // "Forty-ninth session").
  const std::vector<ContactManifold>& manifolds = world.contactManifolds();
  const std::vector<Contact>& contacts = world.contacts();
  for (std::size_t k = 0; k < island.manifolds.size(); ++k) {
    const ContactManifold& m = manifolds[island.manifolds[k]];
    const BodyState &a = world.body(m.a), &b = world.body(m.b);
    const bool b_held = b.moves() && !a.moves() && !a.kinematic;
    const bool a_held = a.moves() && !b.moves() && !b.kinematic;
    if ((!a_held && !b_held) || m.last_pressure <= 0.0) continue;
    if (!std::binary_search(row_bodies_.begin(), row_bodies_.end(), b_held ? m.b : m.a)) continue;
    const auto curved = [](const Contact& c) { return c.core_a >= 0.0 || c.core_b >= 0.0; };
    if (std::any_of(contacts.begin() + m.first, contacts.begin() + m.first + m.count, curved)) continue;
    sig.insert(sig.end(), {static_cast<int>(Source::Contact), static_cast<int>(k),
                           m.count + frictionRows(m, contacts[m.first]), a_held ? m.a : kWorldBody,
                           b_held ? m.b : kWorldBody});
  }
}

void DirectSolver::build(World& world) {
  // Rows and their entries from the signature, joints as [source, index,
  // rows, a, b] (kWorldBody for a body that does not move), paths as
  // [source, index, 1, count, bodies...].
  rows_.clear();
  entries_.clear();
  bodies_.clear();
  // A block's moving bodies, into block_bodies; returns where the next
  // block starts.
  std::vector<BodyId> block_bodies;
  const auto block = [&](std::size_t k) {
    block_bodies.clear();
    if (static_cast<Source>(signature_[k]) == Source::Path) {
      block_bodies.assign(signature_.begin() + k + 4, signature_.begin() + k + 4 + signature_[k + 3]);
      return k + 4 + signature_[k + 3];
    }
    for (const BodyId id : {signature_[k + 3], signature_[k + 4]})
      if (id != kWorldBody) block_bodies.push_back(id);
    return k + 5;
  };
  // The window of ids the bodies lie in, where it is at most a few times
  // their number (slotOf).
  BodyId lowest = std::numeric_limits<BodyId>::max(), highest = -1;
  std::size_t listed = 0;
  for (std::size_t k = 0; k < signature_.size();) {
    k = block(k);
    for (const BodyId id : block_bodies) lowest = std::min(lowest, id), highest = std::max(highest, id);
    listed += block_bodies.size();
  }
  const bool none = highest < lowest;
  const bool window = none || static_cast<std::size_t>(highest - lowest) < 4 * listed + 64;
  body_base_ = none ? 0 : lowest;
  body_index_.assign(window && !none ? highest - lowest + 1 : 0, -1);
  body_ids_.clear();
  const auto bodyIndex = [&](BodyId id) {
    if (window) {
      int& slot = body_index_[id - body_base_];
      if (slot < 0) slot = static_cast<int>(bodies_.size()), bodies_.push_back(id);
      return slot;
    }
    const auto it = std::lower_bound(body_ids_.begin(), body_ids_.end(), std::pair{id, -1});
    if (it != body_ids_.end() && it->first == id) return it->second;
    body_ids_.insert(it, {id, static_cast<int>(bodies_.size())});
    bodies_.push_back(id);
    return static_cast<int>(bodies_.size()) - 1;
  };
  for (std::size_t k = 0; k < signature_.size();) {
    const auto source = static_cast<Source>(signature_[k]);
    const int index = signature_[k + 1], count = signature_[k + 2];
    k = block(k);
    for (int r = 0; r < count; ++r) {
      Row row{source, index, static_cast<int>(entries_.size()), static_cast<int>(block_bodies.size()), 0, 0, 0, 0};
      for (const BodyId id : block_bodies) {
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
    hubs_.push_back({static_cast<int>(b), dofs, unknowns, 0, 0});
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
  for (std::vector<double>* v : {&C_, &alpha_, &lo_, &hi_, &lambda_, &dlambda_, &delta_, &length_, &placed_length_})
    v->assign(n, 0.0);
  linear_.assign(n, 0);
  placed_.assign(n, 0);
  for (std::vector<double>* v : {&x_, &rhs_}) v->assign(unknowns, 0.0);
  hub_motion_.assign(unknowns - n, 0.0);
  held_.dlambda.assign(n, 0.0);
  held_.hub_motion.assign(unknowns - n, 0.0);
  held_.state.assign(n, State::Free);
  hub_inertia_.assign(hubs_.size(), Mat3::Zero());
  keep_.assign(unknowns, 0);
  state_.assign(n, State::Free);
  pulled_.assign(n, false);
  at_cap_.assign(n, 0);
  at_cap_start_.assign(n, 0);
  warm_.assign(n, 0);
  drive_of_.assign(n, -1);
  mirror_.assign(n, nullptr);
  dir_.assign(n, Vec6::Zero());
  linear_a_.assign(n, nullptr);
  angular_a_.assign(n, nullptr);
  full_.assign(ldlt_.values().size(), 0.0);
  curvature_.assign(entries_.size(), Mat3::Zero());
  bend_.assign(entries_.size(), 0.0);
  std::size_t points = 0;  // no allocation in a step: at most a fixed end a point
  for (const Row& row : rows_)
    points += row.source == Source::Path ? world.path(row.index).points.size() : row.source == Source::Distance ? 2 : 0;
  fixed_ends_.reserve(points);
  fixed_spans_.reserve(rows_.size());
  stiffened_moves_.reserve(bodies_.size());
  const std::size_t m = bodies_.size();
  stiffened_turns_.reserve(m);
  secants_.reserve(points);
  secant_of_.assign(entries_.size(), -1);
  frames_.assign(m, BodyFrame{});
  run_.slot_entry.assign(m, -1);
  dx_.assign(m, Vec3::Zero());
  dphi_.assign(m, Vec3::Zero());
  for (auto* v : {&moved_x_, &moved_phi_, &shift_x_, &shift_phi_}) v->assign(m, Vec3::Zero());
  stiffness_.assign(m, Mat3::Zero());
  lateral_stiffness_.assign(m, Mat3::Zero());
  jointed_.assign(m, 0);
  // A contact row holds its body along the normal alone: the span ends'
  // sideways stiffness stays (newtonResidual).
  for (const Entry& e : entries_)
    if (const Source source = rows_[e.row].source;
        source != Source::Path && source != Source::Distance && source != Source::Contact)
      jointed_[e.body] = 1;
  row_bodies_.reserve(contacts_begin_);  // no allocation when a contact first comes (describeContacts)
  contact_rows_.clear();
  for (int r = 0; r < n; ++r)
    if (rows_[r].source == Source::Contact) contact_rows_.push_back(r);
  contact_of_.assign(n, -1);
  contact_written_.assign(n, 0.0);
  contact_dir_.assign(n, Vec3::Zero());
  contact_kind_.assign(n, ContactRow::Normal);
  world_inertia_.assign(m, Mat3::Zero());
  axial_stiffness_.assign(m, 0.0);
  reweigh_.assign(m, 0);
}

bool DirectSolver::prepare(World& world, const Island& island, double h, bool again) {
  const std::size_t contacts_begin = describe(world, island, scratch_);
  const bool rebuilt = scratch_ != signature_;
  const bool contacts_relaid = rebuilt && contacts_begin == contacts_begin_ &&
                               std::equal(scratch_.begin(), scratch_.begin() + contacts_begin, signature_.begin());
  if (rebuilt) {
    signature_ = scratch_;  // a copy: scratch_ keeps its capacity for the next substeps
    contacts_begin_ = contacts_begin;
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
    f.axial_inv0 = f.inv_axial;
    f.axial_inertia = f.inv_axial > 0.0 ? 1.0 / f.inv_axial : 0.0;
    const Scalars3 axle = rotated(b.q, b.rotor_axis);  // in scalars: math.h
    f.axle = Vec3(axle.x, axle.y, axle.z);
    f.evaluated_turn = b.solve_turn;
  }
  evaluated_ = false;
  manifolds_ = &island.manifolds;
  for (const int r : contact_rows_) {  // they push, and only that
    lo_[r] = 0.0;
    hi_[r] = kInf;
    mirror_[r] = nullptr;
    linear_a_[r] = angular_a_[r] = nullptr;
    contact_written_[r] = 0.0;
    contact_of_[r] = -1;  // set as evaluated
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
  // A solve done again starts from the caps the first one started from.
  if (again) at_cap_ = at_cap_start_;
  else at_cap_start_ = at_cap_;
  if (!again) last_lambda_ = lambda_;
  std::fill(lambda_.begin(), lambda_.end(), 0.0);
  // A contact or weighted path swept between the iterations moves the
  // bodies too: the next iteration then does not start where the last
  // one's solve left them (met_).
  touching_ = !island.manifolds.empty();
  const bool unweighted = std::all_of(island.paths.begin(), island.paths.end(),
                                      [&](int i) { return world.path(i).weights.empty(); });
  moves_alone_ = !touching_ && unweighted;
  // Every manifold of the island a block of rows here ([source, index,
  // rows, a, b] each, after contacts_begin_).
  contacts_in_rows_ = unweighted && (signature_.size() - contacts_begin_) / 5 == island.manifolds.size();
  startPoint(world, h, again, rebuilt);
  first_iteration_ = true;
  plain_solve_ = false;
  met_ = false;
  last_step_ = 0.0;
  last_rho_ = 0.0;
  extrapolated_ = false;
  if (world.settings().projection == Projection::Start) {
    linearizeAtStart(world, h);
    // The rows take start_'s gradients: none is kept (keepsSpan).
    std::fill(placed_.begin(), placed_.end(), 0);
  } else {
    start_.clear();
  }
  return contacts_relaid;
}

void DirectSolver::startPoint(const World& world, double h, bool again, bool rebuilt) {
  // Newton's iterations may start anywhere; XPBD starts them at the
  // prediction x~, where gravity has moved each body g h^2 from where the
  // rows held it. A machine at rest then starts every substep displaced
  // from its answer, its short spans to static bodies turned by that
  // displacement (the hand's wrist pinholes: 2.7 mm across 1 to 2 cm at 1
  // x 20), and Newton's steps are spent coming back (DESIGN.md,
  // "Twenty-ninth session: where Newton starts"). Here each body starts
  // where the rows' acceleration of the last substep would put it, a =
  // moved_x / h_last^2 and alpha = moved_phi / h_last^2 (moved_x, moved_phi:
  // the last substep's solve's motion and turn of the body), wherever it
  // repeated the substep's before to kStartSteady of its size:
  //   x = x~ + h^2 a,   q = q~ turned by h^2 alpha
  // (the rows' impulse reused, as Box2D and Jolt warm-start theirs; in a
  // steady motion a changes by O(h) a substep, and the start is O(h^3)
  // from the answer instead of gravity's g h^2). Elsewhere (an impact, a
  // jam, a release: a stale acceleration there flung a slider hauled into
  // its pulley) each body the rows held up against gravity starts held up
  // as much, at most by its weight:
  //   x = x~ + h^2 a_up u,   u = -g / |g|,   a_up = clamp(a . u, 0, |g|)
  // (the bounded "adaptive initialization" of Chen et al., "Vertex Block
  // Descent", SIGGRAPH 2024). The start is no force: it is Newton's
  // residual M (x - x~), which the solve takes back wherever the rows no
  // longer hold the body so (a load let go falls freely from that substep
  // on).
  // The start stays x~ where it would decide more than where the
  // iterations begin:
  // - one iteration a substep: no Newton step follows, and the projection
  //   from x~ along its own gradients is the answer (exact for one
  //   distance row; from the lifted start the Galileo bob dips 1.05 mm
  //   below its circle at 1 x 1);
  // - an island a contact or weighted path sweeps between the iterations
  //   (their motion is not in moved_x), and a rotor (no gravity on it).
  //   Contacts that are all rows of this solve (describeContacts) move
  //   their bodies in moved_x and are lifted with them: Servin's island,
  //   its plate resting on the ground, took 4 iterations a substep at 1 x
  //   10 from x~ (3 solves and the check that found them met), 2 or 3
  //   lifted;
  // - an island where the lift would move a stop that pushed in the last
  //   substep (a limit, a one-sided slide: liftMovesStops): a body resting
  //   on its stop would start exactly at it, where the limit's activity
  //   is rounding's to decide, and at 4 x 2 the gym's redundant stops (the
  //   stack's and a handle's, one cable between them) then cycled, the
  //   handle leaving its stop by multiples of g h^2. A stop the lift does
  //   not move (a winch drum's angle: the drum turns nothing) keeps its
  //   C, and the island is lifted; lifted without the bodies on stops
  //   (those left at x~), the bow at 1 x 10 drew its nock through the
  //   arrow and broke its string's bookkeeping at 0.7 s;
  // - an island whose spans are long against g h^2 (kStartSag), or that
  //   has none (joints alone): its first solve from x~ is linearized well
  //   enough, and the lift would change only rounding; and one whose rows
  //   all stay linear as the bodies move (linearRows: exact from x~);
  // - a new layout, a solve done again (it starts where the first did),
  //   the start projection (its gradients are the substep's start's).
  if (!again) {
    const Vec3 g = world.settings().gravity;
    const double g_size = g.norm();
    bool lift = !rebuilt && last_h_ > 0.0 && contacts_in_rows_ && g_size > 0.0 && world.settings().iterations > 1 &&
                world.settings().projection == Projection::End && !linearRows(world);
    double shortest = kInf;  // m, of the island's spans (length_: as the last substep evaluated them)
    bool stopped = false;    // a limit or one-sided slide pushed in the last substep
    for (std::size_t r = 0; r < rows_.size() && lift; ++r) {
      stopped = stopped || pushedAsStop(static_cast<int>(r));
      if (rows_[r].source == Source::Path || rows_[r].source == Source::Distance)
        shortest = std::min(shortest, length_[r]);
    }
    lift = lift && g_size * h * h >= kStartSag * shortest;
    if (lifted_ || start_x_.size() != frames_.size()) {
      start_x_.assign(frames_.size(), Vec3::Zero());
      start_phi_.assign(frames_.size(), Vec3::Zero());
    }
    lifted_ = false;
    const Vec3 up = lift ? Vec3(-g / g_size) : Vec3::Zero();
    // The rows' acceleration of each body in the last substep, and whether
    // it repeated the one before. Kept only while the island is lifted: a
    // new layout, or a substep it was not lifted in, knows none before (and
    // an island that never is, a chain of rotors, pays nothing for it).
    if (last_a_.size() != frames_.size()) {
      last_a_.assign(frames_.size(), Vec3::Zero());
      last_alpha_.assign(frames_.size(), Vec3::Zero());
    }
    const bool known = lift && !rebuilt && last_lifted_;
    last_lifted_ = lift;
    const double per_h2 = last_h_ > 0.0 ? 1.0 / (last_h_ * last_h_) : 0.0;
    const double steady2 = kStartSteady * kStartSteady;
    for (std::size_t i = 0; i < frames_.size() && lift; ++i) {
      const Vec3 a = per_h2 * moved_x_[i], alpha = per_h2 * moved_phi_[i];  // m/s^2, rad/s^2
      const bool steady = known && (a - last_a_[i]).squaredNorm() <= steady2 * a.squaredNorm() &&
                          (alpha - last_alpha_[i]).squaredNorm() <= steady2 * alpha.squaredNorm();
      last_a_[i] = a;
      last_alpha_[i] = alpha;
      const BodyFrame& f = frames_[i];
      if (f.inv_axial > 0.0 || f.inv_mass == 0.0 || hub_of_[i] >= 0 || f.state->kinematic) continue;
      // A start turned past kNewtonTurn is one the solve cannot take back:
      // such a body takes XPBD's steps, without Newton's residual, and a
      // first solve that finds its rows met keeps the start as motion. A
      // yo-yo falling from a hand, spinning 4 rad a substep round its turn,
      // was started a further 4 rad round and 2 cm up, its string slack:
      // kept, that threw it up and spun it the other way (+0.09 J of its
      // 1.27 J in a frame, 1.8 J by 0.8 s at 1 x 2; DESIGN, "Fifty-ninth
      // session"). It starts held up at most by its weight, as after a jerk.
      if (steady && h * h * alpha.norm() <= kNewtonTurn) {
        start_x_[i] = h * h * a;
        start_phi_[i] = h * h * alpha;
      } else {
        start_x_[i] = (h * h * std::clamp(a.dot(up), 0.0, g_size)) * up;
      }
      lifted_ = lifted_ || !start_x_[i].isZero(0.0) || !start_phi_[i].isZero(0.0);
    }
    if (lifted_ && stopped && liftMovesStops(direct::substepTolerance(world.settings().tolerance, h))) {
      std::fill(start_x_.begin(), start_x_.end(), Vec3::Zero());
      std::fill(start_phi_.begin(), start_phi_.end(), Vec3::Zero());
      lifted_ = false;
    }
    last_h_ = h;
  } else if (start_x_.size() != frames_.size()) {  // a layout built again
    start_x_.assign(frames_.size(), Vec3::Zero());
    start_phi_.assign(frames_.size(), Vec3::Zero());
    lifted_ = false;
  }
  std::fill(moved_phi_.begin(), moved_phi_.end(), Vec3::Zero());
  if (!lifted_) {
    std::fill(moved_x_.begin(), moved_x_.end(), Vec3::Zero());
    return;
  }
  std::copy(start_x_.begin(), start_x_.end(), moved_x_.begin());
  std::copy(start_phi_.begin(), start_phi_.end(), moved_phi_.begin());
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    BodyState& b = *frames_[i].state;
    b.x += start_x_[i];
    if (start_phi_[i].isZero(0.0)) continue;
    rotateExactly(b.q, start_phi_[i]);
    b.solve_turn += start_phi_[i];  // a turn the cables pay out for, as the solve's
  }
}

bool DirectSolver::pushedAsStop(int r) const {
  const Source source = rows_[r].source;
  if (source == Source::Path || source == Source::Distance || source == Source::Contact) return false;
  const bool one_sided = (lo_[r] == 0.0 && hi_[r] == kInf) || (hi_[r] == 0.0 && lo_[r] == -kInf);
  return one_sided && last_lambda_[r] != 0.0;
}

bool DirectSolver::liftMovesStops(double tolerance) const {
  // The change the lift makes to a stop's C, J . (start_x, start_phi),
  // along the gradient the last substep's solve ended with.
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    if (!pushedAsStop(static_cast<int>(r))) continue;
    double dC = 0.0;
    for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e)
      dC += entries_[e].lin.dot(start_x_[entries_[e].body]) + entries_[e].ang.dot(start_phi_[entries_[e].body]);
    if (!(std::abs(dC) <= tolerance)) return true;
  }
  return false;
}

void DirectSolver::linearizeAtStart(World& world, double h) {
  // The rows at the poses the substep started from (x_prev, q_prev): the
  // joints' anchors and the cables' attachments turn back with their
  // bodies; a rolling end stays where the cable update put it (endPoint).
  for (const BodyId id : bodies_) {
    BodyState& b = world.body(id);
    std::swap(b.x, b.x_prev);
    std::swap(b.q, b.q_prev);
  }
  at_start_ = true;
  evaluate(world, h);
  at_start_ = false;
  for (Entry& e : entries_) weigh(e);  // by W at the start poses (evaluateBodies)
  for (const BodyId id : bodies_) {
    BodyState& b = world.body(id);
    std::swap(b.x, b.x_prev);
    std::swap(b.q, b.q_prev);
  }
  start_ = entries_;
  start_curvature_ = curvature_;
}

void DirectSolver::chooseStartRows() {
  // SHAKE's projection along G(x_n) must reach the constraint from x~; a
  // row whose gradient turns much over the substep (a spool spinning a
  // radian, a snap) would not converge in a few iterations, or not at all.
  // Such a row keeps the gradient at the poses solved, |G_n - G|_W >
  // kStartTurnLimit |G|_W (|g|_W^2 = g W g^T, the row's own diagonal).
  // So does every row of an island with contacts: they are swept between
  // the iterations along their normals at the poses solved, and rows along
  // start gradients fought them, worse with every iteration (the segmented
  // rope on its wheel, the most it made in a frame: 0.3 J at 10 x 2, 623 J
  // at 10 x 32, 13,640 J at 32 x 32; with only the rows on bodies in
  // contact at the end, still 1,763 J at 32 x 32).
  use_start_.assign(rows_.size(), 0);
  if (touching_) return;
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const Row& row = rows_[r];
    double norm = 0.0, change = 0.0;
    for (int e = row.first_entry; e < row.first_entry + row.entry_count; ++e) {
      Entry now = entries_[e];
      weigh(now);  // by W at the poses solved (evaluate() left the entries unweighed)
      Entry d = now;
      d.lin = start_[e].lin - now.lin;
      d.ang = start_[e].ang - now.ang;
      weigh(d);
      norm += now.lin.dot(now.wlin) + now.ang.dot(now.wang);
      change += d.lin.dot(d.wlin) + d.ang.dot(d.wang);
    }
    use_start_[r] = change <= kStartTurnLimit * kStartTurnLimit * norm;
  }
}

bool DirectSolver::violated(int r, double value, double tolerance) const {
  return (hi_[r] == 0.0 && value > tolerance) || (lo_[r] == 0.0 && value < -tolerance);
}

bool DirectSolver::met(int r, double value, double tolerance) const {
  const double residual = value + alpha_[r] * lambda_[r];
  // A row held at a bound is met when it asks to go further.
  if ((lambda_[r] >= hi_[r] && residual <= 0.0) || (lambda_[r] <= lo_[r] && residual >= 0.0)) return true;
  return std::abs(residual) <= tolerance;  // NaN is not met
}

bool DirectSolver::converged(double tolerance) const {
  if (!(tolerance > 0.0)) return false;
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const int row = static_cast<int>(r);
    if (state_[r] == State::Off) {  // met unless violated (a limit its drive is to lift off)
      if (violated(row, C_[r], tolerance)) return false;
      continue;
    }
    // A row fixed at a finite cap (a motor stalled at its most torque, a
    // slipping brake) is met as a free one is: a new substep starts its
    // lambda at 0, inside its bounds (a motor driving a rotor into its stop
    // found everything met there and pushed nothing). An unlimited drive
    // fixed against its limit (the limit wins) or a row let go at 0 stays
    // as the solve fixed it.
    const bool capped = state_[r] == State::Fixed && std::isfinite(lo_[r]) && std::isfinite(hi_[r]) &&
                        lo_[r] != 0.0 && hi_[r] != 0.0;
    if ((state_[r] == State::Free || capped) && !met(row, C_[r], tolerance)) return false;
  }
  return true;
}

void DirectSolver::warmStiffness(BodyFrame& f, const Mat3& K, std::size_t i) {
  const BodyState& b = *f.state;
  // The start projection's rows were weighed at the substep's start poses
  // (start_): they take this W, whatever it is.
  reweigh_[i] = !start_.empty();
  // Every |eigenvalue| of K (at most its Frobenius norm) below v . I v:
  // none is kept, without the eigenvectors.
  if (K.norm() < 0.5 * leastMomentBound(b.inertia)) return;
  const Mat3 inertia = f.R * b.inertia * f.R.transpose();
  Eigen::SelfAdjointEigenSolver<Mat3> eig;
  eig.computeDirect(K);
  Vec3 k = eig.eigenvalues().cwiseAbs();
  for (int a = 0; a < 3; ++a) {
    const Vec3 v = eig.eigenvectors().col(a);
    if (k[a] <= v.dot(inertia * v)) k[a] = 0.0;
  }
  if (k.isZero()) return;
  stiffened_ = true;
  f.inv_inertia = stiffenedInverse(inertia, eig.eigenvectors(), k);
  reweigh_[i] = 1;
}

void DirectSolver::stiffenLateral(BodyFrame& f, std::size_t i) {
  // As warmStiffness, in every iteration: only |K_x|'s eigenvalues above
  // the mass (|K_x| is positive semidefinite); the plain step contracts
  // below that.
  const double mass = 1.0 / f.inv_mass;
  const Mat3& K = lateral_stiffness_[i];
  if (K.norm() <= mass) return;
  Eigen::SelfAdjointEigenSolver<Mat3> eig;
  eig.computeDirect(K);
  Vec3 k = eig.eigenvalues();
  for (int a = 0; a < 3; ++a)
    if (k[a] <= mass) k[a] = 0.0;
  if (k.isZero()) return;
  stiffened_ = true;
  const Mat3& V = eig.eigenvectors();
  f.inv_mass_x = (mass * Mat3::Identity() + V * k.asDiagonal() * V.transpose()).inverse();
  f.stiff_x = true;
  reweigh_[i] = 1;
}

double DirectSolver::newtonResidual(bool bounded) {
  // Newton's step on M (x - x~) = J(x)^T lambda, C(x) + alpha~ lambda = 0
  // (XPBD eq. 8-9) from the iterate x, lambda:
  //   [M - K  -J^T] [dx     ]     [g           ]   g = M (x - x~) - J^T lambda,
  //   [J   alpha~ ] [dlambda] = - [C + alpha~ l],  K = sum lambda d2C/dx2.
  // XPBD drops g (and K): it moves along each iterate's gradient, and
  // converges to a projection along gradients near x~, not the implicit
  // one (DESIGN "Newton's residual and geometric stiffness"). Eliminating
  // dx = W~ (J^T dlambda - g), W~ = (M + |K|)^-1, leaves the usual system
  // with C shifted by J dx0, dx0 = -W~ g, and dx0 added to the motion.
  // |K| (K's eigenvalues made positive: Andrews et al. 2017; each body's
  // rotation block, and the translation block of one only cables hold)
  // changes how fast it converges, not where: a body whose rows'
  // lambda turns with it (a light block under a heavy hook) then stops
  // flipping from frame to frame. The first iteration has lambda = 0, so
  // its K is the last substep's, where K exceeds the inertia alone: below
  // that the plain step contracts and is more accurate. A body this solve
  // turned by more than kNewtonTurn takes XPBD's steps: its rows' gradients
  // at the end say little of the impulses that turned it (a tie point on a
  // 1 cm spool going round ten radians a substep; Newton's residual there
  // made energy).
  const std::size_t m = frames_.size();
  for (std::size_t i = 0; i < m; ++i) {
    shift_x_[i].setZero();
    shift_phi_[i].setZero();
    if (frames_[i].inv_axial > 0.0) axial_stiffness_[i] = 0.0;
    else stiffness_[i].setZero();
    lateral_stiffness_[i].setZero();
    reweigh_[i] = 0;
  }
  const bool warm = first_solve_ && last_lambda_.size() == lambda_.size();
  const std::vector<double>& stiff = warm ? last_lambda_ : lambda_;
  stiffened_ = false;
  for (std::size_t i = 0; i < entries_.size(); ++i) {  // -J^T lambda and K, per body
    const Entry& e = entries_[i];
    const double l = lambda_[e.row];
    if (l != 0.0) {
      shift_x_[e.body] -= l * e.lin;
      shift_phi_[e.body] -= l * e.ang;
    }
    if (stiff[e.row] == 0.0) continue;
    // A span end's sideways curvature, on a body that only cables hold: a
    // light one between taut spans (a 50 g bead between a ceiling and 40
    // kg, a floating pulley) is a pendulum of (h omega)^2 = |lambda| / (m
    // length) that no row holds, and Newton's steps without it diverged
    // past 1 (the bead flung metres sideways a solve). A jointed body's
    // rows hold it, and the block-diagonal |K| of two light bodies on one
    // span (the hand's knuckles) slowed their solve: 0.28 rad from rest
    // at 1 x 2, where it converged in 6.
    if (bend_[i] > 0.0 && !jointed_[e.body] && frames_[e.body].inv_axial == 0.0) {
      const double n2 = e.lin.squaredNorm();
      if (n2 > 0.0)
        lateral_stiffness_[e.body] +=
            (std::abs(stiff[e.row]) * bend_[i]) * (Mat3::Identity() - e.lin * e.lin.transpose() / n2);
    }
    if (e.flat) continue;
    if (frames_[e.body].inv_axial > 0.0) axial_stiffness_[e.body] += stiff[e.row] * e.axial;
    else stiffness_[e.body] += stiff[e.row] * curvature_[i];
  }
  // Per body: its g, which newtonStep() turns into dx0 = -W~ g in place,
  // and a bound on |dx0| for any W~ <= W (|K| only adds to M): m or rad,
  // 1 % above the largest |W g| so that rounding in W~ cannot pass it.
  // The sizes' squares, and one square root at the end: the same bits, as
  // the root is monotonic and correctly rounded.
  moved_size_ = 0.0;
  if (first_solve_ && !lifted_) return 0.0;  // no lambda and no motion yet: g = 0
  double moved2 = 0.0, bound2 = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    const BodyFrame& f = frames_[i];
    const BodyState& b = *f.state;
    moved2 = std::max({moved2, moved_x_[i].squaredNorm(), moved_phi_[i].squaredNorm()});
    if (moved_phi_[i].norm() > kNewtonTurn) continue;  // XPBD's steps: no residual
    Vec3 &g_x = shift_x_[i], &g_phi = shift_phi_[i];
    if (f.inv_mass > 0.0) g_x += moved_x_[i] / f.inv_mass;
    if (f.inv_axial == 0.0) {  // a rotor's is its turn about its axle alone (newtonStep)
      world_inertia_[i] = f.R * b.inertia * f.R.transpose();
      g_phi += world_inertia_[i] * moved_phi_[i];
    }
    if (!bounded) continue;
    double turn_bound;
    if (f.inv_axial > 0.0) {
      const double g_u = f.axle.dot(moved_phi_[i]) * f.axial_inertia + f.axle.dot(g_phi);
      turn_bound = std::abs(g_u) / f.axial_inertia;
    } else {
      if (hub_of_[i] < 0 && f.inv_mass > 0.0 && !stiffness_[i].isZero()) {  // W~ = (I + |K|)^-1 <= W
        const double least = leastMomentBound(b.inertia);  // at most the world inertia's least eigenvalue
        turn_bound = least > 0.0 ? g_phi.norm() / least : kInf;
      } else {  // W~ = W
        turn_bound = (f.inv_inertia * g_phi).norm();
      }
    }
    const double x2 = (f.inv_mass * g_x).squaredNorm(), turn2 = turn_bound * turn_bound;
    if (x2 < kInf && turn2 < kInf) bound2 = std::max({bound2, x2, turn2});
    else bounded = false;  // not finite (NaN included): never met by the bound
  }
  moved_size_ = std::sqrt(moved2);
  return bounded ? 1.01 * std::sqrt(bound2) : kInf;
}

void DirectSolver::newtonStep() {
  const std::size_t m = frames_.size();
  const bool warm = first_solve_ && last_lambda_.size() == lambda_.size();
  double shift2 = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    BodyFrame& f = frames_[i];
    if (first_solve_ && f.inv_axial == 0.0) {
      // The substep's first solve: g = 0, and dx0 = 0 (the signed zeros
      // the general case below gives). W stays the plain one
      // (evaluateBodies) but where the last substep's K exceeds the
      // inertia along an eigenvector of K.
      if (hub_of_[i] < 0 && f.inv_mass > 0.0 && !stiffness_[i].isZero()) warmStiffness(f, stiffness_[i], i);
      if (hub_of_[i] < 0 && f.inv_mass > 0.0 && !lateral_stiffness_[i].isZero()) stiffenLateral(f, i);
      shift_x_[i] = -f.inv_mass * shift_x_[i];
      shift_phi_[i] = -(f.inv_inertia * shift_phi_[i]);
      shift2 = std::max({shift2, shift_x_[i].squaredNorm(), shift_phi_[i].squaredNorm()});
      continue;
    }
    if (moved_phi_[i].norm() > kNewtonTurn) {  // XPBD's steps, W and no residual
      if (f.inv_axial > 0.0 && f.inv_axial != f.axial_inv0) {
        f.inv_axial = f.axial_inv0;
        reweigh_[i] = 1;
      }
      shift_x_[i].setZero();
      shift_phi_[i].setZero();
      continue;
    }
    const Vec3 g_x = shift_x_[i], g_phi = shift_phi_[i];
    if (f.inv_axial > 0.0) {  // a rotor: its turn about its axle alone
      const double inertia = f.axial_inertia;
      const double g_u = f.axle.dot(moved_phi_[i]) * inertia + f.axle.dot(g_phi);
      // A tie point on it (a spool run out) turns with it; a rolling end's
      // tangent point does not, and adds nothing.
      double k = std::abs(axial_stiffness_[i]);
      if (warm && k <= inertia) k = 0.0;
      stiffened_ = stiffened_ || k > 0.0;
      // evaluate() weighed it with the last iteration's W; the start
      // projection's rows with the substep's (start_).
      const double inv_axial = 1.0 / (inertia + k);
      if (inv_axial != f.inv_axial || !start_.empty()) {
        f.inv_axial = inv_axial;
        reweigh_[i] = 1;
      }
      shift_x_[i].setZero();
      shift_phi_[i] = -f.axle * (f.inv_axial * g_u);
    } else {
      if (hub_of_[i] < 0 && f.inv_mass > 0.0 && !stiffness_[i].isZero()) {
        const Mat3& inertia = world_inertia_[i];
        const Mat3& K = stiffness_[i];
        stiffened_ = true;
        // Every iteration after the first keeps all of |K|: K itself where
        // it is positive semidefinite (every principal minor >= 0), -K
        // where negative, else its eigenvalues made positive.
        if (const double sign = semidefinite(K); sign != 0.0) {
          f.inv_inertia = (inertia + sign * K).inverse();
        } else {
          Eigen::SelfAdjointEigenSolver<Mat3> eig;
          eig.computeDirect(K);
          f.inv_inertia = stiffenedInverse(inertia, eig.eigenvectors(), eig.eigenvalues().cwiseAbs());
        }
        reweigh_[i] = 1;
      }
      if (hub_of_[i] < 0 && f.inv_mass > 0.0 && !lateral_stiffness_[i].isZero()) stiffenLateral(f, i);
      shift_x_[i] = f.stiff_x ? Vec3(-(f.inv_mass_x * g_x)) : Vec3(-f.inv_mass * g_x);
      shift_phi_[i] = -(f.inv_inertia * g_phi);
    }
    shift2 = std::max({shift2, shift_x_[i].squaredNorm(), shift_phi_[i].squaredNorm()});
  }
  shift_size_ = std::sqrt(shift2);
}

bool DirectSolver::linearRows(const World& world) const {
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const Row& row = rows_[r];
    if (row.source == Source::Path) {
      if (!linear_[r]) return false;
      continue;
    }
    if (row.source != Source::Hinge) return false;
    // A rotor's hinge rows (its drive and limits) turn it about its axle.
    const HingeJoint& j = world.hinges()[row.index];
    if (!world.body(j.a).isRotor() && !world.body(j.b).isRotor()) return false;
  }
  return true;
}

void DirectSolver::shiftValues() {
  for (Entry& e : entries_) {
    if (reweigh_[e.body] || !e.weighed) weigh(e);
    // None at the first iteration but from a lifted start (startPoint).
    // Exact zeros: a shift below Eigen's isZero() precision (1e-12) is
    // still a motion the bodies make (dx_ includes it), so C must see it.
    if (shift_x_[e.body] != Vec3::Zero() || shift_phi_[e.body] != Vec3::Zero())
      C_[e.row] += e.lin.dot(shift_x_[e.body]) + e.ang.dot(shift_phi_[e.body]);
  }
}

double DirectSolver::extrapolation() {
  // Aitken's delta-squared process on the sizes of the iteration's steps
  // (the scalar form of Irons and Tuck's 1969 accelerator, Kuettler and
  // Wall's 2008 dynamic relaxation). Where the iteration converges
  // linearly (Newton's residual under |K|: DESIGN, "Newton's residual and
  // geometric stiffness"), its error near the solution obeys
  // e_{k+1} = T e_k, and the slowest mode of T, contracting by rho a step,
  // soon leads: the steps s_k = (T - I) e_k shrink by rho too, and
  // e_k = -s_k / (1 - rho) along it. A step of s_k / (1 - rho) takes that
  // mode out. For the residual T is the constrained W~ times 2 K+, both
  // semidefinite, so its eigenvalues are real and in [0, rho]: a faster
  // mode is overshot by at most omega - 1 of itself, and the plain steps
  // between extrapolated ones damp it. Only a steady geometric tail is
  // extrapolated: a plain step's ratio within kAitkenSteady of the last
  // one measured (rho is T's, so the one before an extrapolation still
  // counts), a step under kAitkenTail of the substep's motion, an active
  // set that settled, and no lambda pushed past its bound. Without the
  // first two the bow at 10 x 10 blew up after its release: a solve that
  // does not converge (its steps bouncing by 0.5 to 1.5) was thrown away
  // by extrapolating its bounces. The stop (iterate()) is unchanged: this
  // changes how many iterations meet it, not where. Contacts and weighted
  // paths swept between the iterations move the bodies too, and the tail
  // is then the solve's and theirs together: servin.json's plate resting
  // on the ground, its cables and its static friction trading a slip 0.17
  // times the last one each iteration, took 6.7 solves a frame at 1 x 10
  // without extrapolation there, 5.5 with it (rope_segments.json fewer
  // too; no shipped scene more).
  if (first_solve_) {  // the projection: nothing to compare its step with
    last_step_ = 0.0;
    last_rho_ = 0.0;
    extrapolated_ = false;
    return 1.0;
  }
  double step2 = 0.0;
  for (std::size_t i = 0; i < frames_.size(); ++i)
    step2 = std::max({step2, (dx_[i] + shift_x_[i]).squaredNorm(), (dphi_[i] + shift_phi_[i]).squaredNorm()});
  const double step = std::sqrt(step2);
  // After an extrapolated step the next one measures the extrapolation,
  // not T: it is not extrapolated, and the ratio before it is kept.
  const bool after = extrapolated_;
  const double rho = last_step_ > 0.0 && !after ? step / last_step_ : 0.0;
  const bool steady = std::abs(rho - last_rho_) <= kAitkenSteady * rho;
  last_step_ = step;
  if (!after) last_rho_ = rho;
  extrapolated_ = false;
  // moved_size_: the substep's motion before this step (newtonResidual).
  if (!settled_ || !steady || !(rho > kAitkenLeast && rho < kAitkenMost) ||
      step > kAitkenTail * moved_size_)
    return 1.0;
  const double omega = 1.0 / (1.0 - rho);
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const double total = lambda_[r] + omega * dlambda_[r];
    if (total > hi_[r] || total < lo_[r]) return 1.0;
  }
  for (double& dl : dlambda_) dl *= omega;
  extrapolated_ = true;
  return omega;
}

bool DirectSolver::iterate(World& world, double h) {
  if (rows_.empty()) return false;
  if (met_) {  // the last iteration's motion met every row: this one would find so and end the substep
    met_ = plain_solve_ = false;
    return false;
  }
  evaluate(world, h);
  if (!start_.empty()) {
    if (first_iteration_) chooseStartRows();
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      if (!use_start_[r]) continue;
      const Row& row = rows_[r];
      std::copy(start_.begin() + row.first_entry, start_.begin() + row.first_entry + row.entry_count,
                entries_.begin() + row.first_entry);
      std::copy(start_curvature_.begin() + row.first_entry,
                start_curvature_.begin() + row.first_entry + row.entry_count, curvature_.begin() + row.first_entry);
    }
  }
  first_solve_ = first_iteration_;
  first_iteration_ = false;
  // (Tolerance 0, to time every iteration, still meets rows to 1e-10 m.)
  const double scale = direct::substepTolerance(1.0, h);
  const double tolerance = world.settings().tolerance * scale;
  // After a first solve with every body's plain W (no stiffness, and no
  // residual yet) and rows whose gradients J do not change as the bodies
  // move (linearRows), the bodies moved dx = W J^T lambda: Newton's
  // residual M dx - J^T lambda is 0 to rounding, so met rows end the
  // substep without computing it.
  const bool plain = plain_solve_;
  plain_solve_ = false;
  if (plain && converged(tolerance)) return false;
  // Met: every row, and Newton's residual to kNewtonRelative of what the
  // solve moved the bodies this substep (to the tolerance the hand took
  // all 20 iterations at rest: its residual, on the first phalanges whose
  // K is 18 times their inertia about the hinge, falls by about 0.4 an
  // iteration). Where the residual's bound for any W~ meets it, W~ is not
  // needed.
  const bool rows_met = converged(tolerance);
  const double residual_bound = newtonResidual(rows_met);
  const double enough = std::max(tolerance, kNewtonRelative * moved_size_);
  if (rows_met && residual_bound <= enough) return false;
  newtonStep();
  if (rows_met && shift_size_ <= enough) return false;
  plain_solve_ = first_solve_ && !lifted_ && !stiffened_ && start_.empty() && linearRows(world);
  shiftValues();
  warmStartCaps();
  const double solve_tolerance = tolerance > 0.0 ? tolerance : 1e-10 * scale;
  solveActiveSet(solve_tolerance);
  double omega = extrapolation();
  // A step that turns a fixed end past its line-up (line_up.h: a 2 g crank
  // under 1 kg swung radians each way a solve, and v = dx / h made energy
  // without bound) is solved again with that body's turn stiffened, and
  // one that turns it far with the end's gradient its turn's secant, then
  // shortened, lambda with the motion (a damped Newton step), to whatever
  // still turns one past: a row that nothing else can move meets the rest
  // later.
  // So is a first solve that moves a span's fixed ends past their closest
  // approach, with the translation of the end that moved the more
  // stiffened (stiffenMoves).
  stiffened_turns_.clear();
  stiffened_moves_.clear();
  for (int round = 0; round < kLineUpRounds && (stiffenTurns(omega, h) | stiffenMoves(omega) | stiffenStores(omega));
       ++round) {
    warmStartCaps();
    solveActiveSet(solve_tolerance);
    omega = 1.0;
    extrapolated_ = false;
  }
  restoreTurns();
  restoreMoves();
  const double share = lineUpShare(omega, h);
  if (share < 1.0) {
    omega *= share;
    for (double& dl : dlambda_) dl *= share;
  }
  double step2 = 0.0;
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    dx_[i] = omega * (dx_[i] + shift_x_[i]);
    dphi_[i] = omega * (dphi_[i] + shift_phi_[i]);
    step2 = std::max({step2, dx_[i].squaredNorm(), dphi_[i].squaredNorm()});
    moved_x_[i] += dx_[i];
    moved_phi_[i] += dphi_[i];
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
  // The caps the next iteration starts from: a settled active set's. One
  // that ran out of passes clamps whatever it had (a motor spinning a
  // 512-wheel chain up included, and starting there threw the chain about)
  // and leaves the caps as they were.
  for (std::size_t r = 0; r < rows_.size() && settled_; ++r) {
    const double total = lambda_[r] + dlambda_[r];
    const bool cap_hi = std::isfinite(hi_[r]) && hi_[r] != 0.0 && total >= hi_[r];
    const bool cap_lo = std::isfinite(lo_[r]) && lo_[r] != 0.0 && total <= lo_[r];
    at_cap_[r] = cap_hi ? 1 : cap_lo ? -1 : 0;
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
  // A plain solve of linear rows moved the bodies by dx, and each row now
  // stands at C + J dx exactly (predictSpan): that is what the next
  // iteration would evaluate, find met and stop at (Hilbert3's second
  // evaluation a substep: 5 % of its solve). Where a contact or a weighted
  // path may move a body in between, or a row is damped (its C and alpha~
  // the damping's, which the prediction does not redo), the next
  // iteration evaluates.
  met_ = plain_solve_ && moves_alone_ && settled_ && !damped_ && omega == 1.0 && tolerance > 0.0 &&
         metAsSolved(tolerance);
  // A settled solve that left unmet rows where they were: a row no motion
  // can meet, its dependency held by the others (the gym's lat bar landing
  // on its stop under its capped drive, the handle cable taut: 2.8 mm it
  // cannot take up in that substep). Nothing else moves the bodies in
  // between, so every iteration left would evaluate and solve the same:
  // 18 of them at that frame of the paper's 1 x 20.
  const double stalled = kStalled * tolerance;
  if (!rows_met && moves_alone_ && settled_ && share == 1.0 && tolerance > 0.0 && step2 <= stalled * stalled)
    met_ = true;
  return true;
}

double DirectSolver::turnPast(const FixedEnd& f, double omega, double h, double& most) const {
  const Vec3 dphi = omega * (dphi_[f.body] + shift_phi_[f.body]);
  const double angle = dphi.norm();
  most = angle;
  if (angle > trustedStepTurn(f.reach, h)) most = turnToLineUp(f.model(dphi / angle), 1.0);
  return angle;
}

bool DirectSolver::stiffenTurns(double omega, double h) {
  bool changed = false;
  for (const FixedEnd& f : fixed_ends_) {
    double most;
    const double angle = turnPast(f, omega, h, most);
    if (!(angle > trustedStepTurn(f.reach, h))) continue;
    // The row's model promises l1 x turn of length from the end's turn; the
    // turn gives the secant's share of it (turnSecant), a half at the
    // line-up: the end's gradient is that share of its own for this solve,
    // or the rest were left for the next substep, where v = dx / h made it
    // a velocity (a 2 g spool's tie point past its line-up at 100 x 1 threw
    // the 1 kg weight up at 9.5 m/s from 7.5 down).
    const double turn = std::min(angle, most);
    const Vec3 e = omega * (dphi_[f.body] + shift_phi_[f.body]) / angle;
    const TurnModel turning = f.model(e);
    const double secant = turnSecant(turning, turn);
    // Within kSecantSlack of its model, or of less length than the step may
    // leave unmet at kTrustedStepSpeed, the turn keeps its model.
    const double modelled = std::abs(turning.l1) * turn;  // m
    const double slack =
        modelled > kTrustedStepSpeed * h / kSecantSlack ? kTrustedStepSpeed * h / modelled : kSecantSlack;
    const std::optional<Vec3> model = modelGradient(f.entry, secant, angle > most, slack);
    if (!model) continue;
    // Above 1 only the moment about the turn's axis grows (the others are
    // the model's, and may be r where that one is nearly 0). Clamped at 1,
    // a 2 g spool whose tie point its spin had carried near the far side
    // of its rim could not turn it back for what its tangent promised, and
    // its 100 kg load was thrown up at 2.4 m/s instead (307 J at 2 x 2).
    const Vec3 change =
        secant <= 1.0 ? Vec3((secant - 1.0) * f.moment) : Vec3((secant - 1.0) * e.dot(f.moment) * e);
    Entry& own = entries_[f.entry];
    own.ang = *model + change;
    weigh(own);
    changed = true;
    if (angle > most) stopTurn(f.body, f.row, own, most, angle);
  }
  if (changed) reweighStiffened();
  return changed;
}

std::optional<Vec3> DirectSolver::modelGradient(int entry, double secant, bool past, double slack) {
  if (secant_of_[entry] < 0) {
    if (!past && std::abs(secant - 1.0) < slack) return std::nullopt;
    secant_of_[entry] = static_cast<int>(secants_.size());
    secants_.push_back({entry, entries_[entry].ang});
  }
  return secants_[secant_of_[entry]].ang;
}

void DirectSolver::reweighStiffened() {
  for (Entry& e : entries_)
    for (const Stiffened& t : stiffened_turns_)
      if (e.body == t.body) weigh(e);
}

void DirectSolver::stopTurn(int body, int r, const Entry& own, double most, double angle) {
  // The end's row alone, as Gauss-Seidel's visit: dl = target / (rest +
  // s a) turns it |dl| s per, a = j W j^T its own share of the row's w.
  // Where that says nothing (nothing else in the row moves, or the row's
  // other rows hold the rest), the turn asked shrinks in proportion.
  const Row& row = rows_[r];
  double w_all = alpha_[r];
  for (int k = row.first_entry; k < row.first_entry + row.entry_count; ++k)
    w_all += entries_[k].lin.dot(entries_[k].wlin) + entries_[k].ang.dot(entries_[k].wang);
  const double a = own.ang.dot(own.wang), per = own.wang.norm(), rest = w_all - a;
  const double target = std::abs(C_[r] + alpha_[r] * lambda_[r]);
  double s = most / angle;
  if (rest > 1e-12 * w_all && target * per > most * a) s = std::min(s, most * rest / (target * per - most * a));
  if (std::none_of(stiffened_turns_.begin(), stiffened_turns_.end(),
                   [&](const Stiffened& t) { return t.body == body; })) {
    const BodyFrame& b = frames_[body];
    stiffened_turns_.push_back({body, b.inv_inertia, b.inv_axial});
  }
  scaleTurn(body, s);  // on top of the last round's, and of another end's on it
}

bool DirectSolver::stiffenStores(double omega) {
  bool changed = false;
  for (const StoredEnd& f : stored_ends_) {
    const double angle = storeTurn(f, omega), left = std::max(0.0, f.left);
    if (!(angle > left)) continue;  // within its store, or winding on
    // Of the model's r a radian, the turn gains r for the store's turn and
    // r sin(past) after it: the cable's end leaves the tangent point along
    // the span and turns on towards it.
    const double most = left + kQuarterTurn, turn = std::min(angle, most);
    const double secant = (left + std::sin(turn - left)) / turn;
    const std::optional<Vec3> model = modelGradient(f.entry, secant, angle > most, kSecantSlack);
    if (!model) continue;
    Entry& own = entries_[f.entry];
    own.ang = *model + (secant - 1.0) * f.pays.dot(*model) * f.pays;
    weigh(own);
    changed = true;
    if (angle > most) stopTurn(f.body, f.row, own, most, angle);
  }
  if (changed) reweighStiffened();
  return changed;
}

void DirectSolver::scaleTurn(int body, double scale) {
  BodyFrame& b = frames_[body];
  if (b.inv_axial > 0.0) b.inv_axial *= scale;
  else b.inv_inertia *= scale;
  b.turn_scale *= scale;  // a hub's (assembleHubs)
}

void DirectSolver::restoreTurns() {
  for (const Secant& t : secants_) {
    entries_[t.entry].ang = t.ang;
    weigh(entries_[t.entry]);
    secant_of_[t.entry] = -1;
  }
  secants_.clear();
  if (stiffened_turns_.empty()) return;
  for (const Stiffened& t : stiffened_turns_) {
    BodyFrame& b = frames_[t.body];
    b.inv_inertia = t.inv_inertia;
    b.inv_axial = t.inv_axial;
    b.turn_scale = 1.0;
  }
  reweighStiffened();
  stiffened_turns_.clear();
}

Vec3 DirectSolver::pointStep(int body, const Vec3& arm, double omega) const {
  if (body < 0) return Vec3::Zero();
  const Vec3 turn = omega * (dphi_[body] + shift_phi_[body]);
  const Vec3 move = frames_[body].inv_mass > 0.0 ? Vec3(omega * (dx_[body] + shift_x_[body])) : Vec3::Zero();
  return Vec3(move + turn.cross(arm));
}

bool DirectSolver::stiffenMoves(double omega) {
  // A span's fixed ends moved by s D (D the step's relative motion, d the
  // span) are |d + s D| apart: the row's model, |d| + s u . D, shortens
  // the span without end where u . D < 0, but it is shortest at
  // s* = -(d . D) / |D|^2 and longer again past it. A step with s* < 1
  // moves the ends sideways past their closest approach: a 5 g bead
  // between a ceiling and a 40 kg load, a centimetre off their line, was
  // thrown 12 cm to the far side for a length its second order takes back
  // (the model's sideways gradient is the offset over the span, and the
  // light bead's motion the cheapest), then back. The body that moves the
  // more of the two takes s* of its W: solved again, the rest of the
  // correction goes to the others (the load lifted), as stiffenTurns does
  // for a turn past its line-up.
  if (!first_solve_) return false;  // later solves: Newton's, with the spans' sideways stiffness (bend_)
  const auto moved = [&](int body) {
    if (body < 0 || hub_of_[body] >= 0 || !(frames_[body].inv_mass > 0.0)) return -1.0;
    return (omega * (dx_[body] + shift_x_[body])).norm();
  };
  bool changed = false;
  for (const FixedSpan& f : fixed_spans_) {
    const Vec3 D = pointStep(f.body1, f.arm1, omega) - pointStep(f.body0, f.arm0, omega);
    const double along = f.d.dot(D), D2 = D.squaredNorm();
    if (!(along < 0.0 && -along < D2)) continue;  // s* >= 1: not past
    // Below kTrustedStepTurn of the span's turn the model is off by 0.005
    // of the span at most.
    if (!(D2 - along * along / f.d.squaredNorm() > kTrustedStepTurn * kTrustedStepTurn * f.d.squaredNorm())) continue;
    const int body = moved(f.body1) > moved(f.body0) ? f.body1 : f.body0;
    if (!(moved(body) > 0.0)) continue;
    BodyFrame& b = frames_[body];
    if (std::none_of(stiffened_moves_.begin(), stiffened_moves_.end(),
                     [&](const StiffenedMove& m) { return m.body == body; }))
      stiffened_moves_.push_back({body, b.inv_mass, b.inv_mass_x});
    const double s = -along / D2;
    if (s < kLeastMoveShare) continue;
    b.inv_mass *= s;
    b.inv_mass_x *= s;
    changed = true;
  }
  if (changed)
    for (Entry& e : entries_)
      for (const StiffenedMove& m : stiffened_moves_)
        if (e.body == m.body) weigh(e);
  return changed;
}

void DirectSolver::restoreMoves() {
  if (stiffened_moves_.empty()) return;
  for (const StiffenedMove& m : stiffened_moves_) {
    frames_[m.body].inv_mass = m.inv_mass;
    frames_[m.body].inv_mass_x = m.inv_mass_x;
  }
  for (Entry& e : entries_)
    for (const StiffenedMove& m : stiffened_moves_)
      if (e.body == m.body) weigh(e);
  stiffened_moves_.clear();
}

double DirectSolver::lineUpShare(double omega, double h) const {
  double share = 1.0;
  for (const FixedEnd& f : fixed_ends_) {
    double most;
    const double angle = turnPast(f, omega, h, most);
    if (angle > most) share = std::min(share, most / angle);
  }
  for (const StoredEnd& f : stored_ends_) {
    const double angle = storeTurn(f, omega), most = std::max(0.0, f.left) + kQuarterTurn;
    if (angle > most) share = std::min(share, most / angle);
  }
  return share;
}

bool DirectSolver::metAsSolved(double tolerance) const {
  for (int r = 0; r < static_cast<int>(rows_.size()); ++r) {
    const double value = predictedValue(r);
    if (violated(r, value, tolerance) || !met(r, value, tolerance)) return false;
  }
  return true;
}

}  // namespace reeve
