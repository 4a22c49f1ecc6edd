// A fixed point on a turning body moves on a circle, and a span's length
// from it is first order in the turn only until the point's arm lines up
// with the span, where the length is least or most over the turn. A
// solver step that turns the point past there overshoots: both solvers
// turn such a point at most to that pose (DESIGN, "A light crank"):
// Gauss-Seidel's visits (path_constraint.cpp, distance_constraint.cpp)
// and the direct solver's steps (DirectSolver::stiffenTurns).
#pragma once

#include <algorithm>
#include <cmath>

#include "reeve/engine/math.h"

namespace reeve {

/// Turns below these (rad) are not checked. Gauss-Seidel's visit turns a
/// body by its one row: past the line-up by 1e-3 rad the span's length is
/// off its linear model by r 5e-7. The direct solver's step turns it by
/// all its rows: a fixed end at its line-up (the crane's luff on its mast)
/// is turned by the others' (a few mrad), which a cap there locked (1.3e6 J
/// made at 1 x 10); under 0.1 rad the model is off by r 0.005 at most.
inline constexpr double kTrustedVisitTurn = 1e-3;
inline constexpr double kTrustedStepTurn = 0.1;

/// The speed (m/s) a direct step's model of a fixed end's turn may leave
/// unmet. What the model misses of the span's length, up to |arm| a^2 / 2
/// for a turn a, one iteration a substep leaves to the next substep, where
/// v = dx / h makes it a speed: a turn under kTrustedStepTurn then costs
/// more the finer the substeps (a 2 g spool's tie point, spun round by its
/// 100 kg weight's snap, made 1 J in a frame at 50 x 1 and 28 J at 1000 x
/// 1, none at 100 x 2; DESIGN, "Forty-fourth session").
inline constexpr double kTrustedStepSpeed = 1e-2;

/// The turn (rad) of a fixed end at world distance `arm` (m) from its
/// body's centre below which the direct step's model is taken as it is, in
/// a substep of `h` (s): kTrustedStepTurn, or less where the length the
/// model may miss over h passes kTrustedStepSpeed.
inline double trustedStepTurn(double arm, double h) {
  if (!(arm > 0.0)) return kTrustedStepTurn;
  return std::min(kTrustedStepTurn, std::sqrt(2.0 * kTrustedStepSpeed * h / arm));
}

/// A point whose length gradient is shorter than this squared (a pinhole
/// the cable bends through by under 0.06 degrees) is not checked: its
/// length hardly turns with it, and its line-up is rounding's.
inline constexpr double kLeastGradient2 = 1e-6;

/// What a turn does to a path's length, to second order in the turn's
/// geometry: a fixed point with world arm r, turned by `angle` (rad) about
/// the unit axis e, changes a span's length (its far end along the unit
/// `toward` from the point) by l1 sin(angle) + l2 (1 - cos(angle)), l1 =
/// e . (toward x r) and l2 = toward . r_perp (r_perp: r off the axis),
/// where the row's linear model says l1 angle. Several points of one body
/// on one path add theirs: the body's length over its turn, whose line-up
/// is not any one point's (a wrap's two tangent points, each lined up with
/// the chord between them, on a wheel whose circle is off its axle). A far
/// end's own curvature (|dp|^2 / length) is left out.
struct TurnModel {
  double l1 = 0.0, l2 = 0.0;
};

/// The turn (rad, in [0, pi]) in the sense of `sign` about the model's
/// axis to the nearest pose where the length is least or most over the
/// turn (dL/d angle = l1 cos + l2 sin = 0): a single point's arm in line
/// with `toward` (where its length shrinks fastest: minus its gradient, a
/// span's direction away from it) or against it. Turning the other way
/// negates l1 and keeps l2.
inline double turnToLineUp(const TurnModel& m, double sign) {
  const double a = std::atan2(sign > 0.0 ? m.l1 : -m.l1, m.l2);  // l1 = R sin a, l2 = R cos a
  constexpr double kPi = 3.14159265358979323846;
  return a < 0.0 ? -a : kPi - a;
}

/// One fixed point's (Gauss-Seidel's visit, path_constraint.cpp): its world
/// arm `arm` turning about the unit axis `e` in the sense of `sign` in line
/// with `toward` or against it.
inline double turnToLineUp(const Vec3& arm, const Vec3& e, double sign, const Vec3& toward) {
  const Vec3 r = arm - e * e.dot(arm), v = toward - e * e.dot(toward);
  const double a = std::atan2(e.dot(v.cross(r)), v.dot(r));  // from v to r about e, in (-pi, pi]
  constexpr double kPi = 3.14159265358979323846;
  if (sign > 0.0) return a < 0.0 ? -a : kPi - a;
  return a > 0.0 ? a : kPi + a;
}

/// The share of its linear model (l1 angle) a turn by `angle` delivers
/// (TurnModel). Toward the line-up the turn gains less than the model (a
/// half at the line-up itself); from near the other line-up, where the
/// model says little, more (a tie point carried nearly to its span's far
/// side, turned back to where its length is least: 2 r where the model
/// said r sin(0.1) a radian). At least 0; 1 where the model says nothing.
inline double turnSecant(const TurnModel& m, double angle) {
  const double linear = m.l1 * angle;
  if (!(std::abs(linear) > 0.0)) return 1.0;
  const double ratio = (m.l1 * std::sin(angle) + m.l2 * (1.0 - std::cos(angle))) / linear;
  return std::max(ratio, 0.0);
}

// The scale s <= 1 of a body's response to a row that turns it at most
// `most` (rad) where the row's step dl (target / w_all) turns it `angle`,
// `per` a unit of lambda, a = t . turn its share of w_all; dl is updated.
// Where nothing else can move, s stays 1 and dl shrinks.
inline double fixedTurnScale(double most, double angle, double per, double a, double w_all, double target,
                             double& dl) {
  const double rest = w_all - a;  // the other bodies' share and the compliance
  if (!(rest > 1e-12 * w_all)) {
    dl *= most / angle;
    return 1.0;
  }
  // |dl(s)| s per = most, dl(s) = target / (rest + s a).
  const double s = most * rest / (std::abs(target) * per - most * a);
  dl = target / (rest + s * a);
  return s;
}

// A visit's cap on one fixed end (Gauss-Seidel: solveSpan, the distance
// constraint): its world arm, the direction its length shrinks along,
// its turn per unit lambda and that turn's share t . turn of the row's w;
// the row's target (-C - alpha~ lambda), w_all (w + alpha~) and step dl,
// and the end's response scale, are updated for it.
inline void capVisitTurn(const Vec3& arm, const Vec3& toward, const Vec3& turn, double share, double target,
                         double& w_all, double& dl, double& scale) {
  const double per = scale * turn.norm(), angle = std::abs(dl) * per;
  if (!(angle > kTrustedVisitTurn)) return;
  const double most = turnToLineUp(arm, turn / turn.norm(), dl, toward);
  if (angle <= most) return;
  const double a = scale * share, more = fixedTurnScale(most, angle, per, a, w_all, target, dl);
  w_all -= (1.0 - more) * a;
  scale *= more;
}

}  // namespace reeve
