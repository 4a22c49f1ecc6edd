// Wheels on fixed axles under the direct solver are rotors (body.h): their
// hinge has no rows, so what it would report is worked out from what the
// axle took, and its drive and limit act on the turn alone. Each is checked
// against Gauss-Seidel's hinge rows and against statics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "reeve/engine/world.h"
#include "reeve/machines/machines.h"

namespace reeve::test_rotors {
namespace {

const SolverKind kBoth[] = {SolverKind::GaussSeidel, SolverKind::Direct};

// A world solved by `method` at 20 substeps of 4 iterations.
World worldSolvedBy(SolverKind method) {
  SolverSettings settings;
  settings.solver = method;
  settings.substeps = 20;
  settings.iterations = 4;
  return World(settings);
}

// A 1 kg wheel (solid cylinder, r 0.3 m, 0.1 m thick) at the origin, its
// axis z: I = 0.045 kg m^2.
BodyId addWheel(World& world) {
  BodyDef def;
  def.shape = Shape::cylinder(0.3, 0.05);
  def.mass = 1.0;
  return world.addBody(def);
}

// A 10 kg box (0.6 x 0.2 x 0.2 m) resting on a 1 kg square wheel (1 m
// side) hinged to the world at its centre about z, the hinge's drive set to
// `drive` with no torque bound, so the wheel is held still.
struct BoxOnWheel {
  BodyId wheel, box;
  HingeId hinge;
  ContactMaterial material;
};
BoxOnWheel boxOnSquareWheel(World& world, HingeDrive::Mode drive) {
  BodyDef def;
  def.shape = Shape::box(Vec3(0.5, 0.5, 0.1));
  def.mass = 1.0;
  def.collides = true;
  BoxOnWheel r;
  r.material = def.material;
  r.wheel = world.addBody(def);
  def.shape = Shape::box(Vec3(0.3, 0.1, 0.1));
  def.mass = 10.0;
  def.position = Vec3(0.0, 0.6, 0.0);
  r.box = world.addBody(def);
  HingeDef hinge(r.wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ());
  hinge.drive = {drive, 0.0, 0.0};
  r.hinge = world.addHinge(hinge);
  return r;
}

TEST(Rotors, ADriveIntoALimitStopsThereAndPushesWithAllItHas) {
  // A wheel driven at 2 rad/s (at most 5 N m) against an upper limit of
  // 0.5 rad: it stays at the limit and the drive keeps pushing with 5 N m
  // (the limit wins, joint_rows.h); the drive and the limit are one
  // direction twice, which the direct solve must not mistake for one row.
  for (const SolverKind method : kBoth) {
    SolverSettings settings;
    settings.solver = method;
    World world(settings);
    const BodyId wheel = addWheel(world);
    HingeDef hinge(wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ());
    hinge.limit = {true, -0.5, 0.5};
    hinge.drive = {HingeDrive::Mode::Velocity, 2.0, 5.0};
    const HingeId id = world.addHinge(hinge);
    for (int f = 0; f < 60; ++f) world.step(1.0 / 60.0);
    SCOPED_TRACE(solverMethodName(method));
    EXPECT_TRUE(world.body(wheel).isRotor());
    EXPECT_NEAR(world.hingeAngle(id), 0.5, 1e-6);
    EXPECT_NEAR(world.hingeDriveTorque(id), 5.0, 1e-9);
    // Turned the other way, the drive lifts it off the limit at once and
    // spins it up at 5 N m / I for the whole frame.
    world.hinge(id).drive.target = -2.0;
    world.step(1.0 / 60.0);
    const double inertia = 0.5 * 1.0 * 0.3 * 0.3;
    EXPECT_NEAR(world.body(wheel).omega.z(), -5.0 / inertia / 60.0, 1e-6);
  }
}

TEST(Rotors, ADriveIntoALimitPushesWithAllItHasAtEveryBudget) {
  // A velocity drive of at most `cap` N m (or N) turning a wheel into a
  // limit of its hinge, or sliding the same body along a rail into a limit
  // of its slide, either way round: once stalled there it pushes with all
  // of its cap and the limit takes the rest. The direct solve once found
  // the rows met at a new substep (the drive's lambda starts at 0, inside
  // its bounds) and the drive pushed nothing, or kept the push that took it
  // to its target with the limit away (2.7 of 5 N m at one substep a
  // frame): 64 of the 1 kg checks failed so, the test above's cell being
  // one that rounding passed. The direct solver again with a wheel of 1 mg
  // and of a tonne, and a cap of 5 kN m. Gauss-Seidel takes the 1 kg wheel
  // from two iterations a substep: each visit of its drive row adds only
  // what the row's error asks (I w / h at the first), so at one iteration,
  // or on a wheel light against its cap, it stalls short of the cap.
  struct Budget {
    int substeps, iterations;
  };
  struct Case {
    SolverKind method;
    double mass_kg, cap;
  };
  const Budget budgets[] = {{1, 1}, {1, 2}, {4, 2}, {10, 10}};
  const Case cases[] = {{SolverKind::GaussSeidel, 1.0, 5.0}, {SolverKind::Direct, 1.0, 5.0},
                        {SolverKind::Direct, 1e-6, 5.0}, {SolverKind::Direct, 1e-6, 5e3},
                        {SolverKind::Direct, 1e3, 5e3}};
  for (const Case& c : cases)
    for (const Budget& b : budgets) {
      if (c.method == SolverKind::GaussSeidel && b.iterations == 1) continue;
      for (const bool slider : {false, true})
        for (const double limit : {0.3, 0.5, 1.0})
          for (const double speed : {1.0, 2.0, 5.0, -1.0, -2.0, -5.0}) {
            SCOPED_TRACE(std::string(solverMethodName(c.method)) + " " + std::to_string(b.substeps) + " x " +
                         std::to_string(b.iterations) + (slider ? ", slider" : ", hinge") + ", " +
                         std::to_string(c.mass_kg) + " kg, cap " + std::to_string(c.cap) + ", limit " +
                         std::to_string(limit) + ", speed " + std::to_string(speed));
            SolverSettings settings;
            settings.solver = c.method;
            settings.substeps = b.substeps;
            settings.iterations = b.iterations;
            settings.gravity.setZero();
            World world(settings);
            BodyDef def;
            def.shape = Shape::cylinder(0.3, 0.05);
            def.mass = c.mass_kg;
            const BodyId body = world.addBody(def);
            double effort = 0.0, at = 0.0;
            if (slider) {
              PrismaticDef rail;
              rail.body = body;
              rail.limit = {true, -limit, limit};
              rail.drive.mode = PrismaticDrive::Mode::Velocity;
              rail.drive.target = speed;
              rail.drive.max_force = c.cap;
              const PrismaticId id = world.addPrismatic(rail);
              for (int f = 0; f < 90; ++f) world.step(1.0 / 60.0);
              effort = world.prismaticDriveForce(id);
              at = world.prismaticSlide(id);
            } else {
              HingeDef hinge(body, kWorldBody, Vec3::Zero(), Vec3::UnitZ());
              hinge.limit = {true, -limit, limit};
              hinge.drive = {HingeDrive::Mode::Velocity, speed, c.cap};
              const HingeId id = world.addHinge(hinge);
              for (int f = 0; f < 90; ++f) world.step(1.0 / 60.0);
              effort = world.hingeDriveTorque(id);
              at = world.hingeAngle(id);
            }
            // The drive's push over a substep (m or rad; I = m r^2 / 2) and
            // the limit's push back cancel: at one iteration the stop is met
            // to their rounding, 1e-15 of it (3.7e-9 rad for the 1 mg wheel
            // under 5 kN m). Gauss-Seidel's turns are first order (rotateBy):
            // the wheel ends 2.4e-7 rad past its limit at 1 x 2.
            const double h = 1.0 / (60.0 * b.substeps);
            const double push = c.cap * h * h / (slider ? c.mass_kg : 0.5 * c.mass_kg * 0.3 * 0.3);
            EXPECT_NEAR(at, std::copysign(limit, speed),
                        c.method == SolverKind::Direct ? 1e-9 + 1e-15 * push : 1e-6);
            EXPECT_NEAR(effort, std::copysign(c.cap, speed), 1e-12 * c.cap);
          }
    }
}

TEST(Rotors, ALimitItsDrivePullsAwayFromStillHolds) {
  // The wheel starts 0.5 rad past its upper limit (range [-1, -0.5]),
  // driven away from it at 1 rad/s by an unlimited drive: the drive alone
  // would take it 1/60 rad a frame, so the limit must push it the rest of
  // the way in the first frame.
  for (const SolverKind method : kBoth) {
    World world = worldSolvedBy(method);
    world.settings().gravity.setZero();
    world.settings().substeps = 1;
    const BodyId wheel = addWheel(world);
    HingeDef hinge(wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ());
    hinge.limit = {true, -1.0, -0.5};
    hinge.drive = {HingeDrive::Mode::Velocity, -1.0, 0.0};
    const HingeId id = world.addHinge(hinge);
    world.step(1.0 / 60.0);
    SCOPED_TRACE(solverMethodName(method));
    // Gauss-Seidel turns by the first-order rotateBy: 0.5 rad in one go
    // comes out 2 atan(0.25) = 0.49 rad, the rest left to later sweeps.
    EXPECT_LE(world.hingeAngle(id), -0.5 + (method == SolverKind::Direct ? 1e-9 : 0.01));
    for (int f = 0; f < 29; ++f) world.step(1.0 / 60.0);
    EXPECT_NEAR(world.body(wheel).omega.z(), -1.0, 1e-9);  // then it turns at the drive's speed
  }
}

TEST(Rotors, AMotorTurningOverHalfATurnPerSubstepKeepsItsSpeed) {
  // 200 rad/s at one substep of 1/60 s is 3.3 rad a substep: a hinge angle
  // is only known to half a turn, so the drive must take its turn round as
  // far as the wheel went (driveError). An unlimited drive holds 200 rad/s
  // from its first frame (Gauss-Seidel's first-order turns need two); one
  // of 1 N m on a 0.045 kg m^2 wheel spins it up at 22.2 rad/s^2 and stops
  // at 200 rad/s. Gauss-Seidel's first-order turns each fall short by
  // dphi^3 / 12, dphi = tau h^2 / I = 6.2e-3 rad: 1.2e-6 rad/s a substep,
  // at most 8.6e-4 rad/s over the 720 substeps.
  for (const SolverKind method : kBoth) {
    const double tolerance = method == SolverKind::Direct ? 1e-6 * 200.0 : 1e-3;
    for (const double torque : {0.0, 1.0}) {
      World world = worldSolvedBy(method);
      world.settings().gravity.setZero();
      world.settings().substeps = 1;
      const BodyId wheel = addWheel(world);
      HingeDef hinge(wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ());
      hinge.drive = {HingeDrive::Mode::Velocity, 200.0, torque};
      world.addHinge(hinge);
      const double inertia = 0.5 * 0.3 * 0.3, spin_up = torque > 0.0 ? 200.0 * inertia / torque : 0.0;
      SCOPED_TRACE(std::string(solverMethodName(method)) + ", torque " + std::to_string(torque));
      for (int f = 1; f <= 60 * 12; ++f) {
        world.step(1.0 / 60.0);
        const double t = f / 60.0, omega = world.body(wheel).omega.z();
        if (torque > 0.0 && t < spin_up - 0.02) {
          ASSERT_NEAR(omega, torque / inertia * t, tolerance) << t;
        }
        if (t > spin_up + 0.04) {
          ASSERT_NEAR(omega, 200.0, tolerance) << t;
        }
      }
    }
  }
}

TEST(Rotors, TheAxleCarriesWhatRestsOnTheWheel) {
  // A 10 kg box resting on a 1 kg square wheel held still by a rigid angle
  // drive: the axle holds both up, 11 kg x g, whether the contact's push
  // comes through hinge rows (Gauss-Seidel) or a rotor's axle (direct).
  for (const SolverKind method : kBoth) {
    World world = worldSolvedBy(method);
    const HingeId id = boxOnSquareWheel(world, HingeDrive::Mode::Angle).hinge;
    for (int f = 0; f < 60; ++f) world.step(1.0 / 60.0);
    const double weight = 11.0 * -world.settings().gravity.y();
    const JointWrench wrench = world.hingeWrench(id);
    std::printf("[ measured ] %s: axle force %.4f N, 11 kg x g = %.4f N\n", solverMethodName(method), wrench.force.y(),
                weight);
    SCOPED_TRACE(solverMethodName(method));
    EXPECT_NEAR(wrench.force.y(), weight, 1e-3 * weight);
    EXPECT_NEAR(wrench.force.x(), 0.0, 1e-3 * weight);
  }
}

TEST(Rotors, TheAxleTakesABendingMoment) {
  // A 2 kg weight hangs from a rigid link tied 0.2 m along the axle from
  // the 1 kg wheel's centre: the hinge holds 3 kg x g and the moment
  // 2 kg x g x 0.2 m about x, a torque the wheel cannot turn under.
  for (const SolverKind method : kBoth) {
    World world = worldSolvedBy(method);
    BodyDef def;
    def.shape = Shape::cylinder(0.3, 0.25);
    def.mass = 1.0;
    const BodyId wheel = world.addBody(def);
    def.shape = Shape::box(Vec3(0.1, 0.1, 0.1));
    def.mass = 2.0;
    def.position = Vec3(0.0, -1.0, 0.2);
    const BodyId weight = world.addBody(def);
    const HingeId id = world.addHinge(HingeDef(wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ()));
    DistanceConstraint link;
    link.a = wheel;
    link.b = weight;
    link.local_a = Vec3(0.0, 0.0, 0.2);
    link.local_b = Vec3(0.0, 0.1, 0.0);
    link.rest_length = 0.9;
    link.unilateral = false;
    world.addDistance(link);
    for (int f = 0; f < 60; ++f) world.step(1.0 / 60.0);
    const double g = -world.settings().gravity.y();
    const JointWrench wrench = world.hingeWrench(id);
    std::printf("[ measured ] %s: axle force %.4f N (3 g = %.4f), moment %.4f N m (-2 g 0.2 = %.4f)\n",
                solverMethodName(method), wrench.force.y(), 3.0 * g, wrench.torque.x(), -0.4 * g);
    SCOPED_TRACE(solverMethodName(method));
    EXPECT_NEAR(wrench.force.y(), 3.0 * g, 1e-3 * 3.0 * g);
    EXPECT_NEAR(wrench.torque.x(), -0.4 * g, 1e-3 * 0.4 * g);
    EXPECT_NEAR(wrench.torque.z(), 0.0, 1e-9);
  }
}

TEST(Rotors, TheAxleFeelsTheFrictionOfABoxSlidingOverTheWheel) {
  // A 10 kg box pushed at 2 m/s across a square wheel held still: dynamic
  // friction (mu_d 0.3, the default material) drags the wheel along with
  // mu_d m g, which its axle holds; the contacts' velocity pass applies it.
  for (const SolverKind method : kBoth) {
    World world = worldSolvedBy(method);
    const BoxOnWheel rig = boxOnSquareWheel(world, HingeDrive::Mode::Velocity);
    for (int f = 0; f < 30; ++f) world.step(1.0 / 60.0);  // settle
    world.body(rig.box).v = Vec3(2.0, 0.0, 0.0);
    world.step(1.0 / 60.0);
    const double friction = rig.material.dynamic_friction * 10.0 * -world.settings().gravity.y();
    const JointWrench wrench = world.hingeWrench(rig.hinge);
    std::printf("[ measured ] %s: axle force along the slide %.4f N, mu_d m g = %.4f N\n", solverMethodName(method),
                -wrench.force.x(), friction);
    SCOPED_TRACE(solverMethodName(method));
    EXPECT_NEAR(-wrench.force.x(), friction, 0.01 * friction);
  }
}

TEST(Rotors, AWheelThatSaggedOnACompliantHingeIsMadeARotorOnItsAxle) {
  // A 1 g wheel under 1 and 2 kg boxes on a compliant hinge (1e-3 m/N:
  // it sags about (T1 + T2) x 1e-3 = 26 mm) is a free body; its hinge
  // made rigid, it becomes a rotor back on the axle, and stays there.
  for (const SolverKind method : kBoth) {
    SCOPED_TRACE(solverMethodName(method));
    machines::AtwoodSpec spec;
    spec.wheel_kg = 1e-3;
    spec.budget.solver = method;
    machines::Atwood m = machines::atwood(spec);
    World& world = *m.scene.world;
    world.hinge(m.axle).compliance = 1e-3;
    for (int f = 0; f < 20; ++f) world.step(1.0 / 60.0);
    const auto offset = [&] {
      const HingeJoint& j = world.hinge(m.axle);
      return (world.body(j.a).toWorld(j.frame.anchor_a) - world.body(j.b).toWorld(j.frame.anchor_b)).norm();
    };
    EXPECT_FALSE(world.body(m.wheel).isRotor());
    EXPECT_GT(offset(), 1e-3);
    world.hinge(m.axle).compliance = 0.0;
    for (int f = 0; f < 20; ++f) {
      world.step(1.0 / 60.0);
      EXPECT_LT(offset(), 1e-12);
    }
    EXPECT_TRUE(world.body(m.wheel).isRotor());
  }
}

TEST(Rotors, AHingeMadeCompliantStopsBeingARotor) {
  // A rotor cannot sag on its axle; one whose hinge is given compliance
  // after the first step is a free body on that hinge again.
  World world;
  const BodyId wheel = addWheel(world);
  const HingeId id = world.addHinge(HingeDef(wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ()));
  world.step(1.0 / 60.0);
  EXPECT_TRUE(world.body(wheel).isRotor());
  world.hinge(id).compliance = 1e-3;  // m/N: 1 kg hangs g x 1e-3 = 9.8 mm low
  double sag = 0.0;
  for (int f = 0; f < 60; ++f) {
    world.step(1.0 / 60.0);
    sag = std::max(sag, -world.body(wheel).x.y());
  }
  EXPECT_FALSE(world.body(wheel).isRotor());
  // Let go at the axle, it swings down past 9.8 mm, to twice that at most.
  const double hanging = 9.81 * 1e-3;
  EXPECT_GT(sag, hanging);
  EXPECT_LT(sag, 2.0 * hanging);
}

TEST(Rotors, AMotorDrivingALongCableNeverPassesItsTorque) {
  // The level-2 Hilbert machine from rest: the first solves of 64 spans
  // and the motor may run out of active-set passes; the drive's torque
  // stays within its bound all the same.
  machines::HilbertSpec spec;
  spec.level = 2;
  spec.budget = {1, 10};
  spec.motor_torque_Nm = 20.0;
  machines::Hilbert m = machines::hilbert(spec);
  double worst = 0.0;
  for (int f = 0; f < 60; ++f) {
    m.scene.world->step(1.0 / 60.0);
    worst = std::max(worst, std::abs(m.scene.world->hingeDriveTorque(m.motor)));
  }
  std::printf("[ measured ] Hilbert-2 motor: largest drive torque %.6f N m of %.1f\n", worst, spec.motor_torque_Nm);
  EXPECT_LE(worst, spec.motor_torque_Nm * (1.0 + 1e-12));
  EXPECT_GT(worst, 0.5 * spec.motor_torque_Nm);  // it did push
}

}  // namespace
}  // namespace reeve::test_rotors
