// Every row of a joint at the current poses, at once, for the direct
// solver (direct_solver.h): the bilateral rows the Gauss-Seidel visit
// solves as a block (joint_rows.h) and the clamped rows (drive, limits) it
// solves one at a time with it. Private to reeve_engine.
#pragma once

#include <array>

#include "joint_rows.h"
#include "reeve/engine/fixed_joint.h"
#include "reeve/engine/hinge_joint.h"
#include "reeve/engine/prismatic_joint.h"
#include "reeve/engine/spherical_joint.h"

namespace reeve::joint_rows {

/// A joint's rows: world anchor arms, bilateral rows (compliant) and up to
/// three clamped rows (rigid, but for a spring drive's). The number of
/// rows depends only on the joint's set-up (which drive and limits it
/// has), not on the poses: a limit that is not touched is a row with
/// `active` false.
struct JointRowSet {
  Vec3 r_a = Vec3::Zero(), r_b = Vec3::Zero();
  BilateralRows bilateral;
  std::array<ClampedRow, 3> clamped;
  std::array<bool, 3> active = {false, false, false};
  int clamped_count = 0;
  // Which clamped rows are a coordinate's drive and limits (-1: none).
  int drive = -1, lower = -1, upper = -1;

  /// Starts the set over: arms, no rows yet (the joint adds its bilateral
  /// rows to `bilateral` in place: a set reused joint after joint is
  /// neither zeroed nor copied).
  void start(const Vec3& arm_a, const Vec3& arm_b) {
    r_a = arm_a;
    r_b = arm_b;
    bilateral.count = 0;
    clamped_count = 0;
    drive = lower = upper = -1;
  }

  void addClamped(const Vec6& dir, double C, double alpha, double lo, double hi, double* lambda,
                  bool is_active) {
    ClampedRow& row = clamped[clamped_count];
    row.dir = dir;
    row.C = C;
    row.alpha = alpha;
    row.lo = lo;
    row.hi = hi;
    row.lambda = lambda;
    active[clamped_count++] = is_active;
  }
};

/// The drive and limit rows of a coordinate along the 6-D `dir` (the same
/// rows, values and conditions as solveCoordinateRows, all at `value` and
/// `turned`).
inline void addCoordinateRows(JointCoordinate& c, const JointLimit& limit, bool driven, bool angle,
                              double value, double turned, const Vec6& dir, JointRowSet& out) {
  if (driven) {
    out.drive = out.clamped_count;
    out.addClamped(dir, driveError(c, value, angle, turned), c.drive_compliance, -c.max_drive_lambda,
                   c.max_drive_lambda, &c.lambda_drive, true);
  }
  if (limit.enabled) {
    const double below = value - limit.lower, above = value - limit.upper;
    out.lower = out.clamped_count;
    out.addClamped(dir, below, 0.0, 0.0, kInf, &c.lambda_lower, below < 0.0 || c.lambda_lower > 0.0);
    out.upper = out.clamped_count;
    out.addClamped(dir, above, 0.0, -kInf, 0.0, &c.lambda_upper, above > 0.0 || c.lambda_upper < 0.0);
  }
}

/// The rows of each joint type, in a substep of `h` s. A hinge whose
/// moving body is a rotor (BodyState::rotor_axis) has no bilateral rows:
/// its axle holds by construction.
void hingeRowSet(HingeJoint& joint, const BodyState& a, const BodyState& b, double h, JointRowSet& out);
void prismaticRowSet(PrismaticJoint& joint, const BodyState& a, const BodyState& b, JointRowSet& out);
void sphericalRowSet(SphericalJoint& joint, const BodyState& a, const BodyState& b, JointRowSet& out);
void fixedRowSet(FixedJoint& joint, const BodyState& a, const BodyState& b, JointRowSet& out);

}  // namespace reeve::joint_rows
