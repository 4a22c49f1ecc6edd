// Bodies so light beside the loads their cables carry that the solvers
// take them as massless: placed on their spans between iterations
// (World::solveDirect, World::sweepGaussSeidel; DESIGN, "Forty-first
// session").
//
// A bead a million times lighter than its load, tied into a rigid chain
// that starts bent, is whipped across as the chain lines up, and its
// cables pull it sideways with their tension times their small angle (a
// tightrope). Newton's steps on bead and load together start from a
// tension the first solve found by moving the cheap bead, 200 times short
// at the catch, and needed 3 to 8 iterations a substep to settle; with
// fewer, the spans ended stretched and the next substep threw the load up
// at the stretch over h (15 kJ in a frame under a 4 t load). A massless
// bead has no dynamics of its own: wherever both spans are taut it lies
// on them (on the straight line between its neighbours once they are
// their lengths apart), so it is placed there and each solve linearizes
// the chain where it really bends. Gauss-Seidel stalled on it whatever
// its place (each visit of a span moved the bead, not the load: the 1e-6
// bead's spans stretched past 1 % in 80 of its 88 cells on `reeve bench
// extremes`); there
// one row between the run's ends, of the spans' summed length, stands for
// its spans (World::sweepGaussSeidel), and the run is placed after each
// sweep.
#pragma once

#include <vector>

#include "reeve/engine/body.h"

namespace reeve {

class World;
struct Island;

/// At most this share of the lighter dynamic body at its run's two ends
/// (the bodies its spans lead to, through other light ones; a wheel where
/// there is none: findLightBodies), a body is
/// taken as massless. Measured on `reeve bench extremes`' bead (its 44
/// budgets, the chain bent 5 or 30 cm): placed, beads of 1e-8 to 1e-3 of
/// their load are stable in every cell under both solvers. The bead of
/// 1e-3, left unplaced until the fifty-seventh session, failed in 4 of its
/// 88 cells (both bends) under the direct solver (one iteration at 30 and
/// 60 Hz made energy) and in 34 of 88 under Gauss-Seidel (its spans
/// stretched up to 4.7 times the map's 1 %); placed by the forty-first
/// session's solver it failed in 39. 2e-3 keeps the measured 1e-3 off the
/// threshold. Knots of 3e-3 to 0.1 of their load, not placed, fail in 2
/// direct cells of 88 (3e-3 and 5e-3) and 8 to 42 Gauss-Seidel ones;
/// placed with the share at 1e-2 they passed, but a placed knot's weight
/// is not all in its spans' tensions (the direct solver's read half of it,
/// Gauss-Seidel's none), and the share bounds what is left out (DESIGN,
/// "Fifty-eighth session").
inline constexpr double kMasslessShare = 2e-3;

/// A light body and its two spans: path ids, and which of each path's two
/// points is on the body; in a run, path[0] is the span towards the run's
/// first end.
struct LightBody {
  BodyId body = 0;
  int path[2] = {0, 0};
  int end[2] = {0, 0};
};

/// Light bodies joined span to span (a cable with several light knots):
/// members [first, first + count) of the bodies' list, in order from one
/// end body to the other.
struct LightRun {
  int first = 0, count = 0;
};

/// The island's runs of light bodies now, into `bodies` and `runs`
/// (cleared; their storage kept). A member: a dynamic body, not a rotor,
/// held by exactly two enabled rigid spans (two-point paths, unweighted,
/// compliance 0, tied at one fixed point of the body) and by nothing else
/// (no joint, distance constraint, contact or other path). A run: members
/// joined by their spans, between two end bodies that are not members and
/// not one body (a closed ring of members is no run), each member at most
/// kMasslessShare of the lighter dynamic end body, or where neither is
/// one, of the lighter hinged wheel (a rotor) there, counted with its
/// rim's mass I / r^2 and the dynamic bodies its other spans lead to. The
/// spans' ends on the end bodies may roll: a knot tied in a cable that
/// comes off a wheel.
/// `scratch` holds the spans' ends and the members.
void findLightBodies(const World& world, const Island& island, std::vector<LightBody>& scratch,
                     std::vector<LightBody>& bodies, std::vector<LightRun>& runs);

/// Each run placed where massless bodies would lie. Once its end bodies'
/// tie points are further apart than its rest lengths' sum, every member
/// on the straight line between them, each span long by an even share of
/// the excess (the solve takes that back through the ends). A rolling end
/// counts from where the solve holds its tangent point, its span longer by
/// the cable its wheel's turn paid out (SolvePoint; `stores`: as the
/// direct solver's rows, no more than a spool holds). Else each
/// member from its neighbours as they are, the run swept as many times as
/// it has members: left where it is while both its spans are within
/// their rest lengths; moved the least onto the one it overstretches, or
/// onto their circle where it overstretches both. The move is a
/// correction of where a body is, not of how it moves: its start pose
/// x_prev moves with it, so that v = (x - x_prev) / h keeps only what the
/// solves did, until setLightVelocities sets it after the last.
void placeLightBodies(World& world, const std::vector<LightBody>& bodies, const std::vector<LightRun>& runs,
                      bool stores);

/// Each run's members given the motion a massless body has, after the
/// substep's last placement: what the cable at the run's ends moved this
/// substep (a fixed end's tie point; at a rolling end, along the tangent
/// by the arc its wheel turned), shared by where along the run the member
/// lies, as start pose x_prev = x - that, so v = (x - x_prev) / h. Placed
/// without it, a member kept the velocity its integration gave it, which
/// nothing took back: a 1 g bead hanging still under 40 kg read -49 m/s
/// after 10 s (half of gravity's g h a substep).
/// `stores`: as placeLightBodies.
void setLightVelocities(World& world, const std::vector<LightBody>& bodies, const std::vector<LightRun>& runs,
                        bool stores);

}  // namespace reeve
