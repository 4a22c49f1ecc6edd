// The direct solver's rows at the current poses, linearized: each joint's
// rows (joint_rows.h) and each path's or distance constraint's one, their
// values C, compliance terms, bounds and gradients (the entries).
#include "direct_solver.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "reeve/engine/correction.h"
#include "reeve/engine/math.h"
#include "reeve/engine/world.h"
#include "../line_up.h"

namespace reeve {
namespace {

// d2C / d(rotation)^2 of a point at arm r whose dC/dp is g: the second
// order of C along g as the body turns by theta, g . (theta x (theta x r)) / 2.
Mat3 curvatureAt(const Vec3& g, const Vec3& r) {
  const Mat3 gr = g * r.transpose();
  return 0.5 * (gr + gr.transpose()) - g.dot(r) * Mat3::Identity();
}

bool listed(const World& world, BodyId id) { return direct::listed(world.body(id)); }

// A cable this much of its length short of its rest length is taut by
// rounding (evaluatePath).
constexpr double kTautRounding = 1e-12;

// The compliance term (alpha~, 1/kg) of a static friction row that does not
// hold: dlambda = -(C + alpha~ lambda) / (J W J^T + alpha~) is then -lambda
// to 1e-11 of itself on any body above a microgram, and C adds at most
// 1e-20 kg m a metre: the row gives back what it held and holds nothing.
constexpr double kLetGo = 1e20;

using joint_rows::JointRowSet;
using joint_rows::kInf;
using joint_rows::Vec6;

}  // namespace

void DirectSolver::evaluateBodies() {
  const bool first = !evaluated_ && !at_start_;  // the substep's first evaluation, at the poses solved
  for (BodyFrame& f : frames_) {
    const BodyState& b = *f.state;
    f.turned = b.solve_turn - f.evaluated_turn;
    f.evaluated_turn = b.solve_turn;
    if (first) {
      f.still = b.x == f.placed_x && (f.axle - f.placed_axle).squaredNorm() <= 1e-30;
      f.placed_x = b.x;
      f.placed_axle = f.axle;
    }
    // A rotor's rotation is read only where a span on it is evaluated in
    // full (endPoint), and taken there, if one is (rotation()); a hub's
    // and any other body's also by the solve.
    f.rotated = f.inv_axial == 0.0 || hub_of_[&f - frames_.data()] >= 0;
    if (!f.rotated) continue;
    f.R = b.q.toRotationMatrix();
    if (f.inv_axial == 0.0) f.inv_inertia = f.R * b.inv_inertia * f.R.transpose();
    f.stiff_x = false;
  }
}

const Mat3& DirectSolver::rotation(int slot) {
  BodyFrame& f = frames_[slot];
  if (!f.rotated) {
    f.R = f.state->q.toRotationMatrix();
    f.rotated = true;
  }
  return f.R;
}

// Inlined: called, its gradient went through the stack and was read back
// a pair of doubles across two stores, which the store buffer could not
// forward (the hand 1.5 % faster inlined, the same bits).
EIGEN_STRONG_INLINE void DirectSolver::curve(int i, const Vec3& g, const Vec3& r, bool add) {
  Entry& e = entries_[i];
  const BodyFrame& f = frames_[e.body];
  e.flat = false;
  if (f.inv_axial > 0.0) {
    const double k = f.axle.dot(g) * f.axle.dot(r) - g.dot(r);
    e.axial = add ? e.axial + k : k;
  } else if (add) {
    curvature_[i] += curvatureAt(g, r);
  } else {
    curvature_[i] = curvatureAt(g, r);
  }
}

void DirectSolver::curveEnd(int e, const Vec3& g, const SolvePoint& p, bool add) {
  if (p.axis.isZero()) return curve(e, g, p.arm, add);
  // C as evaluated: the centre c = arm - lever moves with the body; the
  // lever turns with it, then back about the axle a by the turn about a,
  // so a turn theta moves it by (P theta) x lever, P = I - a a^T, and the
  // pay-out is linear in theta. A rotor turns about a alone: no lever term.
  const Vec3 centre = p.arm - p.lever;
  if (frames_[entries_[e].body].inv_axial > 0.0) return curve(e, g, centre, add);
  const Mat3 P = Mat3::Identity() - p.axis * p.axis.transpose();
  const Mat3 k = curvatureAt(g, centre) + P * curvatureAt(g, p.lever) * P;
  curvature_[e] = add ? Mat3(curvature_[e] + k) : k;
  entries_[e].flat = false;
}

void DirectSolver::weigh(Entry& e) const {
  // W J: a rotor's angular part is u u^T / I_u (prepare()).
  const BodyFrame& f = frames_[e.body];
  e.wlin = f.stiff_x ? Vec3(f.inv_mass_x * e.lin) : Vec3(f.inv_mass * e.lin);
  e.wang = f.inv_axial > 0.0 ? Vec3(f.axle * (f.inv_axial * f.axle.dot(e.ang))) : Vec3(f.inv_inertia * e.ang);
  e.weighed = true;
}

SolvePoint DirectSolver::endPoint(const World& world, const PathPoint& point, int slot) {
  // At the start poses a rolling end is where the cable update put it, not
  // turned back with its wheel: the tangent point is geometry, not
  // material (the wheel may have turned a radian under it).
  if (at_start_ && !point.roll_axis.isZero()) {
    // (Only integrate() sets q_pred: a static drum is as it is. Read there,
    // a rotated static drum's rolling end was placed as if unrotated.)
    const BodyState& b = world.body(point.body);
    const Quat& q = b.takesImpulses() ? b.q_pred : b.q;
    SolvePoint p;
    p.arm = q * point.local;
    p.axis = q * point.roll_axis;
    p.lever = q * (point.local - point.roll_centre);
    return p;
  }
  if (point.roll_axis.isZero()) {
    SolvePoint p;
    p.arm = slot >= 0 ? Vec3(rotation(slot) * point.local) : Vec3(world.body(point.body).q * point.local);
    return p;
  }
  if (slot >= 0 && world.body(point.body).solve_turn.isZero()) {  // not turned yet: solvePoint's, by R
    const Mat3& R = rotation(slot);
    SolvePoint p;
    p.arm = R * point.local;
    p.axis = R * point.roll_axis;
    p.lever = R * (point.local - point.roll_centre);
    return p;
  }
  return solvePoint(world.body(point.body), point, true, true);
}

void DirectSolver::evaluateSpan(const World& world, int r, const PathPoint& p0, const PathPoint& p1) {
  // A plain span: C = |p1 - p0| - rest, gradient -u at p0 and u at p1.
  const Row& row = rows_[r];
  const int s0 = slotOf(p0.body), s1 = slotOf(p1.body);
  const SolvePoint e0 = endPoint(world, p0, s0), e1 = endPoint(world, p1, s1);
  const Vec3 &a0 = e0.arm, &a1 = e1.arm;
  const Vec3& x0 = s0 >= 0 ? frames_[s0].state->x : world.body(p0.body).x;
  const Vec3& x1 = s1 >= 0 ? frames_[s1].state->x : world.body(p1.body).x;
  const Vec3 d = (x1 + a1) - (x0 + a0);
  const double l = d.norm();
  const Vec3 u = l >= 1e-12 ? Vec3(d / l) : Vec3::Zero();
  double length = l;  // and the ends' pay-outs
  Vec3 m0 = e0.spanMoment(-u, length), m1 = e1.spanMoment(u, length);
  Vec3 g0 = -u, g1 = u;
  // Out of a rolling end's plane, its tangent point's slide (tangentSlide),
  // but between ends that hold still (linearEnd: a rotor's centred circle,
  // whose tangent point stays in space and which takes only the moment
  // about its axle, zero there; a body the solve does not move): the
  // level-3 Hilbert machine's spans, all out of their wheels' planes.
  bool slid0 = leavesPlane(e0, d), slid1 = leavesPlane(e1, d);
  if ((slid0 || slid1) && linearEnd(p0) && linearEnd(p1)) slid0 = slid1 = false;
  addSpanSlides(e0, e1, d, slid0, slid1, length, g0, m0, g1, m1);
  // Fixed points on moving bodies, for the step's line-up (line_up.h); a
  // span with both ends on one body has no turn in its length.
  if (s0 != s1) {
    if (s0 >= 0 && e0.axis.isZero()) {
      fixed_ends_.push_back({s0, r, row.first_entry});
      fixed_ends_.back().add(a0, u);
    }
    if (s1 >= 0 && e1.axis.isZero()) {
      fixed_ends_.push_back({s1, r, row.first_entry + (s0 >= 0 ? 1 : 0)});
      fixed_ends_.back().add(a1, -u);
    }
    if (e0.axis.isZero() && e1.axis.isZero()) fixed_spans_.push_back({s0, s1, a0, a1, d});
    // Rolling ends with a store still to pay out (stiffenStores).
    const auto stored = [&](int slot, const PathPoint& p, const SolvePoint& e, int entry) {
      if (slot < 0 || p.store_sense == 0 || e.axis.isZero()) return;
      const double radius = (e.lever - e.axis.dot(e.lever) * e.axis).norm();
      if (!(radius > 0.0)) return;
      const double left = p.roll_store / radius - p.store_sense * e.turn;
      stored_ends_.push_back({slot, r, entry, p.store_sense * e.axis, left});
    };
    if (p0.store_sense != 0 || p1.store_sense != 0) {
      stored(s0, p0, e0, row.first_entry);
      stored(s1, p1, e1, row.first_entry + (s0 >= 0 ? 1 : 0));
    }
  }
  int e = row.first_entry;
  const double bend = s0 != s1 && l >= 1e-12 ? 1.0 / l : 0.0;
  if (s0 >= 0) {
    entries_[e].lin = g0;
    entries_[e].ang = m0;
    bend_[e] = bend;
    curveEnd(e, -u, e0, false);
    ++e;
  }
  if (s1 >= 0) {
    if (s1 == s0) {  // both ends on one body
      if (slid0 || slid1) entries_[e - 1].lin += g1;
      else entries_[e - 1].lin.setZero();
      entries_[e - 1].ang += m1;
      curveEnd(e - 1, u, e1, true);
    } else {
      entries_[e].lin = g1;
      entries_[e].ang = m1;
      bend_[e] = bend;
      curveEnd(e, u, e1, false);
    }
  }
  for (e = row.first_entry; e < row.first_entry + row.entry_count; ++e) entries_[e].weighed = false;
  C_[r] = length;  // minus the rest length, by the caller
}

bool DirectSolver::linearEnd(const PathPoint& point) const {
  const int slot = slotOf(point.body);
  if (slot < 0) return true;
  if (point.store_sense != 0) return false;  // its store may run out in the solve
  const BodyFrame& f = frames_[slot];
  const Vec3& centre = point.roll_centre;
  if (f.axial_inv0 == 0.0 || centre.x() != 0.0 || centre.y() != 0.0 || centre.z() != 0.0)
    return false;  // not a rotor, or a circle off its axle
  const Vec3 &u = point.roll_axis, &axle = f.state->rotor_axis;
  if (u == axle) return true;  // most often
  // |sin| of the axes' angle at most 1e-12: C's second order in a turn
  // theta is then below 1e-12 theta^2 r.
  const double u2 = u.squaredNorm();
  return u2 > 0.0 && u.cross(axle).squaredNorm() <= 1e-24 * u2;
}

void DirectSolver::predictSpan(int r) {
  // The span was evaluated in full at the substep's first evaluation (as
  // the cable update left it), and since only predicted. A rotor's turn
  // theta u moves a linear end's cable by perRadian theta, and its entry's
  // ang . u is perRadian (SolvePoint::spanMoment): so C(theta) = C + sum
  // ang . turned, exactly, where the evaluation would turn the lever back
  // by theta and take the same span again.
  const Row& row = rows_[r];
  double length = length_[r];
  for (int e = row.first_entry; e < row.first_entry + row.entry_count; ++e)
    length += entries_[e].ang.dot(frames_[entries_[e].body].turned);
  C_[r] = length;
}

bool DirectSolver::keepsSpan(const PathConstraint& path, int r) const {
  if (!linear_[r] || path.placement == 0 || path.placement != placed_[r]) return false;
  const Row& row = rows_[r];
  for (int e = row.first_entry; e < row.first_entry + row.entry_count; ++e)
    if (!frames_[entries_[e].body].still) return false;
  return true;
}

void DirectSolver::evaluatePath(const World& world, int r, double h) {
  // C = sum of segment lengths - rest, dC/dp_i = u_{i-1} - u_i (a distance
  // constraint is a two-point path, pull-only if unilateral).
  const Row& row = rows_[r];
  double compliance, damping, start_length;
  if (row.source == Source::Path) {
    const PathConstraint& p = world.path(row.index);
    const bool span = p.points.size() == 2 && p.scales.empty();
    // A linear span (Projection::End; Start replaces gradients, use_start_)
    // takes its length at the substep's later evaluations from the turns
    // since, and at its first keeps the last substep's first evaluation
    // where its points and bodies stayed put: a rotor's tangent points
    // stay where they are as it turns (CableSystem::keepsTangents).
    const bool end_projection = start_.empty() && !at_start_;
    if (span && end_projection && evaluated_ && linear_[r]) {
      predictSpan(r);
    } else if (span && end_projection && keepsSpan(p, r)) {
      C_[r] = placed_length_[r];
      for (int e = row.first_entry; e < row.first_entry + row.entry_count; ++e) entries_[e].weighed = false;
    } else if (span) {
      evaluateSpan(world, r, p.points[0], p.points[1]);
      if (end_projection && !evaluated_) {
        linear_[r] = linearEnd(p.points[0]) && linearEnd(p.points[1]);
        placed_[r] = p.placement;
        placed_length_[r] = C_[r];
      }
    } else {
      evaluateRun(world, r, p.points.data(), p.points.size(), p.scales.empty() ? nullptr : p.scales.data());
      if (end_projection && !evaluated_) linear_[r] = 0;
    }
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
  // Taut (C >= 0: a cable exactly at its rest length touches too, and so
  // does one short of it by rounding, 1e-12 of its length), or already
  // pulling: in the active set. A scene that starts a cable taut sets its
  // rest lengths from the geometry, leaving C at rounding either side;
  // spans counted slack by it joined one per pass, as the pass before
  // pulled their far ends, and a motor starting a taut 512-wheel chain ran
  // out of passes (hilbert3 braked at 10 x 2: spans slack, the wheels
  // thrown about for 10 frames).
  const bool unilateral = hi_[r] == 0.0;
  const bool taut = C_[r] >= -kTautRounding * length_[r];
  state_[r] = !unilateral || taut || lambda_[r] < 0.0 || pulled_[r] ? State::Free : State::Off;
  // Damping (correction.h: dampedRow) on a row in the set, as Gauss-Seidel
  // damps a row taut or pulling; its gradient is C's, so the system keeps
  // its matrix J W J^T and only C and alpha~ change. start_length is the
  // start's C here: dC = C - (start length - rest length).
  const double alpha_tilde = compliance / (h * h);
  if (damping == 0.0 || state_[r] != State::Free) {
    alpha_[r] = alpha_tilde;
    return;
  }
  damped_ = true;
  const DampedRow damped = dampedRow(C_[r], alpha_tilde, alpha_tilde * h * damping, C_[r] - start_length);
  C_[r] = damped.C;
  alpha_[r] = damped.alpha_tilde;
}

void DirectSolver::evaluateRun(const World& world, int r, const PathPoint* points, std::size_t count,
                               const double* scales) {
  // A run through pinholes: a body holding several points gets the sum of
  // their gradients. Segment i's length and direction count scales[i]
  // times (PathConstraint::scales; once where there are none).
  const Row& row = rows_[r];
  if (run_.arm.size() < count) {  // grown to the longest path, then kept
    run_.arm.resize(count);
    run_.pos.resize(count);
    run_.u.resize(count);
    run_.entry.resize(count);
    run_.fixed.resize(count);
  }
  std::vector<Vec3>&arm = run_.arm, &pos = run_.pos, &seg = run_.u;
  std::vector<int>& entry = run_.entry;
  std::vector<int>& slot_entry = run_.slot_entry;
  for (int e = row.first_entry; e < row.first_entry + row.entry_count; ++e) slot_entry[entries_[e].body] = e;
  SolvePoint ends[2];
  for (std::size_t i = 0; i < count; ++i) {
    const BodyId id = points[i].body;
    const int slot = slotOf(id);
    const SolvePoint p = endPoint(world, points[i], slot);
    if (i == 0 || i + 1 == count) ends[i == 0 ? 0 : 1] = p;  // rolling ends are a run's ends
    arm[i] = p.arm;
    pos[i] = world.body(id).x + arm[i];
    entry[i] = slot >= 0 ? slot_entry[slot] : -1;
  }
  for (int e = row.first_entry; e < row.first_entry + row.entry_count; ++e) {
    slot_entry[entries_[e].body] = -1;
    entries_[e].lin.setZero();
    entries_[e].ang.setZero();
    curvature_[e].setZero();
    bend_[e] = 0.0;  // a run's points have no sideways block yet
    entries_[e].axial = 0.0;
    entries_[e].flat = false;
  }
  double length = 0.0;
  Vec3 prev_u = Vec3::Zero();
  for (std::size_t i = 0; i < count; ++i) {
    Vec3 u = Vec3::Zero();
    if (i + 1 < count) {
      const Vec3 d = pos[i + 1] - pos[i];
      const double l = d.norm(), s = scales ? scales[i] : 1.0;
      length += s * l;
      if (l >= 1e-12) u = s * d / l;
      seg[i] = u;
    }
    if (entry[i] >= 0) {
      const Vec3 grad = prev_u - u;
      entries_[entry[i]].lin += grad;
      const bool end = i == 0 || i + 1 == count;  // a rolling end pays out per radian (SolvePoint::moment)
      entries_[entry[i]].ang += end ? ends[i == 0 ? 0 : 1].moment(grad) : Vec3(arm[i].cross(grad));
      if (end) curveEnd(entry[i], grad, ends[i == 0 ? 0 : 1], true);
      else curve(entry[i], grad, arm[i], true);
    }
    prev_u = u;
  }
  // A body's length is most or least over its turn where its fixed points'
  // arms line up with their gradients, taken together (line_up.h,
  // TurnModel): a bar threaded on a rope through two holes locks where it
  // lines up with the rope, each hole alone far from its own line-up there
  // (a solve turned a 0.1 kg bar past its lock and the next yanked its 1
  // kg load up: DESIGN, "Fifty-sixth session"). A chord (both points on
  // one body, both fixed or both held, neither a rolling end) keeps its
  // length however the body turns and is left out, as the path kernel
  // leaves it (path_constraint.cpp); a pinhole the cable runs straight
  // through has no line-up to speak of.
  const auto paysOut = [&](std::size_t i) {
    return (i == 0 && !ends[0].axis.isZero()) || (i + 1 == count && !ends[1].axis.isZero());
  };
  const auto chord = [&](std::size_t i) {  // segment i, from point i to i + 1
    return points[i].body == points[i + 1].body && points[i].slides == points[i + 1].slides && !paysOut(i) &&
           !paysOut(i + 1);
  };
  std::fill_n(run_.fixed.begin(), row.entry_count, -1);
  for (std::size_t i = 0; i < count; ++i) {
    if (entry[i] < 0 || paysOut(i)) continue;
    Vec3 grad = Vec3::Zero();
    if (i > 0 && !chord(i - 1)) grad += seg[i - 1];
    if (i + 1 < count && !chord(i)) grad -= seg[i];
    if (!(grad.squaredNorm() > kLeastGradient2)) continue;
    int& f = run_.fixed[entry[i] - row.first_entry];
    if (f < 0) {
      f = static_cast<int>(fixed_ends_.size());
      fixed_ends_.push_back({entries_[entry[i]].body, r, entry[i]});
    }
    fixed_ends_[f].add(arm[i], -grad);
  }
  // Out of a rolling end's plane, its tangent point's slide (tangentSlide)
  // with its neighbour, the segment's scale times.
  const double s_first = scales ? scales[0] : 1.0, s_last = scales ? scales[count - 2] : 1.0;
  for (int k = 0; k < 2; ++k) {
    const std::size_t i = k == 0 ? 0 : count - 1, j = k == 0 ? 1 : count - 2;
    if (!leavesPlane(ends[k], pos[j] - pos[i])) continue;
    SolvePoint far = j == 0 || j + 1 == count ? ends[j == 0 ? 0 : 1] : SolvePoint{};
    if (j != 0 && j + 1 != count) far.arm = arm[j];
    const TangentSlide slide = tangentSlide(ends[k], far, pos[j] - pos[i]);
    const double scale = k == 0 ? s_first : s_last;
    length += scale * slide.length;
    if (entry[i] >= 0) {
      entries_[entry[i]].lin += scale * slide.near_lin;
      entries_[entry[i]].ang += scale * slide.near_ang;
    }
    if (entry[j] >= 0) {
      entries_[entry[j]].lin += scale * slide.far_lin;
      entries_[entry[j]].ang += scale * slide.far_ang;
    }
  }
  for (int e = row.first_entry; e < row.first_entry + row.entry_count; ++e) entries_[e].weighed = false;
  C_[r] = length;  // minus the rest length, by the caller
  if (ends[0].turn != 0.0 || ends[0].paid != 0.0)
    C_[r] += s_first * ends[0].payOut(-(pos[1] - pos[0]).normalized());
  if (ends[1].turn != 0.0 || ends[1].paid != 0.0)
    C_[r] += s_last * ends[1].payOut((pos[count - 1] - pos[count - 2]).normalized());
}

int DirectSolver::evaluateJoint(World& world, int r, double h) {
  const double inv_h2 = 1.0 / (h * h);
  // All the joint's rows at once.
  const Row& first = rows_[r];
  JointRowSet& set = joint_set_;
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
    // Read in place: a 6-vector copied to the stack and read back in
    // halves stalled the store buffer (a third of this function's time).
    const double* s = bilateral ? set.bilateral.dirs.col(k).data() : set.clamped[c].dir.data();
    // Row C along s = [s_p; s_w]: b's anchor along s_p, a's rotation
    // relative to b about s_w (joint_rows.h), so
    //   J_a = [-s_p; -(r_a x s_p) + s_w],  J_b = [s_p; r_b x s_p - s_w].
    const Vec3 sp(s[0], s[1], s[2]), sw(s[3], s[4], s[5]);
    // An angular row (s_p = 0: the axis rows, limits and drives on an
    // angle) has no curvature: its gradient does not turn with the arm.
    const bool angular = sp.isZero();
    int e = rows_[r].first_entry;
    if (a_moves) {
      entries_[e].lin = -sp;
      entries_[e].ang = sw - set.r_a.cross(sp);
      if (angular) flatten(e);
      else curve(e, -sp, set.r_a, false);
      ++e;
    }
    if (b_moves) {
      entries_[e].lin = sp;
      entries_[e].ang = set.r_b.cross(sp) - sw;
      if (angular) flatten(e);
      else curve(e, sp, set.r_b, false);
    }
    for (e = rows_[r].first_entry; e < rows_[r].first_entry + rows_[r].entry_count; ++e) entries_[e].weighed = false;
    dir_[r] = Eigen::Map<const Vec6>(s);
    linear_a_[r] = linear_a;
    angular_a_[r] = angular_a;
    if (bilateral) {
      C_[r] = set.bilateral.values[k];
      // The compliance term's lambda is the joint's impulse so far along
      // this row's present direction, as joint_rows::solveRows takes it: a
      // row's direction may turn within the substep (a hinge's axis rows).
      lambda_[r] = sp.dot(-*linear_a) + sw.dot(*angular_a);
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

int DirectSolver::frictionRows(const ContactManifold& m, const Contact& c) {
  if (!(c.static_friction > 0.0) || m.pool >= 0 || m.group >= 0) return 0;
  return m.patch_radius > 0.0 ? 3 : 2;
}

int DirectSolver::evaluateContacts(const World& world, int r) {
  // C = (p_b - p_a) . n, the sweep's normal row (solveContactPositions): n
  // is the static body's, so only the moving body's point turns, and
  //   J = [n; r_b x n] on b,  [-n; -(r_a x n)] on a.
  const ContactManifold& m = world.contactManifolds()[(*manifolds_)[rows_[r].index]];
  const BodyState &a = world.body(m.a), &b = world.body(m.b);
  const bool b_held = b.moves();
  for (int k = 0; k < m.count; ++k, ++r) {
    const Contact& c = world.contacts()[m.first + k];
    const Vec3 r_a = a.q * c.local_a, r_b = b.q * c.local_b;
    const Vec3& n = c.normal;
    C_[r] = ((b.x + r_b) - (a.x + r_a)).dot(n);
    const int e = rows_[r].first_entry;  // the held body's, the only one
    if (b_held) {
      entries_[e].lin = n;
      entries_[e].ang = r_b.cross(n);
      curve(e, n, r_b, false);
    } else {
      entries_[e].lin = -n;
      entries_[e].ang = -r_a.cross(n);
      curve(e, -n, r_a, false);
    }
    entries_[e].weighed = false;
    alpha_[r] = 0.0;
    contact_of_[r] = m.first + k;
    // In the set where it overlaps or already pushes; apart, it joins only
    // where the solve would push the points into each other
    // (solveActiveSet).
    state_[r] = C_[r] <= 0.0 || lambda_[r] > 0.0 ? State::Free : State::Off;
    contact_kind_[r] = ContactRow::Normal;
  }
  const int friction = frictionRows(m, world.contacts()[m.first]);
  if (friction == 0) return m.count;
  // Static friction holds the anchor while it is held: kept from the last
  // substep at the first iteration (anchorFriction), then as the last
  // iteration left it (ContactManifold::stuck: these rows within their
  // bound, or else the sweep's hold). Its bound is mu_s times the
  // manifold's pressure as the last visit left it, at least the kept
  // anchor's, on each tangent (a box: the sweep bounds the sum, a disc,
  // once the rows pass theirs). Not held, the rows give back what they
  // hold and take nothing more (kLetGo).
  const Contact& c = world.contacts()[m.first];
  const Vec3& n = c.normal;
  const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  const bool held = first_iteration_ ? m.anchor_kept : m.stuck;  // the rows' own or the sweep's
  const double bound = c.static_friction * std::max(m.pressure, m.kept_pressure);
  const Vec3 r_a = a.q * m.anchor_a, r_b = b.q * m.anchor_b;
  const Vec3 slip = (b.x + r_b) - (a.x + r_a);
  const int manifold = (*manifolds_)[rows_[r - m.count].index];
  for (int k = 0; k < friction; ++k, ++r) {
    const int e = rows_[r].first_entry;
    const double sign = b_held ? 1.0 : -1.0;  // J on b, or -J on a
    if (k < 2) {
      const Vec3& t = k == 0 ? t1 : t2;
      C_[r] = slip.dot(t);
      entries_[e].lin = sign * t;
      entries_[e].ang = sign * (b_held ? r_b : r_a).cross(t);
      curve(e, sign * t, b_held ? r_b : r_a, false);
      lo_[r] = -bound;
      hi_[r] = bound;
      contact_dir_[r] = t;
      contact_kind_[r] = ContactRow::Slip;
    } else {
      C_[r] = n.dot(rotationVector(b.q * (a.q * m.anchor_turn).conjugate()));
      entries_[e].lin.setZero();
      entries_[e].ang = sign * n;
      flatten(e);
      lo_[r] = -bound * m.patch_radius;
      hi_[r] = bound * m.patch_radius;
      contact_dir_[r] = n;
      contact_kind_[r] = ContactRow::Twist;
    }
    entries_[e].weighed = false;
    contact_of_[r] = manifold;
    if (!held || bound <= 0.0) {
      alpha_[r] = kLetGo;
      lo_[r] = -kInf;
      hi_[r] = kInf;
    } else {
      alpha_[r] = 0.0;
    }
    state_[r] = State::Free;
  }
  return m.count + friction;
}

void DirectSolver::pressContacts(std::vector<Contact>& contacts, std::vector<ContactManifold>& manifolds) {
  // A manifold's friction rows follow its normal rows: each starts as
  // holding, and one that does not hold (let go, or at its bound: the
  // friction it needs passes mu_s times the pressure) leaves the sweep to
  // decide, as without rows.
  for (const int r : contact_rows_) {
    if (contact_of_[r] < 0) continue;  // not evaluated this substep
    const double gained = lambda_[r] - contact_written_[r];
    contact_written_[r] = lambda_[r];
    if (contact_kind_[r] == ContactRow::Normal) {
      double& lambda_n = contacts[contact_of_[r]].lambda_n;
      lambda_n = std::max(0.0, lambda_n + gained);
      continue;
    }
    ContactManifold& m = manifolds[contact_of_[r]];
    if (contact_kind_[r] == ContactRow::Slip) {
      if (contact_kind_[r - 1] == ContactRow::Normal) m.friction_rows = true;  // its first friction row
      m.friction_impulse += gained * contact_dir_[r];
    } else {
      m.twist_impulse += gained;
    }
    const bool holds = alpha_[r] == 0.0 && lambda_[r] > lo_[r] && lambda_[r] < hi_[r];
    m.friction_rows = m.friction_rows && holds;
  }
}

void DirectSolver::evaluate(World& world, double h) {
  damped_ = false;
  fixed_ends_.clear();
  fixed_spans_.clear();
  stored_ends_.clear();
  evaluateBodies();
  const int n = static_cast<int>(rows_.size());
  for (int r = 0; r < n;) {
    if (rows_[r].source == Source::Path || rows_[r].source == Source::Distance) {
      evaluatePath(world, r, h);
      ++r;
    } else if (rows_[r].source == Source::Contact) {
      r += evaluateContacts(world, r);
    } else {
      r += evaluateJoint(world, r, h);
    }
  }
  evaluated_ = !at_start_;
}

}  // namespace reeve
