#include "reeve/engine/contact.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "reeve/engine/contact_material.h"
#include "reeve/engine/convex_hull.h"
#include "reeve/engine/correction.h"

namespace reeve {

bool isValid(const ContactMaterial& m) {
  return std::isfinite(m.static_friction) && m.static_friction >= 0.0 &&
         std::isfinite(m.dynamic_friction) && m.dynamic_friction >= 0.0 &&
         m.restitution >= 0.0 && m.restitution <= 1.0;
}

namespace {

double turn(const Vec2& o, const Vec2& p, const Vec2& q) {
  return (p - o).x() * (q - o).y() - (p - o).y() * (q - o).x();
}

/// Room for a patch's points in a thread's scratch: at least 32, so that
/// it is grown once, not at each larger patch (a step allocates nothing
/// once the first frame ran).
std::size_t scratchPoints(int count) { return std::max<std::size_t>(32, static_cast<std::size_t>(count)); }

/// The convex hull of `points` (which it sorts), counter-clockwise
/// (Andrew's monotone chain); one point when all coincide.
void convexHull(std::vector<Vec2>& points, std::vector<Vec2>& hull) {
  hull.reserve(2 * points.capacity());
  std::sort(points.begin(), points.end(),
            [](const Vec2& p, const Vec2& q) { return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y()); });
  hull.clear();
  for (int pass = 0; pass < 2 && points.size() > 1; ++pass) {
    const std::size_t start = hull.size();
    for (std::size_t k = 0; k < points.size(); ++k) {
      const Vec2& p = pass == 0 ? points[k] : points[points.size() - 1 - k];
      while (hull.size() >= start + 2 && turn(hull[hull.size() - 2], hull.back(), p) <= 0.0) hull.pop_back();
      hull.push_back(p);
    }
    hull.pop_back();
  }
  if (hull.empty()) hull.push_back(points.front());
}

/// Distance from p to a counter-clockwise convex polygon (a segment, a
/// point); 0 inside.
double distanceToHull(const std::vector<Vec2>& hull, const Vec2& p) {
  bool inside = hull.size() > 2;
  double distance = (p - hull.front()).norm();
  for (std::size_t k = 0; k < hull.size() && hull.size() > 1; ++k) {
    const Vec2 &e0 = hull[k], &e1 = hull[(k + 1) % hull.size()];
    inside = inside && turn(e0, e1, p) >= 0.0;
    const Vec2 e = e1 - e0;
    const double s = std::clamp((p - e0).dot(e) / e.squaredNorm(), 0.0, 1.0);
    distance = std::min(distance, (p - e0 - s * e).norm());
  }
  return inside ? 0.0 : distance;
}

/// A patch's shape from the convex hull of its points along n
/// (convexHull): its centre, the lever arm of its twisting friction (m)
/// and whether it has area (describePatch).
struct PatchShape {
  Vec2 centre;
  double radius;
  bool has_area;
};
PatchShape shapeOf(const std::vector<Vec2>& hull) {
  // Its area, centroid and longest chord.
  double area = 0.0, spread = 0.0;
  Vec2 centroid = Vec2::Zero(), mean = Vec2::Zero();
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const Vec2& p = hull[k];
    const Vec2& q = hull[(k + 1) % hull.size()];
    const double cross = p.x() * q.y() - p.y() * q.x();
    area += 0.5 * cross;
    centroid += (p + q) * cross / 6.0;
    mean += p;
    for (const Vec2& r : hull) spread = std::max(spread, (r - p).norm());
  }
  mean /= static_cast<double>(hull.size());
  // A patch of no area (a line, a point) is centred on its hull's vertices.
  const bool flat = std::abs(area) <= 1e-9 * spread * spread;
  return {flat ? mean : Vec2(centroid / area),
          std::max(2.0 / 3.0 * std::sqrt(std::abs(area) / std::numbers::pi), 0.25 * spread),
          !flat && hull.size() >= 3};
}

/// Static friction's anchor at the patch centre as it was at the substep's
/// start (x_prev, q_prev).
void freshAnchor(ContactManifold& m, const BodyState& a, const BodyState& b) {
  const Vec3 start = b.x_prev + b.q_prev * m.centre_b;
  m.anchor_b = m.centre_b;
  m.anchor_a = a.q_prev.conjugate() * (start - a.x_prev);
  m.anchor_turn = a.q_prev.conjugate() * b.q_prev;
  m.anchor_kept = false;
}

/// The couple (kg m^2; on b, its opposite on a) by which
/// a patch with area keeps a and b from tilting against each other under
/// a tangential impulse P at arms r_a, r_b: its pressure shifts toward one
/// side, a couple in the patch's plane (u, v). With K = I_a^-1 + I_b^-1 and
/// tau = I_b^-1 (r_b x P) + I_a^-1 (r_a x P) the relative turn, the couple
/// M = m_u u + m_v v solves [u v]^T (K M + tau) = 0: b then turns
/// relative to a about n alone.
Vec3 patchCouple(const Mat3& inv_inertia_a, const Mat3& inv_inertia_b, const Vec3& r_a, const Vec3& r_b,
                 const Vec3& P, const Vec3& u, const Vec3& v) {
  const Mat3 K = inv_inertia_a + inv_inertia_b;
  const Vec3 tau = inv_inertia_b * r_b.cross(P) + inv_inertia_a * r_a.cross(P);
  const Vec3 Ku = K * u, Kv = K * v;
  Eigen::Matrix2d A;
  A << u.dot(Ku), u.dot(Kv), v.dot(Ku), v.dot(Kv);
  const Vec2 rhs(-u.dot(tau), -v.dot(tau));
  const double det = A.determinant();
  if (!(std::abs(det) > 0.0)) return Vec3::Zero();
  const Vec2 m = A.inverse() * rhs;
  return m.x() * u + m.y() * v;
}

// The point of `solid` nearest to the point `p` (both m, body-local): on a
// face, an edge, a corner, a cylinder's side, cap or rim. nullopt where p
// lies in the solid or on its surface.
std::optional<Vec3> nearestSolidPoint(const ContactSolid& solid, const Vec3& p) {
  switch (solid.kind) {
    case ContactSolid::Kind::Box: {
      const Vec3 on = p.cwiseMax(-solid.size).cwiseMin(solid.size);
      if (on == p) return std::nullopt;
      return on;
    }
    case ContactSolid::Kind::Cylinder: {
      // The radial part clamped to the radius, the axial to the half length.
      const double radial = std::hypot(p.x(), p.y()), r = solid.size.x(), h = solid.size.z();
      if (radial <= r && std::abs(p.z()) <= h) return std::nullopt;
      const double scale = radial > r ? r / radial : 1.0;
      return Vec3(scale * p.x(), scale * p.y(), std::clamp(p.z(), -h, h));
    }
    case ContactSolid::Kind::Hull: return nearestHullPoint(*solid.hull, p);
    case ContactSolid::Kind::None: break;
  }
  return std::nullopt;
}

// Where a cylinder's side (its axis the segment x + t u, |t| <= `half`,
// world, m; `radius` m) comes nearest to `solid` at (x_s, q_s): the middle
// of the stretch of the axis within 1e-3 `radius` of the least distance
// (the whole overlap of an axis parallel to an edge or face), `on_axis`,
// and the solid's point nearest it, `on_solid` (world). The distance along
// the axis is convex: golden-section search, then bisection for the
// stretch's ends. False where the axis meets the solid, or where the
// stretch is at an end of the axis (a cap touches there, not the side).
bool nearestAxisPoint(const ContactSolid& solid, const Vec3& x_s, const Quat& q_s, const Vec3& x, const Vec3& u,
                      double half, double radius, Vec3& on_axis, Vec3& on_solid) {
  // In the solid's frame, the axis from e0 (t = -half) to e1 (t = half).
  const Vec3 e0 = q_s.conjugate() * (x - half * u - x_s), e1 = q_s.conjugate() * (x + half * u - x_s);
  bool inside = false;
  const auto distance = [&](double s) {
    const Vec3 p = e0 + s * (e1 - e0);
    const std::optional<Vec3> on = nearestSolidPoint(solid, p);
    inside = inside || !on;
    return on ? (p - *on).norm() : 0.0;
  };
  constexpr double kGolden = 0.6180339887498949;
  // To 1e-9 of the axis: the point's place along a stretch moves neither
  // the normal nor the depth, and off one only to second order.
  constexpr int kGoldenSteps = 43, kBisections = 30;
  double lo = 0.0, hi = 1.0, m1 = hi - kGolden * (hi - lo), m2 = lo + kGolden * (hi - lo);
  double f1 = distance(m1), f2 = distance(m2);
  for (int k = 0; k < kGoldenSteps; ++k) {
    if (f1 <= f2) {
      hi = m2, m2 = m1, f2 = f1;
      m1 = hi - kGolden * (hi - lo), f1 = distance(m1);
    } else {
      lo = m1, m1 = m2, f1 = f2;
      m2 = lo + kGolden * (hi - lo), f2 = distance(m2);
    }
  }
  const double best = std::min({f1, f2, distance(0.0), distance(1.0)});
  if (inside || !(best > 1e-6 * radius)) return false;  // the axis in it: deep, MPR's
  // The stretch within the tolerance of the least distance: an interval
  // (a convex function's sublevel set) about the minimum.
  const double level = best + 1e-3 * radius, at = f1 <= f2 ? m1 : m2;
  const auto edge = [&](double in, double out) {  // distance(in) <= level < distance(out), or out itself
    if (distance(out) <= level) return out;
    for (int k = 0; k < kBisections; ++k) {
      const double mid = 0.5 * (in + out);
      (distance(mid) <= level ? in : out) = mid;
    }
    return in;
  };
  const double first = edge(at, 0.0), last = edge(at, 1.0);
  if (last <= 1e-9 || first >= 1.0 - 1e-9) return false;  // at an end: its cap
  const double s = 0.5 * (first + last);
  const Vec3 p = e0 + s * (e1 - e0);
  const std::optional<Vec3> on = nearestSolidPoint(solid, p);
  if (!on || !((p - *on).norm() > 1e-12)) return false;
  on_axis = x_s + q_s * p;
  on_solid = x_s + q_s * *on;
  return true;
}

}  // namespace

bool closestCorePoints(const Contact& c, const Vec3& x_a, const Quat& q_a, const Vec3& x_b, const Quat& q_b,
                       Vec3& P, Vec3& Q) {
  // A box, cylinder or hull and a sphere's centre: the centre's nearest
  // point of the body. None where the centre is in it.
  const auto nearestOn = [](const ContactSolid& solid, const Vec3& x, const Quat& q, const Vec3& p, Vec3& nearest) {
    const std::optional<Vec3> on = nearestSolidPoint(solid, q.conjugate() * (p - x));
    if (on) nearest = x + q * *on;
    return on.has_value();
  };
  const bool solid_a = c.solid_a.kind != ContactSolid::Kind::None, solid_b = c.solid_b.kind != ContactSolid::Kind::None;
  if (solid_a && c.core_b > 0.0)  // a cylinder's side on it
    return nearestAxisPoint(c.solid_a, x_a, q_a, x_b, q_b * Vec3::UnitZ(), c.core_b, c.radius_b, Q, P);
  if (solid_b && c.core_a > 0.0)
    return nearestAxisPoint(c.solid_b, x_b, q_b, x_a, q_a * Vec3::UnitZ(), c.core_a, c.radius_a, P, Q);
  if (solid_a || solid_b) {
    P = x_a;
    Q = x_b;
    if (solid_a && !nearestOn(c.solid_a, x_a, q_a, x_b, P)) return false;
    if (solid_b && !nearestOn(c.solid_b, x_b, q_b, x_a, Q)) return false;
    return (Q - P).norm() > 1e-12;
  }
  const Vec3 u_a = q_a * Vec3::UnitZ(), u_b = q_b * Vec3::UnitZ();
  const double cos_ab = u_a.dot(u_b);
  const Vec3 r = x_a - x_b;
  const double cu = u_a.dot(r), fu = u_b.dot(r), det = 1.0 - cos_ab * cos_ab;
  const bool parallel = c.core_a > 0.0 && c.core_b > 0.0 && std::abs(cos_ab) > 0.99;
  double s = 0.0;
  if (parallel) {
    const double mid_b = -cu, reach_b = std::abs(cos_ab) * c.core_b;  // b's segment along a's axis
    const double lo = std::max(-c.core_a, mid_b - reach_b), hi = std::min(c.core_a, mid_b + reach_b);
    s = lo <= hi ? 0.5 * (lo + hi) : std::clamp(mid_b, -c.core_a, c.core_a);
  } else if (det > 1e-12) {
    s = std::clamp((cos_ab * fu - cu) / det, -c.core_a, c.core_a);
  }
  const double t = std::clamp(cos_ab * s + fu, -c.core_b, c.core_b);
  if (!parallel) s = std::clamp(cos_ab * t - cu, -c.core_a, c.core_a);
  P = x_a + s * u_a;
  Q = x_b + t * u_b;
  return (Q - P).norm() > 1e-12;
}

namespace {

/// Moves a curved contact's points to where its bodies' cores are now
/// closest: the normal runs from P to Q and each point lies its radius
/// along it. Body-fixed points let a thin rod pivot within a solve about
/// the end that first touched, its middle sinking into the wheel, and the
/// next substep threw it out at that depth / h.
void remeasureCurvedContact(Contact& c, const BodyState& a, const BodyState& b) {
  Vec3 P, Q;
  if (!closestCorePoints(c, a.x, a.q, b.x, b.q, P, Q)) return;
  c.normal = (Q - P).normalized();
  c.local_a = a.toLocal(P + c.radius_a * c.normal);
  c.local_b = b.toLocal(Q - c.radius_b * c.normal);
}

/// What a manifold's FrictionPool fellows (the pool's other manifolds)
/// lend its visit (kg m): `spare`, their capacity less the size of their
/// friction (negative where what they hold passes their bound), which its
/// hold may take on top of its own; `pressure`, their pressure.
struct PoolShare {
  const FrictionPool* pool = nullptr;  // none: spare and pressure 0
  double spare = 0.0, pressure = 0.0;
  /// The visit's SupportGroup (none: nothing lent), the contacts, and the
  /// manifold visited.
  const SupportGroup* group = nullptr;
  const Contact* contacts = nullptr;
  const ContactManifold* self = nullptr;

  /// What the group's manifolds outside the visited one's pool leave
  /// spare along the unit direction t (kg m; SupportGroup).
  double lent(const Vec3& t) const {
    double sum = 0.0;
    for (int k = 0; group && k < group->count; ++k) {
      const ContactManifold& o = group->manifolds[group->members[k]];
      if (&o == self || (self->pool >= 0 && o.pool == self->pool)) continue;
      const double along = contacts[o.first].normal.dot(t);
      sum += std::max(0.0, o.friction_capacity * std::sqrt(std::max(0.0, 1.0 - along * along)) -
                               o.friction_impulse.norm());
    }
    return sum;
  }
};

// Whether the pressure `pressure` (kg m; a pool's: all of it) can put up
// the couple `couple` (kg m^2, on b) between a and b: its centre, moved by
// n x couple / pressure from the patch's centre, stays on the patch (the
// hull of its points along n), or on `pool`'s compound patch.
bool centreOnPatch(const ContactManifold& m, const Contact* contacts, const BodyState& a, const BodyState& b,
                   const FrictionPool* pool, const Vec3& n, const Vec3& couple, double pressure) {
  const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
  thread_local std::vector<Vec2> points, hull;
  points.clear();
  const BodyState& moving = a.moves() ? a : b;
  const auto add = [&](const Vec3& p) { points.emplace_back(u.dot(p), v.dot(p)); };
  if (pool) {
    points.reserve(scratchPoints(pool->hull_count));
    for (int k = 0; k < pool->hull_count; ++k) add(moving.toWorld(pool->hull[k]));
  } else {
    points.reserve(scratchPoints(m.count));
    for (int i = m.first; i < m.first + m.count; ++i) add(b.toWorld(contacts[i].local_b));
  }
  convexHull(points, hull);
  const Vec3 centre = (pool ? moving.toWorld(pool->centre) : b.toWorld(m.centre_b)) + n.cross(couple) / pressure;
  return distanceToHull(hull, Vec2(u.dot(centre), v.dot(centre))) == 0.0;
}

/// solveContactPositions but for the curved points' last measure and the
/// pool's sums.
bool visitManifold(ContactManifold& m, Contact* contacts, BodyState& a, BodyState& b, const PoolShare& share) {
  constexpr double kSettled = 1e-12;  // m: a sweep moving no row more than this ends the visit
  const int end = m.first + m.count;
  bool changed = false;  // a correction applied and kept
  // One sweep over the normal rows, in the sweep's order; returns the
  // deepest overlap it pushed out (m).
  const auto pressNormals = [&](int sweep) {
    double largest = 0.0;
    for (int k = 0; k < m.count; ++k) {
      const int i = sweep % 2 == 0 ? m.first + k : end - 1 - k;
      // Normal row: C = (p_b - p_a) . n, dC/dp_b = n; unilateral (C < 0 only).
      Contact& c = contacts[i];
      if (c.core_a >= 0.0) remeasureCurvedContact(c, a, b);
      const Vec3 r_a = a.q * c.local_a, r_b = b.q * c.local_b;
      const double C = ((b.x + r_b) - (a.x + r_a)).dot(c.normal);
      if (C >= 0.0) continue;
      const double dl = positionalDeltaLambda(a, b, r_a, r_b, c.normal, C, 0.0, c.lambda_n);
      if (!(dl > 0.0)) continue;
      c.lambda_n += dl;
      applyPositionalImpulse(a, b, r_a, r_b, dl * c.normal);
      largest = std::max(largest, -C);
    }
    return largest;
  };
  const auto pressed = [&] {  // lambda_n of the whole manifold
    double sum = 0.0;
    for (int i = m.first; i < end; ++i) sum += contacts[i].lambda_n;
    return sum;
  };
  for (int sweep = 0; sweep < kManifoldSweeps; ++sweep) {
    const double largest = pressNormals(sweep);
    changed |= largest > 0.0;
    if (largest <= kSettled) break;
  }
  const double lambda_n = pressed();
  const double mu_s = contacts[m.first].static_friction;
  m.pressure = lambda_n;
  m.friction_capacity = lambda_n > 0.0 ? mu_s * std::max(lambda_n, share.pool ? m.kept_pressure : 0.0) : 0.0;
  if (lambda_n <= 0.0) {  // not pressed: nothing holds the anchor
    m.stuck = false;
    return changed;
  }
  if (m.friction_rows) {  // held in the direct solve, with its cables
    m.stuck = true;
    return changed;
  }
  // A curved point rolls: its anchor is where it touches now, as it was at
  // the substep's start (SCA 2020, eq. 27), never one kept from earlier,
  // which would hold the rod to pivot about the point it touched first.
  if (m.count == 1 && contacts[m.first].core_a >= 0.0) {
    m.centre_a = contacts[m.first].local_a;
    m.centre_b = contacts[m.first].local_b;
    freshAnchor(m, a, b);
  }
  // Static friction of the patch: one tangential row at its anchor and one
  // twist row about n, held together or not at all.
  const Vec3& n = contacts[m.first].normal;
  const FrictionPool* pool = share.pool;
  const double radius = pool ? std::max(m.patch_radius, pool->radius) : m.patch_radius;
  // What holding changes on a body, kept to undo it (on the bodies the
  // solve writes to: BodyState::takesImpulses).
  struct Held {
    Vec3 x;
    Quat q;
    Vec3 impulse, angular_impulse, solve_turn;
  };
  const auto keep = [](const BodyState& s) { return Held{s.x, s.q, s.impulse, s.angular_impulse, s.solve_turn}; };
  const auto undo = [](BodyState& s, const Held& k) {
    if (!s.takesImpulses()) return;
    s.x = k.x;
    s.q = k.q;
    s.impulse = k.impulse;
    s.angular_impulse = k.angular_impulse;
    s.solve_turn = k.solve_turn;
  };
  const Held before_a = keep(a), before_b = keep(b);
  const Vec3 friction_before = m.friction_impulse;
  const double twist_before = m.twist_impulse;
  const double point_pressed_before = contacts[m.first].lambda_n;
  // Holds the anchor (local_a, local_b, relative orientation anchor_turn);
  // false, with everything undone, when that passes the bound. `applied`:
  // it moved a body, and kept the motion. A single point takes no moment:
  // friction pulling at it, off the bodies' centres, turns them against
  // each other, so holding presses harder than sliding. Where its friction
  // row alone passes the bound, a second pass lets its normal row answer
  // and weighs the bound against the pressure that leaves. (Against the
  // pressure before, a thin rod rocking on a wheel let go with its
  // friction 0.494 of the pressure, 1.3 % short of what holding would have
  // left: test_friction_bounds.cpp.) A patch of many points takes the moment
  // by moving pressure between its points, which rows that only push
  // would count twice: its bound stays the pressure before (DESIGN,
  // "Thirty-fourth session").
  //
  // `level`: on a patch with area between a body and one that
  // constraints do not move (the ground, a fixed ramp, a kinematic slab),
  // the hold moves the body as the patch's pressure lets it move, without
  // tilting (patchCouple): the friction it asks is then what stops it.
  // Free to tilt, a hold at the base of a unit cube asked 2.5 x less (1/m +
  // r^2/I against 1/m), the next iteration's normal rows took the tilt
  // back, and a cube held on a ramp up to 29 degrees where mu_s = 0.5
  // holds it to 26.6 (test_friction_bounds.cpp). Where the couple would
  // put the pressure's centre off the patch, the body tips or rolls
  // instead: the hold is redone free. Between two moving bodies it stays
  // free to tilt (DESIGN, "Thirty-fourth session"). A kinematic body takes
  // impulses (its work is booked) but moves as its schedule says, as the
  // ground does: counted as moving, it held a box up to a degree past the
  // friction angle (DESIGN, "Thirty-fifth session"). A pool's manifold,
  // a single point's too, is held level: the body's other supports keep
  // it from tilting about the one that holds (free to, a box held at one
  // of three balls asked too little and held at 0.5 rad where mu_s = 0.5;
  // DESIGN, "Forty-seventh session").
  const bool level_pair = (m.patch_has_area || pool) && (!a.moves() || !b.moves());
  const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
  const Mat3 inv_inertia_a = level_pair ? inverseInertiaWorld(a) : Mat3::Zero();
  const Mat3 inv_inertia_b = level_pair ? inverseInertiaWorld(b) : Mat3::Zero();
  // Whether the patch's pressure `pressure` (kg m) can put up the couple
  // `couple` (on b): its centre, moved by n x couple / pressure from the
  // patch centre, stays on the patch (the hull of its points along n).
  // A pool's patch is its compound patch, under all its pressure.
  const auto pressureCentreOnPatch = [&](const Vec3& couple, double pressure) {
    return centreOnPatch(m, contacts, a, b, pool, n, couple, pool ? pressure + share.pressure : pressure);
  };
  bool applied = false, tipped = false;
  const auto hold = [&](const Vec3& local_a, const Vec3& local_b, const Quat& anchor_turn, bool level,
                        double kept_pressure) {
    applied = tipped = false;
    for (const bool pressing : {false, true}) {
      if (pressing && (m.count != 1 || level)) break;
      for (int sweep = 0; sweep < kManifoldSweeps; ++sweep) {
        // Tangential: C = |dp_t| of the anchor, gradient dp_t / |dp_t| wrt b.
        const Vec3 r_a = a.q * local_a, r_b = b.q * local_b;
        const Vec3 dp = (b.x + r_b) - (a.x + r_a);
        const Vec3 dp_t = dp - n * n.dot(dp);
        const double len = dp_t.norm();
        if (len > kSettled && level) {
          // w: how far a unit impulse along t, with its couple, moves the
          // anchor points apart along t.
          const Vec3 t = dp_t / len;
          const Vec3 couple = patchCouple(inv_inertia_a, inv_inertia_b, r_a, r_b, t, u, v);
          const Vec3 turn_b = inv_inertia_b * (r_b.cross(t) + couple);
          const Vec3 turn_a = -(inv_inertia_a * (r_a.cross(t) + couple));
          const double w = a.inv_mass + b.inv_mass + t.dot(turn_b.cross(r_b) - turn_a.cross(r_a));
          const double dl = w > 0.0 ? -len / w : 0.0;
          m.friction_impulse += dl * t;
          applyPositionalImpulse(a, b, r_a, r_b, dl * t);
          applyAngularImpulse(a, b, dl * couple);
          applied = true;
        } else if (len > kSettled) {
          const Vec3 t = dp_t / len;
          const Vec3 P = positionalDeltaLambda(a, b, r_a, r_b, t, len, 0.0, 0.0) * t;
          m.friction_impulse += P;
          applyPositionalImpulse(a, b, r_a, r_b, P);
          applied = true;
        }
        // Twist: C = the turn of b relative to a about n since the anchor.
        const double turn = n.dot(rotationVector(b.q * (a.q * anchor_turn).conjugate()));
        if (std::abs(turn) > kSettled && radius > 0.0) {
          const double dl = angularDeltaLambda(a, b, n, turn, 0.0, 0.0);
          m.twist_impulse += dl;
          applyAngularImpulse(a, b, dl * n);
          applied = true;
        }
        const double pushed = pressing ? pressNormals(sweep) : 0.0;
        applied |= pushed > 0.0;
        if (len <= kSettled && std::abs(turn) * radius <= kSettled && pushed <= kSettled) break;
      }
      // A kept anchor's pressure is at least what it was at the end of
      // the substep it comes from: an unconverged solve carries a stack's
      // weight to its bottom late (its pressure dipped 10 % a few substeps
      // after it was put, at 10 x 2, and a push at 0.9 mu_s slid it), and
      // a body put touching settles (a log laid along a ramp, a line
      // contact held free, pressed 1.04 then 0.95 x its weight and let go
      // at 0.455 rad). `kept_pressure` is 0 where there is no such floor.
      const double holding = std::max(pressing ? pressed() : lambda_n, kept_pressure);
      const bool tips = level && !pressureCentreOnPatch(patchCouple(inv_inertia_a, inv_inertia_b, a.q * local_a,
                                                                     b.q * local_b, m.friction_impulse, u, v),
                                                         holding);
      tipped |= tips;
      const double held = m.friction_impulse.norm();
      const double bound =
          mu_s * holding + share.spare + (share.group && held > 0.0 ? share.lent(m.friction_impulse / held) : 0.0);
      // A pool's friction twists about its centre: held at one support off
      // it, the twist row takes back the turn the friction there gives
      // (a box on four balls needs none, but held at one it asked 0.5 m x
      // the friction).
      double twist = m.twist_impulse;
      if (pool) {
        const Vec3 arm = (b.x + b.q * local_b) - (a.moves() ? a : b).toWorld(pool->centre);
        twist += n.dot(arm.cross(m.friction_impulse));
      }
      if (!tips && held <= bound && std::abs(twist) <= bound * radius) {
        m.friction_capacity = mu_s * holding;
        return true;
      }
    }
    // Sliding or spinning: undone.
    undo(a, before_a);
    undo(b, before_b);
    m.friction_impulse = friction_before;
    m.twist_impulse = twist_before;
    if (m.count == 1) contacts[m.first].lambda_n = point_pressed_before;
    applied = false;
    return false;
  };
  const auto holdAnchor = [&](const Vec3& local_a, const Vec3& local_b, const Quat& anchor_turn,
                              double kept_pressure) {
    if (level_pair) {
      if (hold(local_a, local_b, anchor_turn, true, kept_pressure)) return true;
      if (!tipped) return false;  // it slides
    }
    // A free hold against a body that constraints do not move keeps the
    // floor (a line contact, a single point); one redone free where a
    // level hold tipped does not (its pressure is moving to an edge), nor
    // one between two moving bodies.
    const bool floored = !level_pair && (!a.moves() || !b.moves());
    return hold(local_a, local_b, anchor_turn, false, floored ? kept_pressure : 0.0);
  };
  m.stuck = holdAnchor(m.anchor_a, m.anchor_b, m.anchor_turn, m.anchor_kept || pool ? m.kept_pressure : 0.0);
  changed |= applied;
  if (m.stuck || !m.anchor_kept) return changed;
  // Pulling back what earlier substeps let slip passes the bound (in an
  // early iteration, before the normal rows carry the whole load, or
  // under a load near it): hold this substep's motion alone, as a fresh
  // anchor does, and the next substep anchors afresh unless a later visit
  // holds the kept anchor.
  ContactManifold fresh = m;
  freshAnchor(fresh, a, b);
  holdAnchor(fresh.anchor_a, fresh.anchor_b, fresh.anchor_turn, 0.0);
  return changed || applied;
}

}  // namespace

bool solveContactPositions(ContactManifold& m, Contact* contacts, BodyState& a, BodyState& b,
                           FrictionPool* pool, const SupportGroup* group) {
  // The pool's fellows: their capacity less what they hold already (its
  // size: the spread of a total within the sum of the bounds is free).
  const Vec3 friction_before = m.friction_impulse;
  const double capacity_before = m.friction_capacity, pressure_before = m.pressure;
  PoolShare share;
  share.group = group;
  share.contacts = contacts;
  share.self = &m;
  if (pool) {
    share.pool = pool;
    share.spare = (pool->capacity - capacity_before) - (pool->friction - friction_before).norm();
    share.pressure = pool->pressure - pressure_before;
  }
  const bool changed = visitManifold(m, contacts, a, b, share);
  if (pool) {
    pool->friction += m.friction_impulse - friction_before;
    pool->capacity += m.friction_capacity - capacity_before;
    pool->pressure += m.pressure - pressure_before;
  }
  // A friction hold that was undone measured the curved points at poses
  // it took back: they are measured again where the bodies are, for the
  // velocity pass and the next visit. (Left at the undone poses, a ball's
  // normal lagged 7e-5 rad behind it on a log and the velocity pass read
  // that as an approach.)
  for (int i = m.first; i < m.first + m.count; ++i)
    if (contacts[i].core_a >= 0.0) remeasureCurvedContact(contacts[i], a, b);
  return changed;
}

void anchorFriction(ContactManifold& m, const Contact* contacts, const ContactManifold* previous,
                    const BodyState& a, const BodyState& b, double margin) {
  if (previous && previous->stuck) {
    const bool same = previous->a == m.a;
    const Vec3& on_a = same ? previous->anchor_a : previous->anchor_b;
    const Vec3& on_b = same ? previous->anchor_b : previous->anchor_a;
    // On the hull of all the points, not only the pressed ones, which come
    // and go on a resting face.
    const Vec3& n = contacts[m.first].normal;
    const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
    const auto inPlane = [&](const Vec3& p) { return Vec2(u.dot(p), v.dot(p)); };
    thread_local std::vector<Vec2> points, hull;
    points.clear();
    points.reserve(scratchPoints(m.count));
    for (int i = m.first; i < m.first + m.count; ++i) points.push_back(inPlane(b.toWorld(contacts[i].local_b)));
    convexHull(points, hull);
    const Vec3 slip = b.toWorld(on_b) - a.toWorld(on_a);
    if (distanceToHull(hull, inPlane(b.toWorld(on_b))) <= kAnchorOnPatch * margin &&
        (slip - n * n.dot(slip)).norm() <= margin) {
      m.anchor_a = on_a;
      m.anchor_b = on_b;
      m.anchor_turn = same ? previous->anchor_turn : previous->anchor_turn.conjugate();
      m.anchor_kept = true;
      m.kept_pressure = previous->pressure;
      return;
    }
  }
  freshAnchor(m, a, b);
}

void describePatch(ContactManifold& m, const Contact* contacts, const BodyState& a,
                   const BodyState& b) {
  // The overlapping points (all of them when none overlaps yet) in the
  // patch plane, (u, v) along two tangents; h: their mean height along n.
  const Vec3& n = contacts[m.first].normal;
  const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
  thread_local std::vector<Vec2> points;
  points.clear();
  points.reserve(scratchPoints(m.count));
  double h = 0.0;
  for (int pass = 0; pass < 2 && points.empty(); ++pass) {
    for (int i = m.first; i < m.first + m.count; ++i) {
      const Contact& c = contacts[i];
      const Vec3 p_b = b.toWorld(c.local_b);
      if (pass == 0 && (p_b - a.toWorld(c.local_a)).dot(n) >= 0.0) continue;
      points.emplace_back(u.dot(p_b), v.dot(p_b));
      h += n.dot(p_b);
    }
  }
  h /= static_cast<double>(points.size());
  thread_local std::vector<Vec2> hull;
  convexHull(points, hull);
  const PatchShape shape = shapeOf(hull);
  const Vec3 centre = shape.centre.x() * u + shape.centre.y() * v + h * n;
  m.centre_a = a.toLocal(centre);
  m.centre_b = b.toLocal(centre);
  m.patch_radius = shape.radius;
  m.patch_has_area = shape.has_area;
}

void describePool(FrictionPool& pool, const std::vector<Vec3>& points, const Vec3& n, std::vector<Vec3>& hull) {
  const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
  thread_local std::vector<Vec2> flat, flat_hull;
  flat.clear();
  flat.reserve(scratchPoints(static_cast<int>(points.size())));
  double h = 0.0;
  for (const Vec3& p : points) {
    flat.emplace_back(u.dot(p), v.dot(p));
    h += n.dot(p);
  }
  h /= static_cast<double>(points.size());
  convexHull(flat, flat_hull);
  const PatchShape shape = shapeOf(flat_hull);
  for (const Vec2& p : flat_hull) hull.push_back(p.x() * u + p.y() * v + h * n);
  pool.hull_count = static_cast<int>(flat_hull.size());
  pool.centre = shape.centre.x() * u + shape.centre.y() * v + h * n;
  pool.radius = shape.radius;
}

namespace {

/// Velocity change of a point impulse p (kg m/s) on b at r_b and -p on a at
/// r_a, over a substep of h s: recorded in the bodies' impulses as p h,
/// which divided by h^2 is the force, as for the position rows (body.h).
void applyVelocityImpulse(BodyState& a, BodyState& b, const Vec3& r_a, const Vec3& r_b,
                          const Vec3& p, double h) {
  b.v += p * b.inv_mass;
  b.omega += b.applyInvInertia(r_b.cross(p));
  a.v -= p * a.inv_mass;
  a.omega -= a.applyInvInertia(r_a.cross(p));
  b.impulse += h * p;
  b.angular_impulse += h * r_b.cross(p);
  a.impulse -= h * p;
  a.angular_impulse -= h * r_a.cross(p);
}

double inverseMassAlong(const BodyState& a, const BodyState& b, const Vec3& r_a, const Vec3& r_b,
                        const Vec3& dir) {
  return generalizedInverseMass(a, r_a, dir) + generalizedInverseMass(b, r_b, dir);
}

// Dynamic friction of a pooled manifold (bound: mu_d lambda_n / h, kg
// m/s) along -t at arms r_a, r_b, level: the couple of the friction at
// the body's base goes into its supports' pressures (patchCouple, the
// position pass's level hold), not into a pitch. Applied free, the pitch
// of a plank sliding on two posts pressed the leading post in, the
// position pass lifted it out, and the posts' pressures summed to 1.2 %
// over its weight: mu_d x that braked it 3.2 % too hard (6.5 % on a bed of
// 64 balls; DESIGN, "Forty-eighth session"). Returns false, applying
// nothing, where the couple would take the pressure's centre off the
// pool's compound patch: the body tips, and its friction is applied free.
bool levelDynamicFriction(const ContactManifold& m, const Contact* contacts, BodyState& a, BodyState& b,
                          const FrictionPool& pool, const Vec3& r_a, const Vec3& r_b, const Vec3& n, const Vec3& t,
                          double bound, double speed, double h) {
  const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
  const Mat3 inv_inertia_a = inverseInertiaWorld(a), inv_inertia_b = inverseInertiaWorld(b);
  const Vec3 couple = patchCouple(inv_inertia_a, inv_inertia_b, r_a, r_b, t, u, v);  // per unit impulse along t
  const Vec3 turn_b = inv_inertia_b * (r_b.cross(t) + couple);
  const Vec3 turn_a = -(inv_inertia_a * (r_a.cross(t) + couple));
  const double w = a.inv_mass + b.inv_mass + t.dot(turn_b.cross(r_b) - turn_a.cross(r_a));
  if (!(w > 0.0)) return false;
  // The impulse and its couple do work -impulse (speed + couple . (w_b -
  // w_a)) + impulse^2 w / 2: taken no larger than that rate over w, never
  // positive (a body pitching against its couple is not pushed on).
  const double rate = std::min(speed, speed + couple.dot(b.omega - a.omega));
  const double impulse = std::min(bound, std::max(0.0, rate) / w);  // kg m/s, along -t
  // The couple as a position-level impulse (kg m^2) against the pool's
  // pressure (kg m): the same ratio, metres.
  if (pool.pressure <= 0.0 || !centreOnPatch(m, contacts, a, b, &pool, n, -impulse * h * couple, pool.pressure))
    return false;
  applyVelocityImpulse(a, b, r_a, r_b, -impulse * t, h);
  const Vec3 L = -impulse * couple;  // angular impulse on b, kg m^2/s
  b.omega += b.applyInvInertia(L);
  a.omega -= a.applyInvInertia(L);
  b.angular_impulse += h * L;
  a.angular_impulse -= h * L;
  return true;
}

}  // namespace

void solveContactVelocities(const ContactManifold& m, const Contact* contacts, BodyState& a,
                            BodyState& b, double h, double rest_speed, const FrictionPool* pool) {
  const int end = m.first + m.count;
  double lambda_n = 0.0;
  for (int i = m.first; i < end; ++i) lambda_n += contacts[i].lambda_n;
  if (lambda_n <= 0.0) return;
  // The velocity of a body's point at world lever r. A kinematic body's is
  // the chord its material point travelled over the substep, as a dynamic
  // body's velocity is read from its poses: its own velocity at the end
  // pose (a turntable's tangent there) is off a held point's chord by
  // omega^2 |r| h / 2 toward the axle, which dynamic friction braked on
  // top of the static friction (a box on a turntable held to 26-46 % past
  // mu_s m g; DESIGN, "Thirty-fifth session").
  const auto pointVelocity = [&](const BodyState& s, const Vec3& r) -> Vec3 {
    if (s.kinematic) return ((s.x + r) - (s.x_prev + s.q_prev * (s.q.conjugate() * r))) / h;
    return s.v + s.omega.cross(r);
  };
  // A curved pair's velocity, read from its poses, is the chord of its
  // path around the curve: it leans out of the end normal by half the turn
  // of the normal over the substep, (v_t h / R) / 2. Taken out as an
  // approach, that outward lean cost the motion what makes a ball leave a
  // log: it clung on to half the centripetal speed, till cos theta = 5/12
  // where rolling leaves at 10/17. Measured against the normal midway
  // through the substep (the bisector of the start's and the end's, to
  // which a chord of a circle is square), the chord is no approach.
  const auto midNormal = [&](const Contact& c) -> Vec3 {
    Vec3 P, Q;
    if (c.core_a < 0.0 || !closestCorePoints(c, a.x_prev, a.q_prev, b.x_prev, b.q_prev, P, Q)) return c.normal;
    const Vec3 mid = c.normal + (Q - P).normalized();
    return mid.norm() > 1e-12 ? Vec3(mid.normalized()) : c.normal;
  };
  for (int i = m.first; i < end; ++i) {
    // Restitution (eq. 34), per pressed point; e = 0 for slow contacts.
    const Contact& c = contacts[i];
    if (c.lambda_n <= 0.0) continue;
    const Vec3 n = midNormal(c);
    // A curved point's arms midway too, each its radius along that normal
    // off its core: a ball's spin then moves no point of it along n (at
    // the end's arms, a rolling ball's spin read as an approach by that
    // same lean, and it clung to the log as before).
    Vec3 r_a = a.q * c.local_a, r_b = b.q * c.local_b;
    if (c.core_a >= 0.0) {
      r_a += c.radius_a * (n - c.normal);
      r_b -= c.radius_b * (n - c.normal);
    }
    const Vec3 v = pointVelocity(b, r_b) - pointVelocity(a, r_a);
    const double e = std::abs(c.normal_speed_before) <= rest_speed ? 0.0 : c.restitution;
    const double dvn = -n.dot(v) + std::max(-e * c.normal_speed_before, 0.0);
    if (const double w = inverseMassAlong(a, b, r_a, r_b, n); w > 0.0 && dvn != 0.0)
      applyVelocityImpulse(a, b, r_a, r_b, n * (dvn / w), h);
  }
  // Dynamic friction (eq. 30) at the patch centre, bounded in impulse:
  // mu_d |f_n| h = mu_d lambda_n / h. A patch with area that let go at
  // its last visit but held at an earlier one this substep keeps that
  // hold's static friction (the Gauss-Seidel visits after it moved the
  // bodies on): it slid, so what it holds against the sliding counts
  // toward mu_d lambda_n. Counted twice, a cube whose hold failed on
  // alternate substeps past the friction angle was braked by 0.7 of its
  // weight on those and rocked between the two, sliding at 1 cm/s where
  // it should have sped up (DESIGN, "Thirty-fifth session").
  const Contact& c = contacts[m.first];
  const bool slid_after_holding = !m.stuck && (m.patch_has_area || m.pool >= 0);
  const Vec3 r_a = a.q * m.centre_a, r_b = b.q * m.centre_b;
  const Vec3 v = pointVelocity(b, r_b) - pointVelocity(a, r_a);
  const Vec3 n_mid = midNormal(c);
  const Vec3 vt = v - n_mid * n_mid.dot(v);
  const double vt_len = vt.norm();
  if (vt_len >= 1e-15) {
    const Vec3 t = vt / vt_len;
    const double held = slid_after_holding ? std::max(0.0, -m.friction_impulse.dot(t)) : 0.0;
    const double bound = std::max(0.0, c.dynamic_friction * lambda_n - held) / h;
    const bool level = pool && levelDynamicFriction(m, contacts, a, b, *pool, r_a, r_b, n_mid, t, bound, vt_len, h);
    if (const double w = inverseMassAlong(a, b, r_a, r_b, t); !level && w > 0.0)
      applyVelocityImpulse(a, b, r_a, r_b, -t * std::min(bound, vt_len / w), h);
  }
  // Dynamic twist friction: the spin about n, braked by a torque of at
  // most mu_d |f_n| x the patch radius. (Less what an earlier hold braked,
  // as above, the humanoid sample's landing made 1.07 J in a frame at 12
  // iterations, 0.43 J without.)
  const Vec3& n = c.normal;
  const double spin = n.dot(b.omega - a.omega);
  const double w = n.dot(a.applyInvInertia(n)) + n.dot(b.applyInvInertia(n));
  if (spin == 0.0 || !(w > 0.0) || m.patch_radius <= 0.0) return;
  const double impulse = std::min(c.dynamic_friction * lambda_n * m.patch_radius / h, std::abs(spin) / w);
  const Vec3 L = -std::copysign(impulse, spin) * n;  // angular impulse on b, kg m^2/s
  b.omega += b.applyInvInertia(L);
  a.omega -= a.applyInvInertia(L);
  b.angular_impulse += h * L;
  a.angular_impulse -= h * L;
}

}  // namespace reeve
