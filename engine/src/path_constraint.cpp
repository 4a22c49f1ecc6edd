#include "reeve/engine/path_constraint.h"

#include <algorithm>
#include <array>
#include <cassert>

namespace reeve {
namespace {

// Paths are short (a cable's pinholes plus two ends); this bounds the
// per-visit scratch so the kernel never allocates.
constexpr size_t kMaxPoints = 64;

}  // namespace

void solvePathConstraint(PathConstraint& path, const BodyTable& bodies, double alpha_tilde) {
  if (!path.enabled) return;
  const size_t n = path.points.size();
  assert(n >= 2 && n <= kMaxPoints);
  std::array<Vec3, kMaxPoints> arm, grad;  // world arm r_i and gradient g_i = dC/dp_i
  std::array<Vec3, kMaxPoints> pos;
  for (size_t i = 0; i < n; ++i) {
    const BodyState& b = bodies(path.points[i].body);
    arm[i] = b.q * path.points[i].local;
    pos[i] = b.x + arm[i];
    grad[i].setZero();
  }
  // C = sum |p_{i+1} - p_i| - L; dC/dp_i = u_{i-1} - u_i.
  double length = 0.0;
  for (size_t i = 0; i + 1 < n; ++i) {
    const Vec3 d = pos[i + 1] - pos[i];
    const double l = d.norm();
    length += l;
    if (l < 1e-12) continue;
    const Vec3 u = d / l;
    grad[i] -= u;
    grad[i + 1] += u;
  }
  const double C = length - path.rest_length;
  if (C <= 0.0 && path.lambda == 0.0) return;  // slack and never pulled
  // w = sum over bodies of G^T M^-1 G, G the body's summed linear and
  // angular gradients: pairs of points on one body interact.
  double w = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const BodyState& bi = bodies(path.points[i].body);
    const Vec3 ti = arm[i].cross(grad[i]);
    for (size_t j = 0; j < n; ++j) {
      if (path.points[j].body != path.points[i].body) continue;
      w += bi.inv_mass * grad[i].dot(grad[j]) + ti.dot(bi.applyInvInertia(arm[j].cross(grad[j])));
    }
  }
  if (w + alpha_tilde <= 0.0) return;
  double dl = (-C - alpha_tilde * path.lambda) / (w + alpha_tilde);
  dl = std::min(path.lambda + dl, 0.0) - path.lambda;
  path.lambda += dl;
  for (size_t i = 0; i < n; ++i) {
    BodyState& b = bodies(path.points[i].body);
    const Vec3 turn = dl * b.applyInvInertia(arm[i].cross(grad[i]));
    b.x += dl * b.inv_mass * grad[i];
    rotateBy(b.q, turn);
    b.impulse += dl * grad[i];
    b.angular_impulse += dl * arm[i].cross(grad[i]);
    b.solve_turn += turn;
  }
}

}  // namespace reeve
