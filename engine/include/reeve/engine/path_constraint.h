// A unilateral constraint on the length of a polyline through body-local
// points: sum_i |p_{i+1} - p_i| <= rest_length. A cable running through
// pinholes is one such constraint, so the tension is the same in every
// span, as a frictionless pinhole demands (a two-point path is a plain
// cable span). The generalization of Box2D's pulley joint to any number
// of points and bodies. Segment weights put friction between segments: a
// cable slipping over a wheel or through a hole with friction keeps the
// capstan ratio T_tight / T_slack = exp(mu theta) between the two sides.
#pragma once

#include <limits>
#include <vector>

#include "reeve/engine/body.h"

namespace reeve {

/// A point of a path: a body and a body-local position (m). A rolling end
/// (a cable joint's end on a wheel it does not slip on, paper sec. 4) also
/// gives the circle it is a tangent point of: body-local unit axle
/// `roll_axis` (zero: a point fixed on the body) and centre `roll_centre`.
struct PathPoint {
  BodyId body = 0;
  Vec3 local = Vec3::Zero();
  Vec3 roll_axis = Vec3::Zero();
  Vec3 roll_centre = Vec3::Zero();
  /// A rolling end's store (a spool's stored cable, paper Alg. 2): the
  /// cable (m) it can pay out while the solve turns its body in
  /// `store_sense` (+1 or -1 about roll_axis); 0 there: no store, it only
  /// rolls. Once a solve has turned it past, the cable has run out: the
  /// end is tied where the cable ends and turns with its body
  /// (SolvePoint).
  double roll_store = 0.0;
  int store_sense = 0;
  /// A tangent point of a circle (roll_axis, roll_centre) the cable slips
  /// over inside a run (a slipping friction wrap): the cable slides past
  /// it, so a solve's turn of the body about the axle leaves it where the
  /// cable update put it on the circle and pays nothing out; only the
  /// circle's moving changes the path's length. Its pull turns the body
  /// all the same (the friction torque, r (T_in - T_out)). Turned with the
  /// body instead, a belt over two hinged wheels, whose slipping length no
  /// turn changes, grew a length gradient from the turn alone and a visit
  /// divided by it: 16 kN, the motor flung backwards, 128 J made in a
  /// frame (DESIGN, "Fifty-second session").
  bool slides = false;
};

/// A path point where a solve has put it (issue 29, item 3). A point fixed
/// on its body turns with it. A rolling end does not: while its body turns
/// by `turn` about the axle in the solve (BodyState::solve_turn, rad), the
/// cable stays in touch where it was and winds on or off, so the point is
/// held at its place on the circle (`lever`, from the circle's centre,
/// turned back by -turn) and the path is longer by turn x axis . (lever x
/// dC/dp): what the body-fixed point's gradient says to first order, now
/// for any turn. Held as a body-fixed point, a wheel a solve turned by
/// radians swung the span's end round its rim.
struct SolvePoint {
  Vec3 arm = Vec3::Zero();    ///< from the body's centre of mass, world (m)
  Vec3 lever = Vec3::Zero();  ///< a rolling end's, from the circle's centre, world (m)
  Vec3 axis = Vec3::Zero();   ///< a rolling end's world unit axle; zero for a fixed point
  double turn = 0.0;          ///< the solve's turn about `axis` (rad)
  /// A rolling end tied in this solve (PathPoint::roll_store run out): a
  /// point fixed on its body (axis zero), and the store it paid out before,
  /// -roll_store (m), in the path's length.
  double paid = 0.0;
  /// The cable a rolling end pays out per radian turned about its axle
  /// (m), for the length's gradient `grad` at this point (dC/dp): the
  /// lever's moment axis . (lever x grad) over grad's share in the cable
  /// plane, r for a span leaving the rim tangentially at any angle out of
  /// the plane. The moment alone (r cos phi for a span phi out of the
  /// plane) is what the body-fixed point's gradient gave; the cable update
  /// winds r per radian, so the two disagreed and a free wheel passed on
  /// T cos phi of an out-of-plane span's T: hoisting a load that swung
  /// out of its sheave's plane made energy (issue 29). With r, tension is
  /// the same on both sides of a free frictionless wheel, as a rope riding
  /// its groove's flank out to r / cos phi has it (Clairaut's relation for
  /// a geodesic on a surface of revolution: rho cos(psi) stays r).
  double perRadian(const Vec3& grad) const {
    const double moment = axis.dot(lever.cross(grad));
    const double in_plane = (grad - axis.dot(grad) * axis).norm();
    return in_plane > 1e-9 * grad.norm() ? moment * grad.norm() / in_plane : moment;
  }
  /// The path's length (m) that the turn wound off, for `grad`.
  double payOut(const Vec3& grad) const { return turn == 0.0 ? paid : turn * perRadian(grad); }
  /// dC/d(rotation) of the body (m) for `grad` at this point: arm x grad,
  /// at a rolling end with its part along the axle perRadian(grad).
  Vec3 moment(const Vec3& grad) const {
    const Vec3 m = arm.cross(grad);
    return axis.isZero() ? m : Vec3(m + axis * (perRadian(grad) - axis.dot(lever.cross(grad))));
  }
  /// moment(g), with payOut(g) added to `length`, for a span's direction g
  /// (|g| = 1, or 0 for a span of no length): the lever's moment and g's
  /// share in the cable plane taken once for both.
  Vec3 spanMoment(const Vec3& g, double& length) const {
    double per_radian = 0.0;
    const Vec3 m = spanMomentPerRadian(g, per_radian);
    if (!axis.isZero()) length += turn * per_radian;
    else if (paid != 0.0) length += paid;
    return m;
  }
  /// spanMoment(g) without the pay-out: `per_radian` (m/rad) is set to
  /// the cable the end pays out per radian for g, left at a fixed point.
  Vec3 spanMomentPerRadian(const Vec3& g, double& per_radian) const {
    const Vec3 m = arm.cross(g);
    if (axis.isZero()) return m;
    const double moment = axis.dot(lever.cross(g));
    const double in_plane = (g - axis.dot(g) * axis).norm();
    per_radian = in_plane > 1e-9 ? moment / in_plane : moment;
    return Vec3(m + axis * (per_radian - moment));
  }
};
/// What a rolling end's tangent point sliding round its circle adds to a
/// span out of the cable plane, to first order (both solvers' span rows,
/// and a run's end segments).
/// The cable update puts the tangent point where the span from the far
/// point P touches the circle, (P - c) . n = r in the plane (n the unit
/// lever), and winds r of cable per radian it moves round the circle. The
/// span shortens by only r cos(e) a radian for a span e out of the plane
/// (its share in the plane), so as P moves and the point slides the cable
/// grew or shrank by r (1 - cos e) a radian: an impulse the rows never
/// saw, which made energy (a load on a rail falling 0.3 m out of its
/// drum's plane, 0.4 % of its work; a wheel's own turn pays out r a
/// radian, SolvePoint::perRadian). With w = P - T, the solve's tangent
/// point held where it was off the tangency by n . w, the slide is
///   dpsi = -n . w / (s |w_in|),  dC = r s (1 - cos e) dpsi = -k (lever . w),
///   k = 1 / |w_in| - 1 / |w|,
/// s the winding's sense and w_in w's part in the plane; exact where the
/// cable update left the point (lever . w = 0), its gradient with k held.
struct TangentSlide {
  double length = 0.0;  ///< -k lever . w (m), added to C
  /// dC/dp and dC/d(rotation) on the rolling end's body (`near`: its
  /// lever turned with the body but about the axle) and on the far point's
  /// (as SolvePoint::moment moves it, a rolling far end turned back too).
  Vec3 near_lin = Vec3::Zero(), near_ang = Vec3::Zero(), far_lin = Vec3::Zero(), far_ang = Vec3::Zero();
};
/// Whether `near` rolls and the span w = far point - near point (world, m)
/// leaves its plane by more than 1e-9 rad ((1 - cos e) below 5e-19 there):
/// a span's every visit asks, so without a square root.
inline bool leavesPlane(const SolvePoint& near, const Vec3& w) {
  const double along = near.axis.dot(w);  // 0 for an end fixed on its body
  return along * along > 1e-18 * w.squaredNorm();
}
/// The slide of `near`'s tangent point for the span w (leavesPlane).
TangentSlide tangentSlide(const SolvePoint& near, const SolvePoint& far, const Vec3& w);
/// A span's two ends' slides (`slid0`, `slid1`: which to take), d = p1 - p0
/// (m), added to its length (m) and to each end's dC/dp (g) and
/// dC/d(rotation) (t): both solvers' span rows.
void addSpanSlides(const SolvePoint& first, const SolvePoint& last, const Vec3& d, bool slid0, bool slid1,
                   double& length, Vec3& g0, Vec3& t0, Vec3& g1, Vec3& t1);

/// dC/d(rotation) (m) of a point that slides (PathPoint::slides), at `arm`
/// from its body's centre of mass, for the length's gradient `grad`
/// there: the arm's moment less the lever's about the axle (`axis`, world
/// unit; `lever` from the circle's centre), which does not move the point.
inline Vec3 slidingMoment(const SolvePoint& p, const Vec3& grad) {
  return p.arm.cross(grad) - p.axis * p.axis.dot(p.lever.cross(grad));
}

/// `point` on `body`. `in_solve`: the body's solve_turn is this solve's
/// (from the start of a position solve until the next substep's
/// integration); otherwise every point is fixed on its body. `stores`: a
/// rolling end pays out no more than its store (PathPoint::roll_store) and
/// is tied past it, as the direct solver's rows have it; Gauss-Seidel's
/// visits leave the overdraft to the cable update (DESIGN, "Forty-second
/// session"). A point that slides is held as a rolling end is, with no
/// store.
SolvePoint solvePoint(const BodyState& body, const PathPoint& point, bool in_solve, bool stores = false);

/// At least two points; `rest_length` (m), `compliance` (m/N) and
/// `damping` (N s/m: a force -damping dL/dt on the path's length L, only
/// with compliance > 0; XPBD eq. 25-26, correction.h: dampedRow) of the
/// whole path. Disabled paths are skipped and exert nothing.
///
/// `weights`: empty (every segment pulls with the same tension: a
/// frictionless path) or one value > 0 per segment (points - 1): segment i
/// pulls with tension w_i T, T = -lambda / h^2 being the tension of a
/// weight-1 segment. The length constraint stays unweighted, sum L_i <=
/// rest_length; only the forces are weighted (gradient of the length J_c,
/// force direction J_f = sum w_i grad L_i), so the path is not a
/// conservative constraint when the weights differ: it dissipates, as the
/// friction it stands for does (the direct solver, whose system is
/// symmetric, sweeps weighted paths with solvePathConstraint after each of
/// its iterations). `compliance` is the stretch of the whole path per unit
/// T: sum_i w_i c_i for segment compliances c_i.
///
/// `scales`: empty (every segment counts once) or one value >= 0 per
/// segment: the length is sum_i s_i L_i (with the weights, segment i pulls
/// with s_i w_i T), a conservative constraint whatever the scales. Cables
/// joined in one length constraint (MuJoCo's pulley branches: s = 1 /
/// divisor) are one path of all their points, each cable's segments scaled
/// by its share and the segment from one cable's end to the next cable's
/// start by 0 (no cable there). Rolling ends only at the path's ends.
struct PathConstraint {
  std::vector<PathPoint> points;
  std::vector<double> weights;
  std::vector<double> scales;
  double rest_length = 0.0;
  double compliance = 0.0;
  double damping = 0.0;
  /// Cable fed into the path this substep at a point that does not slide
  /// (m, as long as it was stretched; a winch paying out, negative reeling
  /// in): a change of its length that is not stretching, which the damping
  /// leaves out.
  double fed = 0.0;
  /// The most the path pulls with (N, tension of a weight-1 segment): a
  /// winch's maximum pull; beyond it the constraint gives, lambda held at
  /// -max_tension h^2. Infinite: no limit.
  double max_tension = std::numeric_limits<double>::infinity();
  bool enabled = true;
  double lambda = 0.0;  // accumulated this substep, kg m; <= 0 when pulling
  /// The length at this substep's start poses and present points plus
  /// `fed` (m), set by the World before each solve: the damping's dC is the
  /// length since.
  double start_length = 0.0;
  /// Where the points lie in the world, as a version number: whoever sets
  /// the points gives a new one when they may lie elsewhere, and keeps it
  /// while they are set again on the same bodies at the same world places,
  /// the bodies having stayed put or only turned about a rotor's axle. The
  /// direct solver then keeps a span's length and gradient from its last
  /// evaluation (DirectSolver::evaluatePath), and the World its island
  /// (World::pathMoved). 0: not known, evaluated every substep. The cable
  /// update sets it (CableSystem::updateCable); others leave 0.
  long long placement = 0;
};

/// The World's bodies as the path kernels see them: id -> state, with
/// kWorldBody the fixed world frame.
struct BodyTable {
  BodyState* bodies;
  BodyState* world_frame;
  BodyState& operator()(BodyId id) const { return id == kWorldBody ? *world_frame : bodies[id]; }
};

/// One Gauss-Seidel visit. C = sum_i |p_{i+1} - p_i| - rest_length; the
/// gradient at point i is u_{i-1} - u_i, u_i the unit direction of segment
/// i (weighted w_{i-1} u_{i-1} - w_i u_i for the force; each u_i times its
/// scale s_i in both, and |p_{i+1} - p_i| in C). A body holding
/// several points gets the sum of their gradients, and the generalized
/// inverse mass is J_c M^-1 J_f^T over all of them (SCA 2020 eq. 2-4 for a
/// general gradient; J_c = J_f without weights). lambda is kept in
/// [-max_tension h^2, 0] (pull only, and at most max_tension) for the
/// substep `h` (s). Damping acts only on a path taut or pulling, as the
/// spring does.
void solvePathConstraint(PathConstraint& path, const BodyTable& bodies, double alpha_tilde, double h);

/// The scale of segment i (PathConstraint::scales; 1 without them).
inline double segmentScale(const PathConstraint& path, std::size_t i) {
  return path.scales.empty() ? 1.0 : path.scales[i];
}

/// The path's length at the substep's start poses (m, its segments scaled).
double pathStartLength(const PathConstraint& path, const BodyTable& bodies);

}  // namespace reeve
