// The joint solve every joint type shares, built on the generalized inverse
// masses of correction.h (SCA 2020 sec. 3.3.1 positional, 3.3.2 angular).
// Private to reeve_engine.
//
// A joint's rows live in a 6-D space: a positional part, C_p = p_b - p_a
// (the anchors, m), and an angular part, the rotation of a relative to b
// (rad, world). A row is a unit direction s in that space and a value C.
// The unknowns are the impulse J = [P; L]: P (kg m) on b at its anchor and
// -P on a at its anchor; L (kg m^2) on a and -L on b. J changes the rows by
// M J, M the joint's 6x6 generalized inverse mass (SCA 2020 eq. 2-4 for all
// directions at once):
//   M = [ K                              [r_a]x I_a^-1 + [r_b]x I_b^-1 ]
//       [ (the top right)^T              I_a^-1 + I_b^-1              ]
// with K = pointInverseMass (correction.h) and I^-1 in world axes.
//
// Every visit solves a joint's bilateral rows together, as one block, with
// at most one clamped row (a drive or a limit), exactly to first order.
// A clamped row is rigid, but for a spring drive's, which is compliant.
// Solving the rows one by one, as the paper does, converges slowly when
// they are coupled through an arm: a motor or limit row turns a bob hung
// far from its hinge about the bob's own centre, and the point row then
// turns most of it back (a 1 kg ball 1 m from a hinge with an unlimited
// velocity drive took seconds, not one substep, to reach its target).
#pragma once

#include <limits>

#include "reeve/engine/body.h"
#include "reeve/engine/joint_common.h"

namespace reeve::joint_rows {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

using Vec6 = Eigen::Matrix<double, 6, 1>;

/// Up to six bilateral rows of a joint, with compliance (alpha~ for all).
struct BilateralRows {
  Eigen::Matrix<double, 6, 6> dirs = Eigen::Matrix<double, 6, 6>::Zero();  // columns
  Vec6 values = Vec6::Zero();
  int count = 0;

  /// The three rows C_p = p_b - p_a (point coincidence).
  void addPoint(const Vec3& separation);
  /// A positional row along the unit n: C = n . (p_b - p_a).
  void addPositional(const Vec3& n, double C);
  /// An angular row about the unit n: C = rotation of a relative to b
  /// about n (rad).
  void addAngular(const Vec3& n, double C);
};

/// One clamped row (drive or limit): direction `dir` (unit, 6-D), value
/// `C`, compliance `alpha` (alpha~, already over h^2; 0: rigid, as every
/// row but a spring drive's), accumulated lambda kept in [lo, hi].
struct ClampedRow {
  Vec6 dir = Vec6::Zero();
  double C = 0.0;
  double alpha = 0.0;
  double lo = -kInf, hi = kInf;
  double* lambda = nullptr;
};

/// Solves `rows` (compliant, alpha~ = `alpha_tilde`) together with
/// `clamped` (if any) for the bodies a, b with world anchor arms r_a, r_b:
///   [M_s + alpha~ 1   S^T M c          ] [x]     [C_s + alpha~ S^T Lambda]
///   [c^T M S          c^T M c + alpha_c] [y] = - [C_c + alpha_c lambda_c ],
/// S the bilateral directions, c the clamped one, Lambda the joint's
/// accumulated bilateral impulse (for the compliance term), alpha_c and
/// lambda_c the clamped row's compliance and accumulated lambda; then clamps
/// lambda_c + y to [lo, hi] and, if it was clamped, solves the bilateral
/// rows again with y fixed. Applies J = S x + c y and adds it to the
/// joint's accumulated impulses on a: `linear_a` -= P, `angular_a` += L.
/// Lambda is taken as [-linear_a; angular_a]: the clamped rows of a joint
/// must not share directions with its bilateral rows (they do not: they act
/// along the free directions).
void solveRows(BodyState& a, BodyState& b, const Vec3& r_a, const Vec3& r_b,
               const BilateralRows& rows, double alpha_tilde, const ClampedRow* clamped,
               Vec3& linear_a, Vec3& angular_a);

/// Signed angle (rad, in (-pi, pi]) that turns `from` into `to` about the
/// unit `axis`, both first projected onto the plane normal to `axis`.
double signedAngle(const Vec3& from, const Vec3& to, const Vec3& axis);

/// A unit vector perpendicular to the unit vector `v`.
Vec3 anyPerpendicular(const Vec3& v);

/// Rotation vector (rad, world) of the smallest rotation turning the unit
/// `from` into the unit `to`: angle x (from x to) / |from x to|.
Vec3 alignment(const Vec3& from, const Vec3& to);

/// What a drive targets: nothing, a velocity, or a position (an angle for
/// hinges, a slide for prismatic joints).
enum class DriveKind { None, Velocity, Position };

/// A coordinate's drive (HingeDrive, PrismaticDrive) in the coordinate's
/// units: rad and N m for angles, m and N for slides.
struct DriveSpec {
  DriveKind kind = DriveKind::None;
  double target = 0.0;      // rad/s or m/s (Velocity), rad or m (Position)
  double max_effort = 0.0;  // N m or N; <= 0 or infinite: unlimited
  double stiffness = 0.0;   // N m/rad or N/m; > 0: a spring (Position only)
  double damping = 0.0;     // N m s/rad or N s/m: a spring's, or a velocity drive's damper
  // Added to a spring's error x - x* (rad or m): a trapezoidal spring
  // (HingeDrive::Integration) is a row of a quarter of its stiffness whose
  // error is moved by the part known at the substep's start, 2 e_0 + e_-
  // (e = x - x*).
  double error_offset = 0.0;
};

/// Sets up a coordinate's drive for one substep of `h` s: clears the
/// lambdas, records the coordinate `start` at the beginning of the substep
/// (from the bodies' x_prev, q_prev) and the change `drive_step` the drive
/// asks for:
///   velocity drive, target v* (rad/s or m/s):  drive_step = v* h;
///   position drive, target x* (rad or m): with e = x* - start (an
///   angle's start counted through whole turns: HingeJoint::angle_total) and a_max = max_effort x `inverse_inertia` (the joint's
///   largest acceleration), the drive asks for the largest speed from which
///   it can still stop at x*,  v = sign(e) min(|e| / h, sqrt(2 a_max |e|)),
///   and drive_step = v h. Unlimited effort gives v = e / h: x* at once.
///   Loads are not anticipated: one pulling toward x* (a servo lowering
///   an arm) carries the joint past it, and the drive then brings it back;
///   spring (position drive with stiffness k > 0 and damping c), XPBD
///   (Macklin et al., MIG 2016, eq. 26) on C = x - x*, alpha~ = 1 / (k h^2),
///   beta~ = c h^2, gamma = alpha~ beta~ / h = c / (k h):
///     dlambda = (-C - alpha~ lambda - gamma (x - start))
///               / ((1 + gamma) w + alpha~),
///   w the row's inverse mass. Divided through by 1 + gamma this is an
///   undamped compliant row with a target and a compliance fixed over the
///   substep, which both solvers solve as any other:
///     drive_step = e / (1 + gamma) = e k / (k + c / h),
///     drive_compliance = alpha~ / (1 + gamma) = 1 / ((k + c / h) h^2),
///   and met, lambda / h^2 = -k (x - x*) - c (x - start) / h: the spring's
///   force, implicit Euler in both terms. With an error_offset o, x - x*
///   is replaced by x - x* + o throughout (e by e - o): a trapezoidal
///   spring passes k / 4 and o = 2 e_0 + e_- (e = x - x*), so that met, lambda / h^2
///   = -k (e_+ + 2 e_0 + e_-) / 4 - c (x - start) / h.
/// max_drive_lambda = max_effort h^2 (infinite when unlimited).
void prepareCoordinate(JointCoordinate& c, const DriveSpec& drive, double start,
                       double inverse_inertia, double h);

/// C of a coordinate's drive row at coordinate `value` (solveCoordinateRows).
/// An angle is known only up to whole turns, so its change since the
/// substep began is taken round as far as `turned` says it went (the
/// bodies' relative turn about the axis, from their angular velocities
/// and the solve's turns, BodyState::solve_turn): a motor may turn more
/// than half a turn per substep.
inline double driveError(const JointCoordinate& c, double value, bool angle, double turned) {
  double moved = value - c.start;
  if (angle) moved = turned + wrapAngle(moved - turned);
  return moved - c.drive_step;
}

/// The drive row and then the limit rows of a coordinate, so that a limit
/// wins over a drive pushing into it. `value()` is the current coordinate
/// (rad or m), `turned()` how far it has turned since the substep began as
/// the bodies' motion tells (angles; driveError); `row(C, alpha, lo, hi,
/// lambda)` solves the joint with one clamped row of value C and
/// compliance alpha (alpha~) along the coordinate (lambda > 0 pushes it
/// up), its lambda clamped to [lo, hi]:
///   drive:  C = (x - start) - drive_step  (the change since the substep
///           began, for angles as far round as `turned()` says, minus the
///           asked change; driveError), alpha = drive_compliance (0 but
///           for a spring), |lambda_drive| <= max_drive_lambda;
///   lower:  C = x - lower, only while C < 0 or lambda_lower > 0, lambda >= 0;
///   upper:  C = x - upper, only while C > 0 or lambda_upper < 0, lambda <= 0;
///   limits are rigid (alpha = 0).
/// Returns whether any row was solved.
template <class Value, class Turned, class Row>
bool solveCoordinateRows(JointCoordinate& c, const JointLimit& limit, bool driven, bool angle,
                         Value value, Turned turned, Row row) {
  bool solved = false;
  if (driven) {
    row(driveError(c, value(), angle, turned()), c.drive_compliance, -c.max_drive_lambda, c.max_drive_lambda,
        c.lambda_drive);
    solved = true;
  }
  if (limit.enabled) {
    const double below = value() - limit.lower;
    if (below < 0.0 || c.lambda_lower > 0.0) {
      row(below, 0.0, 0.0, kInf, c.lambda_lower);
      solved = true;
    }
    const double above = value() - limit.upper;
    if (above > 0.0 || c.lambda_upper < 0.0) {
      row(above, 0.0, -kInf, 0.0, c.lambda_upper);
      solved = true;
    }
  }
  return solved;
}

/// 1 / (moment of inertia, kg m^2) of `body` about the axis through its
/// body-local point `local` along the world unit `u`: 0 for a static body.
double inverseInertiaAbout(const BodyState& body, const Vec3& local, const Vec3& u);

/// The frame of a joint created at world `anchor` (m) with world `axis`
/// (normalized here) between bodies at poses a and b.
JointFrame makeJointFrame(const Vec3& anchor, const Vec3& axis, const BodyState& a, const BodyState& b);

}  // namespace reeve::joint_rows
