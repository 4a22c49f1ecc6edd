// Cable machines generated in code, for the tests and benchmarks that sweep
// masses, loads, wheel counts and solver settings beyond the shipped scene
// files: the Atwood machine (on a fixed or a swinging axle, slack or taut,
// rigid or elastic), a cable zig-zagging over K wheels, a block and tackle
// with sheaves on a moving block, and the paper's Hilbert-curve machine
// (Fig. 1 right, Fig. 18). Each returns a Scene (scene.h) and the ids of
// its parts; closed forms of their motion are derived in
// reeve/machines/closed_forms.h. Wheels are solid cylinders: I = M r^2 / 2.
#pragma once

#include <string>
#include <vector>

#include "reeve/scene/scene.h"

namespace reeve::machines {

/// Solver knobs every machine takes.
struct Budget {
  int substeps = 10;
  int iterations = 2;
  SolverKind solver = SolverKind::Direct;
};

/// Two boxes on a cable over one wheel of radius `radius_m` hinged at the
/// origin about z: `light` hangs on the left (x = -r), `heavy` on the right
/// (x = +r), both `drop_m` below the wheel. With `arm_kg` > 0 the wheel's
/// axle is not the world but the lower end of a swinging arm (a 1 m bar
/// hinged to the world at (0, 1, 0)) of that mass. `slack_m` of extra cable
/// goes to the heavy side; `heavy_speed_m_per_s` starts the heavy box
/// moving down (a jerk when it meets the slack); `compliance_m_per_N` is
/// that of the whole cable.
struct AtwoodSpec {
  double light_kg = 1.0, heavy_kg = 2.0, wheel_kg = 2.0, radius_m = 0.3;
  double gravity = 10.0;  // m/s^2, along -y
  double drop_m = 3.0;
  double arm_kg = 0.0;
  double slack_m = 0.0;
  double heavy_speed_m_per_s = 0.0;
  double compliance_m_per_N = 0.0;
  Budget budget;
};

struct Atwood {
  AtwoodSpec spec;
  Scene scene;
  BodyId wheel = 0, light = 0, heavy = 0, arm = kWorldBody;
  HingeId axle = 0;  // the wheel's hinge (to the world or to the arm)
  int cable = 0;     // joint 0: light -> wheel, joint 1: wheel -> heavy
};
Atwood atwood(const AtwoodSpec& spec);

/// One cable over K wheels of radius `radius_m` and mass `wheel_kg`,
/// zig-zagging between a top row (y = 0, the cable over the wheel) and a
/// bottom row (y = -`rows_apart_m`, under it), `pitch_m` apart in x; the
/// first and last wheels are top wheels (with K even the last two both
/// are). `light` hangs from the first wheel's left side, `heavy` from the
/// last one's right side, `drop_m` below the top row. Every wheel is hinged
/// to the world at its centre.
struct ZigZagSpec {
  int wheels = 8;
  double wheel_kg = 0.1, radius_m = 0.1, pitch_m = 0.4, rows_apart_m = 0.8;
  double light_kg = 1.0, heavy_kg = 2.0, gravity = 10.0, drop_m = 2.0;
  Budget budget;
};

struct ZigZag {
  ZigZagSpec spec;
  Scene scene;
  std::vector<BodyId> wheels;
  std::vector<HingeId> axles;
  BodyId light = 0, heavy = 0;
  int cable = 0;  // joint 0 leaves the light box, joint K arrives at the heavy one
};
ZigZag zigzag(const ZigZagSpec& spec);

/// A block and tackle (paper Fig. 1 centre): a static upper block with two
/// sheaves, a moving lower block of `block_kg` with two sheaves on hinges,
/// sheaves of radius `radius_m` and mass `sheave_kg`, `drop_m` apart. The
/// cable is tied to the upper block, runs under lower sheave A, over upper
/// sheave A, under lower sheave B, over upper sheave B and down to a
/// `counterweight_kg` box: four strands carry the lower block, so the
/// counterweight moves four times as far.
struct BlockAndTackleSpec {
  double block_kg = 4.0, sheave_kg = 0.004, counterweight_kg = 1.001, radius_m = 0.1;
  double drop_m = 2.0, gravity = 10.0;
  Budget budget;
};

struct BlockAndTackle {
  BlockAndTackleSpec spec;
  Scene scene;
  BodyId upper_block = 0, lower_block = 0, counterweight = 0;
  BodyId upper[2] = {0, 0}, lower[2] = {0, 0};  // sheaves A, B
  HingeId lower_axles[2] = {0, 0};
  int cable = 0;
};
BlockAndTackle blockAndTackle(const BlockAndTackleSpec& spec);

/// A belt (a closed cable) round K wheels of radius `radius_m` set on a
/// circle in the z = 0 plane, each hinged to the world at its centre; wheel
/// k weighs 10^(spread x ((7 k mod 5) - 2) / 2) kg, from 10^-spread to
/// 10^spread kg, neighbours far apart. A motor on wheel 0 drives it at
/// `motor_speed_rad_per_s` with at most `motor_torque_Nm`. No gravity.
struct BeltRingSpec {
  int wheels = 16;
  double radius_m = 0.1, spread = 0.0;
  double motor_speed_rad_per_s = 5.0, motor_torque_Nm = 100.0;
  Budget budget;
};

struct BeltRing {
  BeltRingSpec spec;
  Scene scene;
  std::vector<BodyId> wheels;
  HingeId motor = 0;
  int cable = 0;
};
BeltRing beltRing(const BeltRingSpec& spec);

/// The paper's Hilbert machine (Fig. 1 right, Fig. 18): a wheel (a disc
/// of `radius_m`, `wheel_kg`) at every point of a 3D Hilbert curve of
/// `level` (8^level wheels, `pitch_m` apart), each hinged to the world at
/// its centre with its axis normal to the curve's turn there (so its cable
/// plane holds the directions of both spans that meet it) or, where the
/// curve runs straight, the neighbour's axis (the cable crosses over). One
/// cable runs along the curve: it starts wound on the first wheel, a drum
/// whose motor (`motor_speed_rad_per_s`, at most `motor_torque_Nm`) winds
/// it in, and ends at a `load_kg` box hanging `load_drop_m` below the last
/// wheel or, with
/// `brake_torque_Nm` > 0, wound on the last wheel, a drum braked with that
/// torque (a velocity drive to 0). Every span starts `slack_m` longer than
/// taut. Gravity `gravity` m/s^2 along -y, frames at 60 Hz.
struct HilbertSpec {
  int level = 3;
  double pitch_m = 1.0, radius_m = 0.25, wheel_kg = 1.0;
  double load_kg = 1.0, load_drop_m = 2.0, gravity = 10.0, brake_torque_Nm = 0.0, slack_m = 0.0;
  double motor_speed_rad_per_s = 2.0, motor_torque_Nm = 1000.0;
  double duration_s = 10.0;
  Budget budget;
};

struct Hilbert {
  HilbertSpec spec;
  Scene scene;
  std::vector<BodyId> wheels;
  HingeId motor = 0;      // wheel 0's
  BodyId load = kWorldBody;  // none when the end is a braked drum
  int cable = 0;
};
/// What `reeve generate hilbert --level L --slack S` writes
/// (scenes/hilbert2.json, hilbert2_loose.json, hilbert3.json): every
/// level ends at a drum braked with 10 N m, as in the paper (brake 0: a
/// 10 kg load 3 m down instead); motors at 8 rad/s (2 m/s of cable), level
/// 3's at 1 rad/s, of at most 1000 N m; g = 9.81, 1 substep x 10
/// iterations (the paper's Table 1), 5 s taut, 10 s loose or level 3.
HilbertSpec hilbertSceneSpec(int level, double slack_m);
/// The machine loaded from hilbertSceneJson(spec) (scene_json.h).
Hilbert hilbert(const HilbertSpec& spec);

/// The series of `reeve bench scaling` (scaling_machines.cpp): machines
/// that scale with a count K and stand still, so that every span of every
/// cable carries one known tension, `tension_N`, from statics (frictionless
/// sheaves and wraps turn or slide freely; g along -y, frames at 60 Hz).
/// Wheels and sheaves are solid cylinders 0.1 m in radius.
struct ScalingSpec {
  int count = 4;         ///< K: wheels, falls, cables, machines or passes
  double load_kg = 1.0;  ///< m: each hanging load, or the load per fall
  double gravity = 10.0;  ///< m/s^2
  Budget budget;
};

struct StaticMachine {
  Scene scene;
  double tension_N = 0.0;  ///< every span's tension at rest (N)
};

/// chain: the zig-zag (above) over K >= 2 wheels of 0.1 kg hinged to the
/// world, m at both ends: tension m g in all K + 1 spans.
StaticMachine scalingChain(const ScalingSpec& spec);

/// tackle_hinged: a K-fall block and tackle (K >= 2). K - 1 sheaves of
/// 0.01 m kg, 0.2 m apart in x, alternately hinged to a static upper block
/// (y = 0) and to a moving lower block 2 m below (the last sheave a lower
/// one); the cable is tied to the block opposite the first sheave, runs
/// over and under them all (K vertical falls) and ends at a point on the
/// upper block. The lower block with its sheaves weighs W = K m, its
/// centre of mass under the falls' centre: each fall carries W g / K = m g.
StaticMachine tackleHinged(const ScalingSpec& spec);

/// tackle_rolling: tackleHinged's K falls without sheave bodies: the cable
/// wraps octagons (circumradius 0.1 m, a vertex at each side) that are
/// sections of the two block bodies themselves, frictionless (mu = 0: it
/// slides, one path constraint); the lower block weighs W = K m: m g per
/// fall. Not `sliding`: the cable sticks to the octagons (no-slip rolling
/// links), so each fall is a row of its own on the lower block, K rigid
/// rows on its 6 freedoms: redundant, each carrying m g in the limit of
/// equal elastic falls.
StaticMachine tackleRolling(const ScalingSpec& spec, bool sliding = true);

/// star_rigid / star_compliant: an effector (a box of 0.1 m sides and
/// M = K m) hanging on K cables, each from an anchor on a circle of radius
/// 0.5 m, 1 m from the effector's top centre, to that point: a cone of
/// half-angle theta = 30 degrees. Each cable carries M g / (K cos theta) =
/// m g / cos theta. Rigid: inextensible, taut at the start (K > 3 makes
/// the cables redundant; the symmetric answer is also the least-norm
/// one). Compliant: each cable's rest length is 1 / 1.01 of its span and
/// its compliance (m/N) stretches it by the remaining 1 % at that tension,
/// so it starts at rest in equilibrium.
StaticMachine star(const ScalingSpec& spec, bool compliant);

/// islands: K Atwood machines (wheels 0.3 m in radius, 2 kg, hinged to
/// the world, 1 m apart in x) with m on both sides, in one scene: 2 K
/// spans, tension m g each. `braked`: each wheel also held at 0 rad by an
/// angle drive of at most 1 N m (a brake the balanced loads never slip),
/// whose braking inertia the step finds every substep
/// (World::brakingInverseInertia).
StaticMachine islands(const ScalingSpec& spec, bool braked = false);

/// wound: one cable wound back and forth between two wheels 1 m apart
/// (hinged to the world at (0, 0, 0) and (1, 0, 0)) in K wraps (K even),
/// clockwise round one wheel, then the other: half a turn each, a quarter
/// at the two ends, all frictionless (mu = 0: one path constraint; the
/// top spans lie on one another, as do the bottom ones); m hangs 2 m down
/// from each free end (left of the first wheel, right of the second):
/// tension m g in all K + 1 spans.
StaticMachine wound(const ScalingSpec& spec);

/// threaded: one rope through two frictionless holes (0.2 m apart, on the
/// top face) of each of K bars of 2 m, 0.4 m apart in x and 2 m below a
/// static upper block, and through two holes on hooks 5 cm below the
/// block between bars (K >= 1): tied there above the first bar's left
/// hole, down through each bar and up, ending on a load of m hanging 2 m
/// down past the last bar; every fall vertical, each bar held by two:
/// tension m g in every span. One path of 4 K spans over K + 2 bodies (a tendon
/// through the holes of many links).
StaticMachine threaded(const ScalingSpec& spec);

/// The points (grid units) of the 3D Hilbert curve with 2^level points per
/// side, in curve order; consecutive points are one unit apart (Skilling,
/// "Programming the Hilbert curve", AIP Conf. Proc. 707, 2004).
std::vector<Vec3> hilbertCurve(int level);

}  // namespace reeve::machines
