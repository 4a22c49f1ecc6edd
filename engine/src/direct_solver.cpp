#include "direct_solver.h"

#include <algorithm>
#include <cassert>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include "joint_row_sets.h"
#include "reeve/engine/world.h"

namespace reeve {
namespace {

using joint_rows::JointRowSet;
using joint_rows::kInf;

// A pivot this small against its diagonal marks a row that depends on
// earlier ones (sparse_ldlt.h). Rows of light wheels between heavy loads
// stay far above it (a 1e-6 kg wheel under 1 kg loads: 1e-6).
constexpr double kDropTolerance = 1e-12;
// Active-set passes per iteration; almost always one or two are enough.
constexpr int kMaxPasses = 8;

// The number of rows of a joint with `bilateral` locked rows and the
// given drive and limits (JointRowSet's layout).
int jointRowCount(int bilateral, bool driven, bool limited) { return bilateral + (driven ? 1 : 0) + (limited ? 2 : 0); }

bool moves(const World& world, BodyId id) { return world.body(id).moves(); }

}  // namespace

void DirectSolver::describe(World& world, std::vector<int>& sig) const {
  sig.clear();
  const auto joint = [&](Source source, int index, BodyId a, BodyId b, int rows) {
    if (!moves(world, a) && !moves(world, b)) return;
    sig.insert(sig.end(), {static_cast<int>(source), index, rows, moves(world, a) ? a : kWorldBody,
                           moves(world, b) ? b : kWorldBody});
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
    if (!p.enabled) continue;
    const std::size_t head = sig.size();
    sig.insert(sig.end(), {static_cast<int>(Source::Path), i, 1});
    for (const PathPoint& point : p.points)
      if (moves(world, point.body) && std::find(sig.begin() + head + 3, sig.end(), point.body) == sig.end())
        sig.push_back(point.body);
    if (sig.size() == head + 3) {
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
      Row row{source, index, static_cast<int>(entries_.size()), static_cast<int>(moving.size()), 0, 0, 0};
      for (const BodyId id : moving) {
        Entry e;
        e.body = bodyIndex(id);
        entries_.push_back(e);
      }
      rows_.push_back(row);
    }
  }
  const int n = static_cast<int>(rows_.size());
  // Rows that share a moving body are coupled; order them to keep the
  // factor sparse (approximate minimum degree).
  std::vector<std::vector<int>> on_body(bodies_.size());
  for (int r = 0; r < n; ++r)
    for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e)
      on_body[entries_[e].body].push_back(e);
  std::vector<int> row_of(entries_.size());
  for (int r = 0; r < n; ++r)
    for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e) row_of[e] = r;
  std::vector<Eigen::Triplet<double>> triplets;
  for (const auto& list : on_body)
    for (const int e1 : list)
      for (const int e2 : list) triplets.emplace_back(row_of[e1], row_of[e2], 1.0);
  Eigen::SparseMatrix<double> pattern(n, n);
  pattern.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::AMDOrdering<int> amd;
  Eigen::AMDOrdering<int>::PermutationType order;
  amd(pattern, order);  // order.indices()[k]: the row eliminated k-th
  for (int k = 0; k < n; ++k) rows_[order.indices()[k]].position = k;
  // One matrix term per pair of entries on a body.
  pairs_.clear();
  std::vector<std::pair<int, int>> upper;
  for (const auto& list : on_body)
    for (std::size_t i = 0; i < list.size(); ++i)
      for (std::size_t j = i; j < list.size(); ++j) {
        const int p = rows_[row_of[list[i]]].position, q = rows_[row_of[list[j]]].position;
        pairs_.push_back({list[i], list[j], 0});
        upper.emplace_back(std::min(p, q), std::max(p, q));
      }
  const std::vector<int> slot = ldlt_.analyze(n, upper);
  std::vector<std::vector<Slot>> coupled(n);
  for (std::size_t i = 0; i < pairs_.size(); ++i) {
    pairs_[i].slot = slot[i];
    const int r1 = row_of[pairs_[i].e1], r2 = row_of[pairs_[i].e2];
    if (r1 == r2) continue;
    coupled[r1].push_back({slot[i], r2});
    coupled[r2].push_back({slot[i], r1});
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
  for (std::vector<double>* v : {&C_, &alpha_, &lo_, &hi_, &lambda_, &dlambda_, &rhs_, &x_}) v->assign(n, 0.0);
  state_.assign(n, State::Free);
  pulled_.assign(n, false);
  mirror_.assign(n, nullptr);
  dir_.assign(n, Eigen::Matrix<double, 6, 1>::Zero());
  linear_a_.assign(n, nullptr);
  angular_a_.assign(n, nullptr);
  full_.assign(ldlt_.values().size(), 0.0);
  const std::size_t m = bodies_.size();
  inv_mass_.assign(m, 0.0);
  inv_inertia_.assign(m, Mat3::Zero());
  dx_.assign(m, Vec3::Zero());
  dphi_.assign(m, Vec3::Zero());
  absorbed_.assign(m, Vec3::Zero());
}

void DirectSolver::prepare(World& world, double /*h*/) {
  describe(world, scratch_);
  if (scratch_ != signature_) {
    signature_.swap(scratch_);
    build(world);
  }
  // A cable that pulled at the end of the last substep starts this one in
  // the active set, even if it is exactly taut (C = 0) after integration:
  // otherwise a long taut cable would join in one span per pass.
  for (std::size_t r = 0; r < rows_.size(); ++r) pulled_[r] = lambda_[r] < 0.0;
  std::fill(lambda_.begin(), lambda_.end(), 0.0);
  std::fill(absorbed_.begin(), absorbed_.end(), Vec3::Zero());
}

void DirectSolver::evaluate(World& world, double h) {
  const double inv_h2 = 1.0 / (h * h);
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const BodyState& b = world.body(bodies_[i]);
    inv_mass_[i] = b.inv_mass;
    const Mat3 R = b.q.toRotationMatrix();
    inv_inertia_[i] = R * b.inv_inertia * R.transpose();
  }
  JointRowSet set;
  const int n = static_cast<int>(rows_.size());
  for (int r = 0; r < n;) {
    const Row& first = rows_[r];
    if (first.source == Source::Path || first.source == Source::Distance) {
      // C = sum of segment lengths - rest; dC/dp_i = u_{i-1} - u_i (a
      // distance constraint is a two-point path, pull-only if unilateral).
      std::array<PathPoint, 2> pair;
      const PathPoint* points;
      std::size_t count;
      double rest, compliance;
      double* lambda;
      bool unilateral = true;
      if (first.source == Source::Path) {
        PathConstraint& p = world.path(first.index);
        points = p.points.data();
        count = p.points.size();
        rest = p.rest_length;
        compliance = p.compliance;
        lambda = &p.lambda;
      } else {
        DistanceConstraint& c = world.distance(first.index);
        pair = {PathPoint{c.a, c.local_a}, PathPoint{c.b, c.local_b}};
        points = pair.data();
        count = 2;
        rest = c.rest_length;
        compliance = c.compliance;
        lambda = &c.lambda;
        unilateral = c.unilateral;
      }
      for (int e = first.first_entry; e < first.first_entry + first.entry_count; ++e) {
        entries_[e].lin.setZero();
        entries_[e].ang.setZero();
      }
      double length = 0.0;
      Vec3 prev_u = Vec3::Zero();
      for (std::size_t i = 0; i < count; ++i) {
        const BodyState& b = world.body(points[i].body);
        const Vec3 arm = b.q * points[i].local, pos = b.x + arm;
        Vec3 u = Vec3::Zero();
        if (i + 1 < count) {
          const BodyState& next = world.body(points[i + 1].body);
          const Vec3 d = next.x + next.q * points[i + 1].local - pos;
          const double l = d.norm();
          length += l;
          if (l >= 1e-12) u = d / l;
        }
        const Vec3 grad = prev_u - u;
        prev_u = u;
        if (!b.moves()) continue;
        for (int e = first.first_entry; e < first.first_entry + first.entry_count; ++e) {
          if (bodies_[entries_[e].body] != points[i].body) continue;
          entries_[e].lin += grad;
          entries_[e].ang += arm.cross(grad);
          break;
        }
      }
      C_[r] = length - rest;
      alpha_[r] = compliance * inv_h2;
      lambda_[r] = *lambda;
      mirror_[r] = lambda;
      lo_[r] = -kInf;
      hi_[r] = unilateral ? 0.0 : kInf;
      // Taut (C >= 0: a cable exactly at its rest length touches too), or
      // already pulling: in the active set.
      state_[r] = !unilateral || C_[r] >= 0.0 || lambda_[r] < 0.0 || pulled_[r] ? State::Free : State::Off;
      linear_a_[r] = angular_a_[r] = nullptr;
      ++r;
      continue;
    }
    // A joint: all its rows at once.
    BodyId a, b;
    Vec3 *linear_a, *angular_a;
    double compliance;
    switch (first.source) {
      case Source::Hinge: {
        HingeJoint& j = world.hinge(first.index);
        joint_rows::hingeRowSet(j, world.body(j.a), world.body(j.b), set);
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
    assert(r + count <= n && rows_[r + count - 1].source == first.source && rows_[r + count - 1].index == first.index);
    assert(r + count == n || rows_[r + count].source != first.source || rows_[r + count].index != first.index);
    const bool a_moves = world.body(a).moves(), b_moves = world.body(b).moves();
    for (int k = 0; k < count; ++k, ++r) {
      const bool bilateral = k < set.bilateral.count;
      const int c = k - set.bilateral.count;
      const Eigen::Matrix<double, 6, 1> s = bilateral ? Eigen::Matrix<double, 6, 1>(set.bilateral.dirs.col(k))
                                                      : set.clamped[c].dir;
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
      dir_[r] = s;
      linear_a_[r] = linear_a;
      angular_a_[r] = angular_a;
      if (bilateral) {
        C_[r] = set.bilateral.values[k];
        alpha_[r] = compliance * inv_h2;
        lo_[r] = -kInf;
        hi_[r] = kInf;
        mirror_[r] = nullptr;
        state_[r] = State::Free;
      } else {
        const joint_rows::ClampedRow& row = set.clamped[c];
        C_[r] = row.C;
        alpha_[r] = 0.0;
        lo_[r] = row.lo;
        hi_[r] = row.hi;
        mirror_[r] = row.lambda;
        lambda_[r] = *row.lambda;
        state_[r] = set.active[c] ? State::Free : State::Off;
      }
    }
  }
  for (Entry& e : entries_) {
    e.wlin = inv_mass_[e.body] * e.lin;
    e.wang = inv_inertia_[e.body] * e.ang;
  }
}

void DirectSolver::bodyMotion() {
  std::fill(dx_.begin(), dx_.end(), Vec3::Zero());
  std::fill(dphi_.begin(), dphi_.end(), Vec3::Zero());
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const double dl = dlambda_[r];
    if (dl == 0.0) continue;
    for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e) {
      dx_[entries_[e].body] += dl * entries_[e].wlin;
      dphi_[entries_[e].body] += dl * entries_[e].wang;
    }
  }
}

void DirectSolver::solveActiveSet() {
  const int n = static_cast<int>(rows_.size());
  std::fill(full_.begin(), full_.end(), 0.0);
  for (const Pair& p : pairs_) {
    const Entry &e1 = entries_[p.e1], &e2 = entries_[p.e2];
    full_[p.slot] += e1.lin.dot(e2.wlin) + e1.ang.dot(e2.wang);
  }
  std::vector<double>& A = ldlt_.values();
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    // The free rows' system; fixed rows move to the right-hand side, and
    // fixed and off rows become identity rows.
    std::copy(full_.begin(), full_.end(), A.begin());
    for (int r = 0; r < n; ++r) {
      const Row& row = rows_[r];
      const int d = ldlt_.diagonalSlot(row.position);
      if (state_[r] == State::Free) {
        A[d] += alpha_[r];
        rhs_[r] = -C_[r] - alpha_[r] * lambda_[r];
        continue;
      }
      for (int s = row.slots_begin; s < row.slots_end; ++s) A[slots_[s].value] = 0.0;
      A[d] = 1.0;
      rhs_[r] = state_[r] == State::Fixed ? dlambda_[r] : 0.0;
    }
    for (int r = 0; r < n; ++r) {
      if (state_[r] != State::Fixed) continue;
      for (int s = rows_[r].slots_begin; s < rows_[r].slots_end; ++s)
        if (state_[slots_[s].other_row] == State::Free) rhs_[slots_[s].other_row] -= full_[slots_[s].value] * dlambda_[r];
    }
    for (int r = 0; r < n; ++r) x_[rows_[r].position] = rhs_[r];
    ldlt_.factor(kDropTolerance);
    ldlt_.solve(x_.data());
    for (int r = 0; r < n; ++r) dlambda_[r] = state_[r] == State::Off ? 0.0 : x_[rows_[r].position];
    bodyMotion();
    if (pass + 1 == kMaxPasses) break;
    bool changed = false;
    for (int r = 0; r < n; ++r) {
      if (state_[r] == State::Free) {
        const double total = lambda_[r] + dlambda_[r];
        if (total > hi_[r] || total < lo_[r]) {
          state_[r] = State::Fixed;
          dlambda_[r] = std::clamp(total, lo_[r], hi_[r]) - lambda_[r];
          changed = true;
        }
      } else if (state_[r] == State::Off) {
        // Would the others' motion violate this one-sided row?
        double predicted = C_[r];
        for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e)
          predicted += entries_[e].lin.dot(dx_[entries_[e].body]) + entries_[e].ang.dot(dphi_[entries_[e].body]);
        if ((hi_[r] == 0.0 && predicted > 0.0) || (lo_[r] == 0.0 && predicted < 0.0)) {
          state_[r] = State::Free;
          changed = true;
        }
      }
    }
    if (!changed) break;
  }
}

void DirectSolver::iterate(World& world, double h) {
  if (rows_.empty()) return;
  evaluate(world, h);
  solveActiveSet();
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    BodyState& b = world.body(bodies_[i]);
    // The exact rotation: a light wheel may turn radians in one solve, and
    // the first-order rotateBy() would turn it less than the solve asked.
    b.x += dx_[i];
    rotateExactly(b.q, dphi_[i]);
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
    for (int e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e)
      absorbed_[entries_[e].body] += dl * entries_[e].lin;
  }
}

void DirectSolver::finish(World& world, double h) {
  // A rotor's centre does not move, so its axle took whatever the rows
  // pushed it with, and its weight: F_axle = -(absorbed / h^2 + m g).
  for (int i = 0; i < static_cast<int>(world.hinges().size()); ++i) {
    HingeJoint& j = world.hinge(i);
    const bool a_rotor = world.body(j.a).isRotor();
    if (!a_rotor && !world.body(j.b).isRotor()) continue;
    const BodyId rotor = a_rotor ? j.a : j.b;
    const int index = rotor < static_cast<int>(body_index_.size()) ? body_index_[rotor] : -1;
    const Vec3 absorbed = index < 0 ? Vec3::Zero() : absorbed_[index];
    const Vec3 on_rotor = -(absorbed + world.bodyMass(rotor) * world.settings().gravity * h * h);
    j.impulse_point = a_rotor ? on_rotor : Vec3(-on_rotor);
  }
}

}  // namespace reeve
