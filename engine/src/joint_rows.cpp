#include "joint_rows.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "reeve/engine/correction.h"

namespace reeve::joint_rows {
namespace {

// [r]x: the matrix of r x (.).
Eigen::Matrix3d crossMatrix(const Vec3& r) {
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Matrix7 = Eigen::Matrix<double, 7, 7>;
using Vec7 = Eigen::Matrix<double, 7, 1>;

// The joint's 6x6 generalized inverse mass M (joint_rows.h).
Matrix6 jointInverseMass(const BodyState& a, const BodyState& b, const Vec3& r_a,
                         const Vec3& r_b) {
  const Eigen::Matrix3d inv_a = inverseInertiaWorld(a), inv_b = inverseInertiaWorld(b);
  const Eigen::Matrix3d ra = crossMatrix(r_a), rb = crossMatrix(r_b);
  const Eigen::Matrix3d ra_inv = ra * inv_a, rb_inv = rb * inv_b;
  const Eigen::Matrix3d coupling = ra_inv + rb_inv;
  Matrix6 M;
  // pointInverseMass, from the products at hand: (m_a^-1 + m_b^-1) 1 -
  // [r_a] I_a^-1 [r_a] - [r_b] I_b^-1 [r_b].
  M.topLeftCorner<3, 3>() = (a.inv_mass + b.inv_mass) * Eigen::Matrix3d::Identity() - ra_inv * ra - rb_inv * rb;
  M.topRightCorner<3, 3>() = coupling;
  M.bottomLeftCorner<3, 3>() = coupling.transpose();
  M.bottomRightCorner<3, 3>() = inv_a + inv_b;
  return M;
}

}  // namespace

void BilateralRows::addPoint(const Vec3& separation) {
  for (int i = 0; i < 3; ++i) addPositional(Vec3::Unit(i), separation[i]);
}

void BilateralRows::addPositional(const Vec3& n, double C) {
  dirs.col(count).setZero();
  dirs.col(count).head<3>() = n;
  values[count++] = C;
}

void BilateralRows::addAngular(const Vec3& n, double C) {
  dirs.col(count).setZero();
  dirs.col(count).tail<3>() = n;
  values[count++] = C;
}

void solveRows(BodyState& a, BodyState& b, const Vec3& r_a, const Vec3& r_b,
               const BilateralRows& rows, double alpha_tilde, const ClampedRow* clamped,
               Vec3& linear_a, Vec3& angular_a) {
  if (!a.moves() && !b.moves()) return;  // nothing can move
  const int m = rows.count;
  if (!clamped && (m == 0 || (alpha_tilde == 0.0 &&
                              !(rows.values.head(m).cwiseAbs().maxCoeff() > 1e-15))))
    return;  // nothing to do, or already met
  if (m == 0 && clamped->dir.head<3>().isZero()) {
    // A clamped angular row alone (a rotor's drive or limit, whose axle
    // holds by construction): the scalar XPBD row (SCA 2020 eq. 11-12),
    // no block to factor.
    const Vec3 n = clamped->dir.tail<3>();
    const double x = angularDeltaLambda(a, b, n, clamped->C, clamped->alpha, *clamped->lambda);
    const double y = std::clamp(*clamped->lambda + x, clamped->lo, clamped->hi) - *clamped->lambda;
    *clamped->lambda += y;
    angular_a += y * n;
    applyAngularImpulse(a, b, -y * n);
    return;
  }
  // Directions D (6 x 7): the bilateral rows, then the clamped one at m.
  Eigen::Matrix<double, 6, 7> D = Eigen::Matrix<double, 6, 7>::Zero();
  D.leftCols<6>() = rows.dirs;
  Vec7 rhs = Vec7::Zero();
  rhs.head<6>() = -rows.values;
  if (clamped) {
    D.col(m) = clamped->dir;
    rhs[m] = -clamped->C - clamped->alpha * *clamped->lambda;
  }
  const int n = m + (clamped ? 1 : 0);
  // A = D^T M D, plus alpha~ on the bilateral rows and the clamped row's
  // own; unused rows: A_ii = 1, rhs_i = 0, so their x_i = 0.
  Matrix7 A = D.transpose() * jointInverseMass(a, b, r_a, r_b) * D;
  Vec6 accumulated;
  accumulated << -linear_a, angular_a;
  for (int i = 0; i < m; ++i) {
    A(i, i) += alpha_tilde;
    rhs[i] -= alpha_tilde * D.col(i).dot(accumulated);
  }
  if (clamped) A(m, m) += clamped->alpha;
  for (int i = n; i < 7; ++i) A(i, i) = 1.0;
  // A is symmetric positive definite wherever a body moves along every row
  // (independent directions, W > 0 on them): Cholesky without pivoting is
  // backward stable there and a third of the pivoted LDL^T's cost. A row
  // no moving body can follow makes A singular; LDL^T takes that case.
  const auto solve = [](const Matrix7& M, const Vec7& b) {
    const Eigen::LLT<Matrix7> llt(M);
    return llt.info() == Eigen::Success ? Vec7(llt.solve(b)) : Vec7(M.ldlt().solve(b));
  };
  Vec7 x = solve(A, rhs);
  if (clamped) {
    const double y = std::clamp(*clamped->lambda + x[m], clamped->lo, clamped->hi) -
                     *clamped->lambda;
    if (y != x[m]) {  // clamped: the bilateral rows again, with y fixed
      rhs -= A.col(m) * y;
      A.row(m).setZero();
      A.col(m).setZero();
      A(m, m) = 1.0;
      rhs[m] = y;
      x = solve(A, rhs);
      x[m] = y;
    }
    *clamped->lambda += x[m];
  }
  const Vec6 J = D * x;
  const Vec3 P = J.head<3>(), L = J.tail<3>();
  linear_a -= P;
  angular_a += L;
  applyPositionalImpulse(a, b, r_a, r_b, P);
  applyAngularImpulse(a, b, -L);  // a turns by I_a^-1 L, b by -I_b^-1 L
}

double signedAngle(const Vec3& from, const Vec3& to, const Vec3& axis) {
  const Vec3 f = from - axis * axis.dot(from);
  const Vec3 t = to - axis * axis.dot(to);
  return std::atan2(axis.dot(f.cross(t)), f.dot(t));
}

Vec3 anyPerpendicular(const Vec3& v) {
  const Vec3 helper = std::abs(v.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return v.cross(helper).normalized();
}

Vec3 alignment(const Vec3& from, const Vec3& to) {
  const Vec3 cross = from.cross(to);
  const double s = cross.norm();
  if (!(s > 1e-15)) return Vec3::Zero();
  return std::atan2(s, from.dot(to)) / s * cross;
}

void prepareCoordinate(JointCoordinate& c, const DriveSpec& drive, double start,
                       double inverse_inertia, double h) {
  c.lambda_lower = c.lambda_upper = c.lambda_drive = 0.0;
  c.start = start;
  c.drive_step = 0.0;
  c.drive_compliance = 0.0;
  const bool unlimited = isUnlimited(drive.max_effort);
  c.max_drive_lambda = unlimited ? kInf : drive.max_effort * h * h;
  switch (drive.kind) {
    case DriveKind::None: break;
    case DriveKind::Velocity:
      c.drive_step = drive.target * h;
      // A damper toward the target speed: the row's impulse is the step it
      // misses over alpha~ = 1 / (damping h), a torque of damping (target -
      // speed), implicit (the spring's formula below with k = 0).
      if (drive.damping > 0.0) c.drive_compliance = 1.0 / (drive.damping * h);
      break;
    case DriveKind::Position: {
      const double e = drive.target - start;  // an angle's start counted through whole turns
      if (drive.stiffness > 0.0) {  // a spring: XPBD, damped (joint_rows.h)
        const double k_eff = drive.stiffness + drive.damping / h;
        c.drive_step = (e - drive.error_offset) * drive.stiffness / k_eff;
        c.drive_compliance = 1.0 / (k_eff * h * h);
        break;
      }
      // Time-optimal in steps of h: the fastest speed v this substep from
      // which the drive, slowing by at most a h a substep (a = max_effort /
      // inertia), still stops at the target, moving h v, h (v - a h), ...,
      // h (v - m a h), then 0 (the last speed at most a h: stopped in one
      // substep). That covers h ((m + 1) v - a h m (m + 1) / 2) = |e|, the
      // m full steps fitting where a h^2 m (m + 1) / 2 <= |e|. Near the
      // target (m = 0) it is |e| / h, met in one substep. The continuous
      // sqrt(2 a |e|) overshot by up to a h^2 / 2 per stop.
      double speed = std::abs(e) / h;
      if (!unlimited) {
        const double a = drive.max_effort * inverse_inertia;
        if (a > 0.0) {
          const double m = std::floor(0.5 * (std::sqrt(1.0 + 8.0 * std::abs(e) / (a * h * h)) - 1.0));
          speed = std::abs(e) / (h * (m + 1.0)) + 0.5 * a * h * m;
        } else {
          speed = 0.0;  // nothing it can move
        }
      }
      c.drive_step = std::copysign(speed * h, e);
      break;
    }
  }
}

double inverseInertiaAbout(const BodyState& body, const Vec3& local, const Vec3& u) {
  if (!body.moves()) return 0.0;
  const Vec3 u_local = body.q.conjugate() * u;
  const Vec3 r = body.q * local;
  const double about_centre = u_local.dot(body.inertia * u_local);
  const double shift = body.mass() * (r.squaredNorm() - r.dot(u) * r.dot(u));
  return 1.0 / (about_centre + shift);
}

JointFrame makeJointFrame(const Vec3& anchor, const Vec3& axis, const BodyState& a, const BodyState& b) {
  JointFrame f;
  f.anchor_a = a.toLocal(anchor);
  f.anchor_b = b.toLocal(anchor);
  const Vec3 n = axis.normalized();
  f.axis_a = a.q.conjugate() * n;
  f.axis_b = b.q.conjugate() * n;
  const Vec3 ref = anyPerpendicular(n);
  f.ref_a = a.q.conjugate() * ref;
  f.ref_b = b.q.conjugate() * ref;
  return f;
}

}  // namespace reeve::joint_rows

namespace reeve {

double scheduledTarget(const std::vector<DriveKeyframe>& schedule, double t) {
  const auto [i, s] = keyframeAt(schedule, t);
  return s == 0.0 ? schedule[i].target : schedule[i].target + s * (schedule[i + 1].target - schedule[i].target);
}

}  // namespace reeve
