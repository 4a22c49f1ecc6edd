#include "reeve/engine/path_constraint.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <tuple>
#include <vector>

#include "reeve/engine/correction.h"
#include "gauss_seidel/span_ends.h"
#include "line_up.h"

namespace reeve {
namespace {

// Per-visit scratch, grown to the longest path seen (a cable over many
// sliding wraps has two points each) and then kept: no allocation per
// visit once warm.
struct Scratch {
  std::vector<Vec3> arm, grad, force, pos, torque, turn;
  // Per point: its body's response to the visit (line_up.h); at a body's
  // first point (by body), its turn per unit lambda and its share of w.
  std::vector<double> scale, share;
  std::vector<Vec3> body_turn;
  // Points that slide (PathPoint::slides): held as the solve found them.
  std::vector<SolvePoint> held;
  // A rolling end's tangent slide (tangentSlide) at the run's ends and their
  // neighbours: dC/dp and dC/d(rotation), and their weighted forces.
  std::vector<Vec3> slide_grad, slide_moment, slide_force, slide_torque;
  std::vector<size_t> by_body;
  void fit(size_t n) {
    if (arm.size() < n)
      for (std::vector<Vec3>* v : {&arm, &grad, &force, &pos, &torque, &turn, &slide_grad, &slide_moment, &slide_force,
                                   &slide_torque})
        v->resize(n);
    by_body.resize(n);
    scale.resize(n);
    share.resize(n);
    body_turn.resize(n);
    held.resize(n);
  }
};
thread_local Scratch scratch;

// A visit's w below this fraction of its terms' magnitudes is their
// rounding (1e-16 of them): the points' pulls cancel in every body
// (solvePathConstraint). A path with a term that does not cancel keeps far
// more: a 1 t load's 1e-3 against the cancelled 2e6 of a 1e-6 kg wheel
// of 0.1 m, 2.5e-10 of them.
constexpr double kCancelledGradient = 1e-14;

// sin and cos of a; below |a| = 0.1 their Taylor series to the a^8 term,
// exact in double precision (the next terms are under 3e-17 relative) and
// several times cheaper: a solve turns a wheel by small angles, and every
// visit of its spans turns their ends back by them. In Horner form with
// the coefficients 1 / k! as constants: multiplications, where dividing
// by 6, 20, 42, ... put eight divisions in a row on the visit's path.
void sinCos(double a, double& s, double& c) {
  if (std::abs(a) >= 0.1) {
    s = std::sin(a);
    c = std::cos(a);
    return;
  }
  constexpr double s3 = -1.0 / 6.0, s5 = 1.0 / 120.0, s7 = -1.0 / 5040.0, s9 = 1.0 / 362880.0;
  constexpr double c2 = -1.0 / 2.0, c4 = 1.0 / 24.0, c6 = -1.0 / 720.0, c8 = 1.0 / 40320.0;
  const double a2 = a * a;
  s = a + a * a2 * (s3 + a2 * (s5 + a2 * (s7 + a2 * s9)));
  c = 1.0 + a2 * (c2 + a2 * (c4 + a2 * (c6 + a2 * c8)));
}

// solvePoint in the solve, with R the body's rotation matrix (three
// products with it cost less than three with its quaternion).
SolvePoint solvePointRotated(const BodyState& body, const Mat3& R, const PathPoint& point, bool stores = false) {
  SolvePoint p;
  if (point.roll_axis.isZero()) {
    p.arm = R * point.local;
    return p;
  }
  p.axis = R * point.roll_axis;
  p.turn = p.axis.dot(body.solve_turn);
  // The lever turned back by the solve's turn about the axle (Rodrigues).
  // A wheel's circle is most often centred on its centre of mass.
  const bool centred = point.roll_centre.isZero();
  const Vec3 lever = R * (centred ? point.local : Vec3(point.local - point.roll_centre));
  double back = p.turn;  // the lever held back by the turn
  bool tied = false;
  if (stores && point.store_sense != 0 && p.turn * point.store_sense > 0.0) {
    // A store run out within the solve: its end, the point that reached
    // the tangent point after a turn of `back` (r back = the store), has
    // turned on with the body since.
    const double r = (lever - p.axis.dot(lever) * p.axis).norm();
    if (r > 0.0 && p.turn * point.store_sense * r > point.roll_store) {
      back = point.store_sense * point.roll_store / r;
      tied = true;
    }
  }
  if (back == 0.0) {
    p.lever = lever;
  } else {
    double s, c;
    sinCos(back, s, c);
    const double along = p.axis.dot(lever);
    p.lever = c * lever - s * p.axis.cross(lever) + (1.0 - c) * along * p.axis;
  }
  p.arm = centred ? p.lever : Vec3(R * point.roll_centre + p.lever);
  if (tied) {
    p.axis.setZero();
    p.lever.setZero();
    p.turn = 0.0;
    p.paid = -point.roll_store;
  }
  return p;
}

}  // namespace

SolvePoint solvePoint(const BodyState& body, const PathPoint& point, bool in_solve, bool stores) {
  if (!in_solve || point.roll_axis.isZero()) {
    SolvePoint p;
    p.arm = body.q * point.local;
    return p;
  }
  return solvePointRotated(body, body.q.toRotationMatrix(), point, stores);
}

TangentSlide tangentSlide(const SolvePoint& near, const SolvePoint& far, const Vec3& w) {
  TangentSlide slide;
  const Vec3& a = near.axis;
  const double along = a.dot(w), span = w.norm();
  const double in_plane = (w - along * a).norm();
  if (!(in_plane > 0.0)) return slide;  // straight along the axle: no tangent point
  // 1 / |w_in| - 1 / |w| without the cancellation: |w| - |w_in| = (w . a)^2 / (|w| + |w_in|).
  const double k = along * along / ((span + in_plane) * in_plane * span);
  const Vec3& lever = near.lever;
  slide.length = -k * lever.dot(w);
  // d(-k lever . w) = k lever . dT - k lever . dP - k w . dlever: T moves with
  // the body but turns back about the axle (lever . (dphi x lever) = 0), the
  // lever turns with the body's turn off the axle.
  const Vec3 twist = lever.cross(w);
  slide.near_lin = k * lever;
  slide.near_ang = k * near.arm.cross(lever) - k * (twist - a * a.dot(twist));
  slide.far_lin = -k * lever;
  slide.far_ang = far.arm.cross(slide.far_lin);
  if (!far.axis.isZero()) slide.far_ang -= far.axis * far.axis.dot(far.lever.cross(slide.far_lin));
  return slide;
}

void addSpanSlides(const SolvePoint& first, const SolvePoint& last, const Vec3& d, bool slid0, bool slid1,
                   double& length, Vec3& g0, Vec3& t0, Vec3& g1, Vec3& t1) {
  for (int k = 0; k < 2; ++k) {
    if (!(k == 0 ? slid0 : slid1)) continue;
    const TangentSlide slide = k == 0 ? tangentSlide(first, last, d) : tangentSlide(last, first, -d);
    length += slide.length;
    (k == 0 ? g0 : g1) += slide.near_lin;
    (k == 0 ? t0 : t1) += slide.near_ang;
    (k == 0 ? g1 : g0) += slide.far_lin;
    (k == 0 ? t1 : t0) += slide.far_ang;
  }
}

namespace {

// A path the span kernel below solves.
bool isSpan(const PathConstraint& path) {
  return path.points.size() == 2 && path.points[0].body != path.points[1].body && path.scales.empty();
}

// A steady end's turn since the solve's start (rad), as the rotor's
// orientation has it, not as the visits' turn vectors add up: rotateBy
// turns by 2 atan(|dphi| / 2), not |dphi|, so the sum would count cable the
// rotor never wound (the lever turned back from the rotor's pose,
// solvePointRotated, keeps the two in step). The orientation gives it up
// to whole turns (a jerk spins a wheel radians in one solve); the sum, off
// by |dphi|^3 / 12 a visit, picks the turn.
double steadyTurn(const SpanEnds& ends, int k, const BodyState& b) {
  const Vec3& axis = ends.end[k].axis;
  const Quat dq = b.q * ends.start_q[k].conjugate();
  const double summed = axis.dot(b.solve_turn) - ends.start_turn[k];
  const double turned = 2.0 * atan2Small(dq.vec().dot(axis), dq.w());
  return ends.start_turn[k] + summed + wrapAngle(turned - summed);
}

// I^-1 v of a rotor, whose I_body^-1 is a a^T / I_a (body.h): in the world
// a_w (a_w . v) / I_a, a_w its world axle and 1 / I_a the trace.
Vec3 rotorResponse(const BodyState& b, const Vec3& axle, const Vec3& v) {
  return Vec3(axle * (axle.dot(v) * b.inv_inertia.trace()));
}

// A span's step dl (kg m) applied to one end's body: its gradient g
// (dC/dp), moment t and response `turn` (its turn per unit lambda), the
// force along f = weight g.
void moveEnd(BodyState& b, double dl, double weight, const Vec3& g, const Vec3& t, const Vec3& turn) {
  if (!b.takesImpulses()) return;
  const Vec3 f = weight * g, dphi = dl * turn;
  b.x += dl * b.inv_mass * f;
  rotateBy(b.q, dphi);
  b.impulse += dl * f;
  b.angular_impulse += dl * weight * t;
  b.solve_turn += dphi;
}

// solveSpan (below) for a span between two steady ends (SpanEnds::
// fixed_line): its line, moments and w as the solve's start had them, its
// length from the turns; the same arithmetic as solveSpan's, so the same
// bits.
void solveFixedLine(PathConstraint& path, BodyState& b0, BodyState& b1, double alpha_tilde, double h,
                    const SpanEnds& ends) {
  double length = ends.chord;
  length += steadyTurn(ends, 0, b0) * ends.per_radian[0];
  length += steadyTurn(ends, 1, b1) * ends.per_radian[1];
  const double C = length - path.rest_length;
  if (C <= 0.0 && path.lambda == 0.0) return;  // slack and never pulled
  const DampedRow row = dampedRow(C, alpha_tilde, alpha_tilde * h * path.damping, length - path.start_length);
  if (!(ends.w + row.alpha_tilde > 0.0)) return;
  const double target = -row.C - row.alpha_tilde * path.lambda;
  double dl = target / (ends.w + row.alpha_tilde);
  dl = std::clamp(path.lambda + dl, -path.max_tension * h * h, 0.0) - path.lambda;
  path.lambda += dl;
  const double weight = path.weights.empty() ? 1.0 : path.weights[0];
  moveEnd(b0, dl, weight, Vec3(-ends.u), ends.moment[0], ends.response[0]);
  moveEnd(b1, dl, weight, ends.u, ends.moment[1], ends.response[1]);
}

// The kernel below for a span between two bodies, the common case (every
// span of a cable over wheels): the same maths without its per-point
// arrays and per-body sums, each rolling end's pay-out per radian taken
// once. With u the unit span, g_0 = -u, g_1 = u, f_i = weight g_i:
//   C = |p_1 - p_0| + pay-outs - L,
//   w = sum_i m_i^-1 g_i . f_i + t(g_i) . I_i^-1 t(f_i),
// t the moment (SolvePoint::moment, linear in its argument).
// `ends`: the span's steady ends (span_ends.h), or none.
void solveSpan(PathConstraint& path, BodyState& b0, BodyState& b1, double alpha_tilde, double h,
               const SpanEnds* ends) {
  if (ends && ends->fixed_line) return solveFixedLine(path, b0, b1, alpha_tilde, h, *ends);
  const PathPoint &p0 = path.points[0], &p1 = path.points[1];
  // A steady end needs no rotation matrix: its rotor's inverse inertia
  // (below) is along its axle.
  const bool steady0 = ends && ends->steady[0], steady1 = ends && ends->steady[1];
  Mat3 R0, R1;
  if (!steady0) R0 = b0.q.toRotationMatrix();
  if (!steady1) R1 = b1.q.toRotationMatrix();
  const auto point = [&](int k, const BodyState& b, const Mat3& R, const PathPoint& p) {
    if (!(ends && ends->steady[k])) return solvePointRotated(b, R, p);
    SolvePoint s = ends->end[k];
    s.turn = steadyTurn(*ends, k, b);
    return s;
  };
  const SolvePoint first = point(0, b0, R0, p0), last = point(1, b1, R1, p1);
  const Vec3 d = (b1.x + last.arm) - (b0.x + first.arm);
  const double l = d.norm();
  const Vec3 u = l < 1e-12 ? Vec3::Zero() : Vec3(d / l);
  // A rolling end's moment about its axle is the cable it pays out per
  // radian (SolvePoint::spanMoment); a fixed point's, arm x g.
  double length = l;
  Vec3 t0 = first.spanMoment(-u, length), t1 = last.spanMoment(u, length);
  Vec3 g0 = -u, g1 = u;  // dC/dp at each end
  // Out of a rolling end's plane, its tangent point's slide (tangentSlide),
  // but between ends that hold still: a steady end's tangent point stays
  // in space as its rotor turns, and the rotor takes only the slide's
  // moment about its axle, which its centred circle makes zero; a static
  // body takes nothing (hilbert3: every span, 17 % of Gauss-Seidel's time).
  const auto still = [](bool steady, const BodyState& b) { return steady || !b.takesImpulses(); };
  const bool moving = !still(steady0, b0) || !still(steady1, b1);
  const bool slid0 = moving && leavesPlane(first, d), slid1 = moving && leavesPlane(last, d);
  addSpanSlides(first, last, d, slid0, slid1, length, g0, t0, g1, t1);
  const double C = length - path.rest_length;
  if (C <= 0.0 && path.lambda == 0.0) return;  // slack and never pulled
  const double weight = path.weights.empty() ? 1.0 : path.weights[0];
  // I^-1 v = R I_body^-1 R^T v (BodyState::applyInvInertia, with R); a
  // rotor's I_body^-1 is a a^T / I_a (body.h), so in the world a_w (a_w .
  // v) / I_a with a_w = R a and 1 / I_a its trace: one product with R,
  // not three.
  // A rolling end on the rotor's own axle has a_w already (a steady one
  // to rounding).
  const auto invInertia = [](const BodyState& b, const Mat3& R, const PathPoint& p, const SolvePoint& s,
                             bool steady, const Vec3& v) {
    if (!b.isRotor()) return Vec3(R * (b.inv_inertia * (R.transpose() * v)));
    return rotorResponse(b, steady || p.roll_axis == b.rotor_axis ? s.axis : Vec3(R * b.rotor_axis), v);
  };
  const Vec3 turn0 = invInertia(b0, R0, p0, first, steady0, weight * t0),
             turn1 = invInertia(b1, R1, p1, last, steady1, weight * t1);
  const double linear = slid0 || slid1
                            ? b0.inv_mass * g0.squaredNorm() + b1.inv_mass * g1.squaredNorm()
                            : u.squaredNorm() * (b0.inv_mass + b1.inv_mass);
  const double w = weight * linear + t0.dot(turn0) + t1.dot(turn1);
  const DampedRow row = dampedRow(C, alpha_tilde, alpha_tilde * h * path.damping, length - path.start_length);
  if (!(w + row.alpha_tilde > 0.0)) return;
  const double target = -row.C - row.alpha_tilde * path.lambda;
  double dl = target / (w + row.alpha_tilde);
  // A fixed point (an attachment, a spool's tie point once run out) turns
  // on a circle (line_up.h): a 2 g crank under 1 kg swung back and forth
  // by radians a substep, and v = dx / h made energy without bound (1e152
  // J at 100 x 1). The visit turns such an end at most to its line-up;
  // the rest of its correction goes to the other end, this end's response
  // to the row scaled by s (as geometric stiffness stiffens it, Andrews et
  // al. 2017; its torque impulse is booked in full).
  double s0 = 1.0, s1 = 1.0, w_all = w + row.alpha_tilde;
  const bool fixed0 = !steady0 && p0.roll_axis.isZero() && b0.takesImpulses();
  const bool fixed1 = !steady1 && p1.roll_axis.isZero() && b1.takesImpulses();
  if (fixed0) capVisitTurn(first.arm, u, turn0, t0.dot(turn0), target, w_all, dl, s0);
  if (fixed1) capVisitTurn(last.arm, -u, turn1, t1.dot(turn1), target, w_all, dl, s1);
  if (fixed0 && s1 < 1.0)  // end 1 took less: end 0 may turn more
    capVisitTurn(first.arm, u, turn0, t0.dot(turn0), target, w_all, dl, s0);
  dl = std::clamp(path.lambda + dl, -path.max_tension * h * h, 0.0) - path.lambda;
  path.lambda += dl;
  moveEnd(b0, dl, weight, g0, t0, s0 * turn0);
  moveEnd(b1, dl, weight, g1, t1, s1 * turn1);
}

}  // namespace

void solvePathConstraint(PathConstraint& path, const BodyTable& bodies, double alpha_tilde, double h) {
  if (!path.enabled) return;
  const size_t n = path.points.size();
  assert(n >= 2);
  assert(path.weights.empty() || path.weights.size() == n - 1);
  assert(path.scales.empty() || path.scales.size() == n - 1);
  if (isSpan(path))
    return solveSpan(path, bodies(path.points[0].body), bodies(path.points[1].body), alpha_tilde, h, nullptr);
  // World arm r_i, gradient of the length g_i = dC/dp_i and force direction
  // f_i (the weighted gradient; f = g without weights).
  scratch.fit(n);
  std::vector<Vec3>&arm = scratch.arm, &grad = scratch.grad, &force = scratch.force, &pos = scratch.pos;
  // A point that slides is held where the solve found it (scratch.held);
  // at an end (a closed loop's, slipping round every link) it is otherwise
  // a fixed point: no pay-out, no tangent slide.
  bool slides = false;  // a point of the path slides (most paths: none)
  const auto endPoint = [&](size_t i) {
    const PathPoint& point = path.points[i];
    if (!point.slides) return solvePoint(bodies(point.body), point, true);
    slides = true;
    SolvePoint fixed;
    fixed.arm = (scratch.held[i] = solvePoint(bodies(point.body), point, true)).arm;
    return fixed;
  };
  const SolvePoint first = endPoint(0), last = endPoint(n - 1);
  for (size_t i = 0; i < n; ++i) {
    const BodyState& b = bodies(path.points[i].body);
    if (i == 0) arm[i] = first.arm;
    else if (i + 1 == n) arm[i] = last.arm;
    else if (!path.points[i].slides) arm[i] = b.q * path.points[i].local;
    else arm[i] = (scratch.held[i] = solvePoint(b, path.points[i], true)).arm, slides = true;
    pos[i] = b.x + arm[i];
    grad[i].setZero();
    force[i].setZero();
  }
  // C = sum s_i |p_{i+1} - p_i| - L; dC/dp_i = u_{i-1} - u_i, f_i = w_{i-1} u_{i-1} - w_i u_i,
  // u_i the unit segment times s_i.
  double length = 0.0;
  const auto paysOut = [&](size_t i) {  // a run's rolling end: its length turns with its gradient
    return (i == 0 && !first.axis.isZero()) || (i + 1 == n && !last.axis.isZero());
  };
  for (size_t i = 0; i + 1 < n; ++i) {
    const Vec3 d = pos[i + 1] - pos[i];
    const double l = d.norm(), s = segmentScale(path, i);
    length += s * l;
    if (l < 1e-12 || s == 0.0) continue;
    // A chord (both points on one body, both fixed on it or both held on
    // its circle, neither a rolling end that pays out: a wrap's, between
    // its tangent points) keeps its length however the body moves: its
    // pull on the two points cancels in the body's sums, and left in each
    // point's gradient it only misleads the per-point line-up cap below
    // (the point lined up with the chord, not with its span).
    const PathPoint &p = path.points[i], &q = path.points[i + 1];
    if (p.body == q.body && p.slides == q.slides && !paysOut(i) && !paysOut(i + 1)) continue;
    const Vec3 u = s * d / l;
    const double w = path.weights.empty() ? 1.0 : path.weights[i];
    grad[i] -= u;
    grad[i + 1] += u;
    force[i] -= w * u;
    force[i + 1] += w * u;
  }
  // Rolling ends are a run's ends (its interior points are pinholes and
  // sliding wraps, on which the cable slides: fixed points).
  length += first.payOut(grad[0]) + last.payOut(grad[n - 1]);
  // Out of a rolling end's plane, its tangent point's slide with its
  // neighbour (tangentSlide), the segment's scale and weight times.
  bool slid = false;
  for (int k = 0; k < 2; ++k) {
    const size_t i = k == 0 ? 0 : n - 1, j = k == 0 ? 1 : n - 2;
    if (!leavesPlane(k == 0 ? first : last, pos[j] - pos[i])) continue;
    // A far point that slides is held (its slide's length moment less the
    // lever's about the axle, as tangentSlide takes a held far end's).
    SolvePoint far = j == 0 ? first : j + 1 == n ? last : SolvePoint{};
    if (j != 0 && j + 1 != n) far = path.points[j].slides ? scratch.held[j] : SolvePoint{arm[j]};
    const TangentSlide slide = tangentSlide(k == 0 ? first : last, far, pos[j] - pos[i]);
    if (!slid)
      for (size_t p = 0; p < n; ++p)
        scratch.slide_grad[p] = scratch.slide_moment[p] = scratch.slide_force[p] = scratch.slide_torque[p] =
            Vec3::Zero();
    slid = true;
    const size_t segment = k == 0 ? 0 : n - 2;
    const double scale = segmentScale(path, segment), weight = path.weights.empty() ? 1.0 : path.weights[segment];
    length += scale * slide.length;
    for (const auto& [p, lin, ang] :
         {std::tuple{i, slide.near_lin, slide.near_ang}, std::tuple{j, slide.far_lin, slide.far_ang}}) {
      scratch.slide_grad[p] += scale * lin;
      scratch.slide_moment[p] += scale * ang;
      scratch.slide_force[p] += scale * weight * lin;
      // A held point's pull turns its body all the same: the arm's moment.
      const bool held = p == j && path.points[p].slides;
      scratch.slide_torque[p] += scale * weight * (held ? Vec3(arm[p].cross(lin)) : ang);
    }
  }
  const double C = length - path.rest_length;
  if (C <= 0.0 && path.lambda == 0.0) return;  // slack and never pulled
  // The angular gradient of vector v at point i (SolvePoint::moment: a
  // rolling end's part along its axle is the cable it pays out per radian).
  const auto moment = [&](size_t i, const Vec3& v) {
    return i == 0 ? first.moment(v) : i + 1 == n ? last.moment(v) : Vec3(arm[i].cross(v));
  };
  // The length's: a point that slides does not move as its body turns
  // about the axle (its pull, `moment`, still turns the body).
  const auto gradMoment = [&](size_t i, const Vec3& g) {
    return slides && path.points[i].slides ? slidingMoment(scratch.held[i], g) : moment(i, g);
  };
  // w = J_c M^-1 J_f^T: the length's rate of change per unit of lambda.
  // Pairs of points on one body interact, so per body B it is
  // inv_mass (sum_i g_i) . (sum_j f_j) + (sum_i t(g_i)) . I^-1 (sum_j t(f_j)),
  // i, j over B's points: the points sorted by body, each body's sums once
  // (linear in the points, not quadratic).
  std::vector<Vec3>&torque = scratch.torque, &turn = scratch.turn;
  std::vector<size_t>& by_body = scratch.by_body;
  for (size_t i = 0; i < n; ++i) {
    torque[i] = moment(i, force[i]);
    by_body[i] = i;
  }
  if (slid)
    for (size_t i = 0; i < n; ++i) {
      torque[i] += scratch.slide_torque[i];
      force[i] += scratch.slide_force[i];
    }
  // By body, then by index: stable, without stable_sort's buffer (a heap
  // allocation per call).
  if (n > 2)  // a span's two points are on two bodies, or one: in order already
    std::sort(by_body.begin(), by_body.begin() + n, [&](size_t x, size_t y) {
      const BodyId bx = path.points[x].body, by = path.points[y].body;
      return bx < by || (bx == by && x < y);
    });
  // `gross`: w's terms point by point, as magnitudes. Where the points'
  // pulls cancel in every body's sums (a rigid belt held on one hinged
  // wheel and sliding frictionless over another centred one: no turn of
  // either changes its length), w is rounding against them, the tension
  // is not the visit's to find, and -C / w would divide rounding by
  // rounding (6.6e22 J in the first frame).
  double w = 0.0, gross = 0.0, most_turn2 = 0.0;  // the largest |body_turn|^2 of a body the visit moves
  for (size_t k = 0; k < n;) {
    const BodyId id = path.points[by_body[k]].body;
    const BodyState& b = bodies(id);
    Vec3 g = Vec3::Zero(), t = Vec3::Zero(), f = Vec3::Zero();
    size_t end = k;
    for (; end < n && path.points[by_body[end]].body == id; ++end) {
      const size_t i = by_body[end];
      Vec3 gi = grad[i], ti = gradMoment(i, grad[i]);
      if (slid) gi += scratch.slide_grad[i], ti += scratch.slide_moment[i];
      turn[i] = b.applyInvInertia(torque[i]);
      gross += b.inv_mass * gi.norm() * force[i].norm() + ti.norm() * turn[i].norm();
      g += gi;
      t += ti;
      f += force[i];
    }
    Vec3 body_turn = Vec3::Zero();  // I^-1 (sum_j t(f_j)), per unit of lambda
    const size_t start = k;
    for (; k < end; ++k) body_turn += turn[by_body[k]];
    const double a = t.dot(body_turn);
    w += b.inv_mass * g.dot(f) + a;
    scratch.body_turn[start] = body_turn;  // for the line-up below, at the body's first point
    scratch.share[start] = a;
    if (b.takesImpulses()) most_turn2 = std::max(most_turn2, body_turn.squaredNorm());
  }
  const DampedRow row = dampedRow(C, alpha_tilde, alpha_tilde * h * path.damping, length - path.start_length);
  if (w <= kCancelledGradient * gross) w = 0.0;
  if (!(w + row.alpha_tilde > 0.0)) return;
  const double target = -row.C - row.alpha_tilde * path.lambda;
  double dl = target / (w + row.alpha_tilde);
  // Each body's fixed points turn at most to the first line-up among them
  // (line_up.h; solveSpan): a point's length is most or least over the
  // turn where its arm lines up with its gradient. A body with a rolling
  // end pays cable out linearly there and is left as it is.
  double w_all = w + row.alpha_tilde;
  bool scaled = false;
  std::vector<double>& scale = scratch.scale;
  const bool turns = dl * dl * most_turn2 > kTrustedVisitTurn * kTrustedVisitTurn;  // most visits: none
  if (turns) std::fill(scale.begin(), scale.begin() + n, 1.0);
  const auto cap = [&]() {
    for (size_t k = 0; k < n;) {
      const size_t start = k;
      const BodyId id = path.points[by_body[k]].body;
      while (k < n && path.points[by_body[k]].body == id) ++k;
      const Vec3& body_turn = scratch.body_turn[start];
      const double s = scale[by_body[start]], per = s * body_turn.norm(), angle = std::abs(dl) * per;
      if (!(angle > kTrustedVisitTurn) || !bodies(id).takesImpulses()) continue;
      const Vec3 e = body_turn / body_turn.norm();
      double most = angle;
      for (size_t j = start; j < k; ++j) {
        const size_t i = by_body[j];
        if (path.points[i].slides) continue;  // held where it is: no line-up to turn past
        if (!path.points[i].roll_axis.isZero()) {  // pays out linearly: left as it is
          most = angle;
          break;
        }
        if (grad[i].squaredNorm() > kLeastGradient2) most = std::min(most, turnToLineUp(arm[i], e, dl, -grad[i]));
      }
      if (angle <= most) continue;
      const double a = s * scratch.share[start], more = fixedTurnScale(most, angle, per, a, w_all, target, dl);
      w_all -= (1.0 - more) * a;
      for (size_t j = start; j < k; ++j) scale[by_body[j]] *= more;
      scaled = true;
    }
  };
  if (turns) cap();
  if (scaled) cap();  // a body after took less: one before may turn more
  dl = std::clamp(path.lambda + dl, -path.max_tension * h * h, 0.0) - path.lambda;
  path.lambda += dl;
  // Each body turned once, by the sum of its points' turns: the points'
  // own turns can be large and opposed (a wrap's two tangent points and
  // the chord between them pull the body round both ways), and the
  // first-order rotateBy of each in turn does not cancel as their sum
  // does. Turned point by point, a frictionless belt over two eccentric
  // wheels at their saddle (its length gradient zero) had three turns of
  // 0.73, -0.98 and 0.24 rad leave a wheel 0.03 rad on where their sum is
  // -0.0013: 200 J made from 0.25 at 32 x 32 (DESIGN, "Fifty-third
  // session").
  // (scratch.body_turn: each body's sum of turns, at its first point; the
  // cap scales all of a body's points alike.)
  for (size_t k = 0; k < n;) {
    const size_t start = k;
    BodyState& b = bodies(path.points[by_body[k]].body);
    Vec3 f = Vec3::Zero(), t = Vec3::Zero();
    for (const BodyId id = path.points[by_body[k]].body; k < n && path.points[by_body[k]].body == id; ++k) {
      f += force[by_body[k]];
      t += torque[by_body[k]];
    }
    if (!b.takesImpulses()) continue;
    const Vec3& body_turn = scratch.body_turn[start];
    const Vec3 dphi = scaled ? Vec3(dl * scale[by_body[start]] * body_turn) : Vec3(dl * body_turn);
    b.x += dl * b.inv_mass * f;
    rotateBy(b.q, dphi);
    b.impulse += dl * f;
    b.angular_impulse += dl * t;
    b.solve_turn += dphi;
  }
}

namespace {

// A path point at the substep's start; one that slides is where the cable
// update put it on its circle (a lever at the predicted pose), the circle's
// centre where it started.
Vec3 startPoint(const BodyState& body, const PathPoint& point) {
  // (A body that does not move is where it is: q_pred is only ever set by
  // integrate(), and a rotated static bollard read as unrotated gave a
  // damped cable slipping over it a false rate, 43 N read as 121 N.)
  if (!point.slides || !body.moves()) return body.toWorldAtSubstepStart(point.local);
  return body.x_prev + body.q_prev * point.roll_centre + body.q_pred * (point.local - point.roll_centre);
}

}  // namespace

double pathStartLength(const PathConstraint& path, const BodyTable& bodies) {
  double length = 0.0;
  for (size_t i = 0; i + 1 < path.points.size(); ++i) {
    const PathPoint &p = path.points[i], &q = path.points[i + 1];
    length += segmentScale(path, i) * (startPoint(bodies(q.body), q) - startPoint(bodies(p.body), p)).norm();
  }
  return length;
}

// A steady end's circle lies about its rotor's axle to this (squared:
// 1e-12 relative), which rounding meets and a circle set on another axis
// or off the axle does not.
constexpr double kSteadyParallel2 = 1e-24;

void prepareSpanEnds(const std::vector<int>& paths, const std::vector<PathConstraint>& all,
                     const BodyTable& bodies, std::vector<SpanEnds>& ends) {
  ends.resize(paths.size());
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const PathConstraint& path = all[paths[k]];
    SpanEnds& e = ends[k];
    for (int i = 0; i < 2; ++i) {
      e.steady[i] = false;
      if (!isSpan(path)) continue;
      const PathPoint& p = path.points[i];
      const BodyState& b = bodies(p.body);
      // Its circle about the rotor's axle, to rounding: the axle's turn
      // moves neither its axis nor its centre.
      const Vec3& a = b.rotor_axis;
      const Vec3 off_axle = p.roll_centre - p.roll_centre.dot(a) * a;
      if (!b.isRotor() || p.roll_axis.isZero() || p.roll_axis.cross(a).squaredNorm() > kSteadyParallel2 ||
          off_axle.squaredNorm() > kSteadyParallel2 * (1.0 + p.roll_centre.squaredNorm()))
        continue;
      e.end[i] = solvePointRotated(b, b.q.toRotationMatrix(), p);
      e.start_q[i] = b.q;
      e.start_turn[i] = e.end[i].turn;
      e.steady[i] = true;
    }
    e.fixed_line = e.steady[0] && e.steady[1];
    if (!e.fixed_line) continue;
    // solveSpan's line, moments and w, as its first visit computes them.
    const BodyState &b0 = bodies(path.points[0].body), &b1 = bodies(path.points[1].body);
    const Vec3 d = (b1.x + e.end[1].arm) - (b0.x + e.end[0].arm);
    e.chord = d.norm();
    e.u = e.chord < 1e-12 ? Vec3::Zero() : Vec3(d / e.chord);
    e.moment[0] = e.end[0].spanMomentPerRadian(-e.u, e.per_radian[0]);
    e.moment[1] = e.end[1].spanMomentPerRadian(e.u, e.per_radian[1]);
    const double weight = path.weights.empty() ? 1.0 : path.weights[0];
    e.response[0] = rotorResponse(b0, e.end[0].axis, weight * e.moment[0]);
    e.response[1] = rotorResponse(b1, e.end[1].axis, weight * e.moment[1]);
    const double linear = e.u.squaredNorm() * (b0.inv_mass + b1.inv_mass);
    e.w = weight * linear + e.moment[0].dot(e.response[0]) + e.moment[1].dot(e.response[1]);
  }
}

void solvePathConstraint(PathConstraint& path, const BodyTable& bodies, double alpha_tilde, double h,
                         const SpanEnds& ends) {
  if (path.enabled && isSpan(path))
    return solveSpan(path, bodies(path.points[0].body), bodies(path.points[1].body), alpha_tilde, h, &ends);
  solvePathConstraint(path, bodies, alpha_tilde, h);
}

}  // namespace reeve
