// Machines written as MuJoCo models, imported, against their closed forms.
#include <cmath>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>

#include "mjcf_fixture.h"
#include "reeve/scene/energy.h"

namespace reeve::test {
namespace {

constexpr double g = 9.81;

// Steps `frames` frames; returns the time stepped (s).
double stepFrames(Scene& s, int frames) {
  for (int f = 0; f < frames; ++f) s.world->step(1.0 / s.frame_rate_hz);
  return frames / s.frame_rate_hz;
}

// models/atwood.xml: 1 kg and 2 kg over a cylinder of radius 0.1 m (axis y).
// Fixed (MuJoCo's wrap): a frictionless pulley, a = (m2 - m1) g / (m1 + m2),
// T = 2 m1 m2 g / (m1 + m2). Turning: a wheel of 1000 kg/m^3 x pi r^2 x
// 0.1 m, I / r^2 = m / 2. Semi-implicit Euler carries a constant
// acceleration's velocity exactly: v = a t at every substep.
// models/atwood_sphere.xml: the same over a sphere of radius 0.1 m wrapped
// in the plane of the two sites, I / r^2 = 2 m / 5 of a 4.19 kg ball.
TEST(MjcfPhysics, AtwoodOverAWrapCylinderOrSphereMeetsItsClosedForm) {
  const double m1 = 1.0, m2 = 2.0, pi = std::numbers::pi;
  struct Case {
    const char* model;
    MjcfWheels wheels;
    double wheel_inertia_over_r2;  // kg
  };
  for (const Case& c : {Case{"atwood", MjcfWheels::Fixed, 0.0},
                        Case{"atwood", MjcfWheels::Turning, 1000.0 * pi * 0.1 * 0.1 * 0.1 / 2.0},
                        Case{"atwood_sphere", MjcfWheels::Fixed, 0.0},
                        Case{"atwood_sphere", MjcfWheels::Turning, 0.4 * 1000.0 * 4.0 / 3.0 * pi * 0.001}}) {
    const double a = (m2 - m1) * g / (m1 + m2 + c.wheel_inertia_over_r2), light_tension = m1 * (g + a);
    Scene s = importedScene(c.model, c.wheels);
    const BodyId heavy = bodyNamed(s, "heavy"), light = bodyNamed(s, "light");
    const double t = stepFrames(s, 20);
    const double v = s.world->body(heavy).v.z();
    EXPECT_NEAR(v, -a * t, 1e-7 * a * t) << c.model << (c.wheels == MjcfWheels::Turning ? " turning" : " fixed");
    EXPECT_NEAR(s.world->body(light).v.z(), a * t, 1e-7 * a * t);
    EXPECT_NEAR(s.cables->tension(0, 0), light_tension, 1e-7 * light_tension);
    // The boxes hang straight: nothing moves them sideways.
    EXPECT_NEAR(s.world->body(heavy).x.x(), 0.1, 1e-9);
  }
}

// models/pulley.xml: a tendon of three pulley branches (divisors 1, 2, 2)
// is a junction of three cables: the counterweight on the first pulls
// with T, each load on the others with T / 2, and
// T = 2 g / (1 / m_c + 1 / (4 m_l) + 1 / (4 m_r)); v = a t exactly. Also
// with a 2.2 t counterweight (a 43 kN pull) and one of 2.2 mg (1e-6 of a
// load), and with the loads balanced (m_c = 2 m_l = 2 m_r: nothing moves,
// T = m_c g).
TEST(MjcfPhysics, PulleyBranchesPullAsAFloatingPulleyBlock) {
  std::ifstream in(mjcfModel("pulley"));
  const std::string xml((std::istreambuf_iterator<char>(in)), {});
  for (const double m_c : {2.2, 2.2e3, 2.2e-6, 2.0}) {
    std::string model = xml;
    const std::string from = "mass=\"2.2\"";
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", m_c);
    model.replace(model.find(from), from.size(), "mass=\"" + std::string(text) + "\"");
    const auto path = writeModel("pulley_mass", model);
    const MjcfImport imported = importMjcf(path);
    Scene s = parseScene(imported.scene_json, path.string());
    ASSERT_EQ(s.cables->junctions().size(), 1u);
    const double T = 2.0 * g / (1.0 / m_c + 0.5), a_c = T / m_c - g, a_l = T / 2.0 - g;
    const double t = stepFrames(s, 20);
    const double scale = std::max(std::abs(a_c), g) * t;
    EXPECT_NEAR(s.world->body(bodyNamed(s, "counterweight")).v.z(), a_c * t, 1e-7 * scale) << m_c << " kg";
    EXPECT_NEAR(s.world->body(bodyNamed(s, "load_left")).v.z(), a_l * t, 1e-7 * scale) << m_c << " kg";
    EXPECT_NEAR(s.world->body(bodyNamed(s, "load_right")).v.z(), a_l * t, 1e-7 * scale) << m_c << " kg";
    EXPECT_NEAR(s.cables->tension(0, 0), T, 1e-7 * T) << m_c << " kg";
    EXPECT_NEAR(s.cables->tension(0, 1), T, 1e-7 * T) << "the lift branch's span past the beam's site";
    EXPECT_NEAR(s.cables->tension(1, 0), T / 2.0, 1e-7 * T);
    EXPECT_NEAR(s.cables->tension(2, 0), T / 2.0, 1e-7 * T);
  }
}

// The junction's length is MuJoCo's: sum_b L_b / divisor_b at load is the
// range's upper end (6 m), its branches at equal strain.
TEST(MjcfPhysics, PulleyBranchesShareTheTendonsLength) {
  Scene s = importedScene("pulley");
  const Junction& junction = s.cables->junctions()[0];
  EXPECT_NEAR(s.world->path(junction.path).rest_length, 6.0, 1e-12);
  EXPECT_NEAR(s.world->pathLength(junction.path), 6.0, 1e-12);
  EXPECT_EQ(junction.scales, (std::vector<double>{1.0, 0.5, 0.5}));
}

// A muscle is a winch pulling with its control times its peak force F0:
// its `force`, or MuJoCo's scale / acc0, acc0 the joint acceleration a
// unit tendon force gives at load. A 2 kg box on a vertical slide hung
// from a tendon: acc0 = 1 / 2 kg, F0 = 200 / 0.5 = 400 N, and at control
// 0.1 it rises at 40 / 2 - g; with force="60" at control 0.5, at
// 30 / 2 - g. A 1 kg rod of 0.5 m on a hinge at its end, its tendon 0.2 m
// from the axle: acc0 = 0.2 / I = 2.4 rad/s^2 per N, F0 = 83.4 N, and at
// control 0.05 the rod turns at 0.05 F0 x 0.2 / I.
TEST(MjcfPhysics, MusclesPullWithControlTimesPeakForce) {
  const auto slide = [](const std::string& muscle) {
    return R"(<mujoco>
  <worldbody>
    <site name="top" pos="0 0 2"/>
    <body name="box" pos="0 0 0">
      <joint name="lift" type="slide" axis="0 0 1"/>
      <geom type="box" size="0.1 0.1 0.1" mass="2"/>
      <site name="hook" pos="0 0 0.1"/>
    </body>
  </worldbody>
  <tendon><spatial name="rope"><site site="top"/><site site="hook"/></spatial></tendon>
  <actuator>)" + muscle + R"(</actuator>
</mujoco>)";
  };
  struct Case {
    std::string muscle;
    double control, pull;
  };
  for (const Case& c : {Case{R"(<muscle name="m" tendon="rope"/>)", 0.1, 40.0},
                        Case{R"(<muscle name="m" tendon="rope" force="60"/>)", 0.5, 30.0}}) {
    const auto path = writeModel("muscle_slide", slide(c.muscle));
    MjcfOptions options;
    options.controls["m"] = c.control;
    Scene s = parseScene(importMjcf(path, options).scene_json, path.string());
    ASSERT_EQ(s.cables->cables().size(), 1u);
    EXPECT_NEAR(s.cables->cables()[0].winch->max_pull, c.pull, 1e-6 * c.pull) << c.muscle;
    const double t = stepFrames(s, 12), a = c.pull / 2.0 - g;
    EXPECT_NEAR(s.world->body(bodyNamed(s, "box")).v.z(), a * t, 1e-6 * a * t) << c.muscle;
  }
  const auto path = writeModel("muscle_hinge", R"(<mujoco>
  <option gravity="0 0 0"/>
  <worldbody>
    <site name="anchor" pos="0.2 0 1"/>
    <body name="rod">
      <joint name="pivot" type="hinge" axis="0 1 0"/>
      <geom type="box" size="0.25 0.01 0.01" pos="0.25 0 0" mass="1"/>
      <site name="hook" pos="0.2 0 0"/>
    </body>
  </worldbody>
  <tendon><spatial name="rope"><site site="anchor"/><site site="hook"/></spatial></tendon>
  <actuator><muscle name="m" tendon="rope"/></actuator>
</mujoco>)");
  MjcfOptions options;
  options.controls["m"] = 0.05;
  Scene s = parseScene(importMjcf(path, options).scene_json, path.string());
  const double inertia = 1.0 / 12.0 * (0.5 * 0.5 + 0.02 * 0.02) + 1.0 * 0.25 * 0.25;  // about the axle
  const double f0 = 200.0 / (0.2 / inertia);
  ASSERT_EQ(s.cables->cables().size(), 1u);
  EXPECT_NEAR(s.cables->cables()[0].winch->max_pull, 0.05 * f0, 1e-6 * f0);
  const double t = stepFrames(s, 2), alpha = 0.05 * f0 * 0.2 / inertia;  // 0.005 rad turned: the arm stays 0.2 m
  EXPECT_NEAR(std::abs(s.world->body(bodyNamed(s, "rod")).omega.y()), alpha * t, 1e-4 * alpha * t);
}

// Contacts between bodies from the geoms' contype and conaffinity: a
// 0.2 m box dropped 0.05 m onto another on the floor rests on it (centre at
// 0.3 m); with contype and conaffinity 0 on the top box, or the pair in a
// <contact><exclude>, it falls through onto the floor (0.1 m). A link
// hinged inside its parent's box never touches it (MuJoCo's filterparent)
// and swings freely through it.
TEST(MjcfPhysics, ContactsBetweenBodiesFollowTheGeomsBits) {
  const auto model = [](const std::string& top_geom, const std::string& contact) {
    return R"(<mujoco>
  <worldbody>
    <geom type="plane" size="5 5 0.1"/>
    <body name="bottom" pos="0 0 0.1"><freejoint/><geom type="box" size="0.1 0.1 0.1" mass="1"/></body>
    <body name="top" pos="0 0 0.35"><freejoint/><geom type="box" size="0.1 0.1 0.1" mass="1" )" + top_geom + R"(/></body>
    <body name="frame" pos="2 0 1">
      <joint type="slide" axis="0 0 1" range="-0.01 0.01"/>
      <geom type="box" size="0.3 0.3 0.3" mass="5"/>
      <body name="swing">
        <joint name="pivot" type="hinge" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0.25 0 0" size="0.02" mass="0.5"/>
      </body>
    </body>
  </worldbody>)" + contact + R"(
</mujoco>)";
  };
  struct Case {
    const char* what;
    std::string top_geom, contact;
    double height;
  };
  for (const Case& c : {Case{"default bits", "", "", 0.3}, Case{"contype 0", R"(contype="0" conaffinity="0")", "", 0.1},
                        Case{"excluded", "", R"(<contact><exclude body1="bottom" body2="top"/></contact>)", 0.1}}) {
    const auto path = writeModel("contacts", model(c.top_geom, c.contact));
    const MjcfImport imported = importMjcf(path);
    for (const std::string& u : imported.unmapped) EXPECT_EQ(u.find("contacts between bodies"), std::string::npos) << u;
    Scene s = parseScene(imported.scene_json, path.string());
    const BodyId top = bodyNamed(s, "top"), bottom = bodyNamed(s, "bottom");
    EXPECT_FALSE(s.world->contactAllowed(bodyNamed(s, "swing"), bodyNamed(s, "frame"))) << c.what;
    double lowest = std::numeric_limits<double>::infinity();  // the link's centre below the pivot
    for (int f = 0; f < 90; ++f) {
      stepFrames(s, 1);
      lowest = std::min(lowest, s.world->body(bodyNamed(s, "swing")).x.z() - s.world->body(bodyNamed(s, "frame")).x.z());
    }
    EXPECT_NEAR(s.world->body(top).x.z(), c.height, 2e-3) << c.what;
    EXPECT_NEAR(s.world->body(bottom).x.z(), 0.1, 2e-3) << c.what;
    // The link, level at the start, swings down through its frame's box
    // to hang straight, its centre 0.125 m below the pivot.
    EXPECT_NEAR(lowest, -0.125, 2e-3) << c.what;
  }
}

// models/arm.xml: a two-link arm held level by a tendon over each joint's
// cylinder: at rest T2 = g 1 kg x 0.25 m / 0.04 m = 61.3125 N in the elbow
// tendon, T1 = g (2 kg x 0.25 m + 1 kg x 0.75 m) / 0.05 m = 245.25 N in the
// shoulder tendon, and both links stay level, to 1e-6. As turning wheels
// the massless cylinders weigh 1000 kg/m^3 (listed): the elbow's 0.201 kg
// on its axle adds its weight at 0.5 m to the shoulder's load, and the
// free wheel passes the elbow tendon's tension on unchanged.
TEST(MjcfPhysics, TwoLinkArmOnTendonsOverItsJointCylindersHoldsItsStatics) {
  for (const MjcfWheels wheels : {MjcfWheels::Fixed, MjcfWheels::Turning}) {
    Scene s = importedScene("arm", wheels);
    stepFrames(s, 60);
    const double wheel = wheels == MjcfWheels::Turning ? 1000.0 * std::numbers::pi * 0.04 * 0.04 * 0.04 : 0.0;
    const double t1 = g * (2.0 * 0.25 + 1.0 * 0.75 + wheel * 0.5) / 0.05, t2 = g * 0.25 / 0.04;
    const int shoulder = 0, elbow = 1;
    EXPECT_NEAR(s.cables->tension(shoulder, 0), t1, 1e-6 * t1) << (wheels == MjcfWheels::Turning ? "turning" : "fixed");
    EXPECT_NEAR(s.cables->tension(elbow, 0), t2, 1e-6 * t2) << (wheels == MjcfWheels::Turning ? "turning" : "fixed");
    EXPECT_NEAR(s.world->body(bodyNamed(s, "upper")).x.z(), 0.0, 1e-8);
    EXPECT_NEAR(s.world->body(bodyNamed(s, "forearm")).x.z(), 0.0, 1e-8);
    EXPECT_NEAR(s.world->body(bodyNamed(s, "forearm")).x.x(), 0.75, 1e-8);
  }
}

// models/lever.xml: a 2 kg link and a welded 1 kg tip held level by a
// tendon whose line of action passes r = 0.05 m from the hinge: at rest
// T = g (2 x 0.25 + 1 x 0.5) / r = 196.2 N, and the link stays level.
// Also with a 1000 kg tip (98 kN in the tendon), its welded pulley still
// 1e-6 of the link's 1002 kg.
TEST(MjcfPhysics, LeverOnATendonOverAJointCylinderHoldsItsStatics) {
  std::ifstream in(mjcfModel("lever"));
  const std::string xml((std::istreambuf_iterator<char>(in)), {});
  for (const double tip : {1.0, 1000.0})
    for (const MjcfWheels wheels : {MjcfWheels::Fixed, MjcfWheels::Turning}) {
      std::string heavy = xml;
      const std::string one = "size=\"0.03\" mass=\"1\"";
      heavy.replace(heavy.find(one), one.size(), "size=\"0.03\" mass=\"" + std::to_string(tip) + "\"");
      const auto path = writeModel("lever_tip", heavy);
      MjcfOptions options;
      options.wheels = wheels;
      Scene s = parseScene(importMjcf(path, options).scene_json, path.string());
      const BodyId link = bodyNamed(s, "link");
      stepFrames(s, 60);
      const double T = g * (2.0 * 0.25 + tip * 0.5) / 0.05;
      EXPECT_NEAR(s.cables->tension(0, 0), T, 1e-6 * T) << "tip " << tip << " kg";
      // The link's centre of mass stays at the axle's height.
      const double x = (2.0 * 0.25 + tip * 0.5) / (2.0 + tip);
      EXPECT_NEAR(s.world->body(link).x.z(), 0.0, 1e-8) << "tip " << tip << " kg";
      EXPECT_NEAR(s.world->body(link).x.x(), x, 1e-8);
    }
}

// A hinge's passive spring (stiffness, springref, damping) as a spring
// drive: a 1 kg point-like bob on a massless rod of 0.5 m, about a
// horizontal axis with gravity off, released 0.3 rad from its springref,
// swings as I theta'' = -k theta - c theta' (I = m l^2 + the bob's own).
// Energy only leaves (implicit spring and damper), and the first swing's
// period and decay meet the closed form of the damped oscillator.
TEST(MjcfPhysics, HingeSpringAndDampingSwingAsTheirOscillator) {
  const auto path = writeModel("spring", R"(<mujoco model="spring">
  <option timestep="0.0005" gravity="0 0 0"/>
  <worldbody>
    <body name="arm" euler="0 0 0">
      <joint name="j" type="hinge" axis="0 0 1" stiffness="4" springref="-17.188733853924695" damping="0.05"/>
      <geom type="sphere" size="0.01" pos="0.5 0 0" mass="1"/>
    </body>
  </worldbody>
</mujoco>)");
  MjcfImport model = importMjcf(path);
  Scene s = parseScene(model.scene_json, path.string());
  const double I = 1.0 * 0.25 + 0.4 * 1.0 * 0.01 * 0.01, k = 4.0, c = 0.05;
  const double w0 = std::sqrt(k / I), zeta = c / (2.0 * std::sqrt(k * I)), wd = w0 * std::sqrt(1.0 - zeta * zeta);
  const BodyId arm = bodyNamed(s, "arm");
  // The angle about the axle of the centre (at 0.5 m) from the +x axis,
  // less the springref's -0.3 rad: theta(t) = 0.3 e^(-zeta w0 t) (cos wd t + ...).
  const double period = 2.0 * std::numbers::pi / wd;
  const int frames = static_cast<int>(std::lround(period * s.frame_rate_hz));
  const double t = stepFrames(s, frames);
  const Vec3 x = s.world->body(arm).x;
  const double theta = std::atan2(x.y(), x.x()) + 0.3;
  const double expected = 0.3 * std::exp(-zeta * w0 * t) * (std::cos(wd * t) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t));
  // The implicit spring's own damping (README, spring drives): each
  // substep h keeps (1 + (w0 h)^2)^(-1/2) of the amplitude, 0.6 % over this
  // period; with it the angle is within 2e-4 rad of the closed form (its
  // rate runs slow by O((w0 h)^2) too; the damping unmapped would leave it
  // 0.04 rad off, a stiffness 1 % off 0.002 rad).
  const double h = 1.0 / (s.frame_rate_hz * s.world->settings().substeps);
  const double kept = std::pow(1.0 + w0 * h * w0 * h, -0.5 * std::lround(t / h));
  EXPECT_NEAR(theta, expected * kept, 2e-4) << "t " << t << " period " << period;
}

// MuJoCo's joint damping alone, -d q', is a damper: a 1 kg disc of radius
// 0.2 m (I = 0.02 kg m^2) spinning at 10 rad/s on a hinge with damping 0.01
// keeps 1 / (1 + d h / I) of its speed a substep (implicit; the continuous
// e^(-d t / I) is 1e-5 away after 1 s).
TEST(MjcfPhysics, JointDampingAloneIsAnImplicitDamper) {
  const auto path = writeModel("damper", R"(<mujoco model="damper">
  <option timestep="0.002" gravity="0 0 0"/>
  <worldbody>
    <body name="disc">
      <joint type="hinge" axis="0 0 1" damping="0.01"/>
      <geom type="cylinder" size="0.2 0.05" mass="1"/>
    </body>
  </worldbody>
</mujoco>)");
  MjcfImport model = importMjcf(path);
  EXPECT_TRUE(model.unmapped.empty());
  Scene s = parseScene(model.scene_json, path.string());
  const BodyId disc = bodyNamed(s, "disc");
  s.world->body(disc).omega = Vec3(0, 0, 10.0);
  const double t = stepFrames(s, 60);
  const double h = 1.0 / (s.frame_rate_hz * s.world->settings().substeps), I = 0.5 * 1.0 * 0.2 * 0.2;
  EXPECT_NEAR(s.world->body(disc).omega.z(), 10.0 * std::pow(1.0 + 0.01 * h / I, -std::lround(t / h)), 1e-12);
}

// models/ball.xml: a 2 kg rod, 1 m long, level on a ball joint at one end,
// its other end hung from a tendon straight up: at rest T = m g / 2, and
// the rod stays level (the tendon holds its pitch and its yaw; its twist
// about its own axis is free and nothing turns it).
TEST(MjcfPhysics, BallJointedRodHangsFromItsTendonWithHalfItsWeight) {
  Scene s = importedScene("ball");
  const BodyId rod = bodyNamed(s, "rod");
  stepFrames(s, 60);
  EXPECT_NEAR(s.cables->tension(0, 0), 2.0 * g / 2.0, 1e-7 * g);
  EXPECT_NEAR((s.world->body(rod).x - Vec3(0.5, 0, 0)).norm(), 0.0, 1e-9);
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

// models/actuators.xml with its controls held: a motor is a constant
// torque (omega = gear x ctrl x t / I), a velocity servo an implicit damper
// toward its control, a position servo a spring of kp gear^2 toward
// ctrl / gear (held there), a motor pulling a tendon a constant tension
// (a box lifted at 20 N / 1 kg - g).
TEST(MjcfPhysics, ActuatorsWithControlsHeldAreDrivesAndAWinch) {
  MjcfOptions options;
  options.controls = {{"spin", 0.5}, {"servo", 3.0}, {"hold", 0.4}, {"lift", -20.0}};
  const std::string path = mjcfModel("actuators");
  MjcfImport model = importMjcf(path, options);
  EXPECT_TRUE(model.unmapped.empty()) << model.unmapped.front();
  Scene s = parseScene(model.scene_json, path);
  const double t = stepFrames(s, 12);  // 0.192 s: the box rises 0.19 m of the 0.95 m to its hook
  const double h = 1.0 / (s.frame_rate_hz * s.world->settings().substeps), I = 0.5 * 0.2 * 0.2;
  const long n = std::lround(t / h);
  EXPECT_NEAR(s.world->body(bodyNamed(s, "spin")).omega.z(), 2.0 * 0.5 * t / I, 1e-9);
  EXPECT_NEAR(s.world->body(bodyNamed(s, "servo")).omega.z(), 3.0 - 3.0 * std::pow(1.0 + 0.5 * h / I, -n), 1e-9);
  const BodyId box = bodyNamed(s, "box");
  EXPECT_NEAR(s.world->body(box).v.z(), (20.0 - g) * t, 1e-9);
  EXPECT_NEAR(s.cables->tension(0, 0), 20.0, 1e-9);
  // The position servo swings about 0.2 rad undamped (w = sqrt(32 / I) =
  // 40 rad/s), losing what implicit Euler loses: settle it and read it.
  stepFrames(s, 600);
  const Vec3 side = s.world->body(bodyNamed(s, "hold")).q * Vec3::UnitX();
  EXPECT_NEAR(std::atan2(side.y(), side.x()), 0.2, 1e-6);
}

// Without controls every actuator is at rest: nothing moves but what
// gravity moves (the box falls; its tendon, pulled by nothing, is no cable).
TEST(MjcfPhysics, ActuatorsAtRestDoNothing) {
  Scene s = importedScene("actuators");
  EXPECT_TRUE(s.cables->cables().empty());
  const double t = stepFrames(s, 30);
  for (const char* disc : {"spin", "servo", "hold"}) EXPECT_EQ(s.world->body(bodyNamed(s, disc)).omega.norm(), 0.0) << disc;
  EXPECT_NEAR(s.world->body(bodyNamed(s, "box")).v.z(), -g * t, 1e-9);
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

// models/gimbal.xml: joints chained through light links. The box on two
// slides falls at g exactly and stays on x = 3; the bob swings about x
// only, its roll hinge at rest, and its energy is not created.
TEST(MjcfPhysics, SeveralJointsInOneBodyChainThroughLightLinks) {
  Scene s = importedScene("gimbal");
  EXPECT_TRUE(s.not_imported.empty());
  EXPECT_EQ(s.world->hinges().size(), 2u);
  const BodyId bob = bodyNamed(s, "bob"), box = bodyNamed(s, "box");
  const double e0 = s.world->energy().kinetic + s.world->energy().gravity;
  double most = 0.0;
  for (int f = 0; f < 60; ++f) {
    s.world->step(1.0 / s.frame_rate_hz);
    EXPECT_NEAR(s.world->body(bob).x.x(), 0.0, 1e-9);
    most = std::max(most, s.world->energy().kinetic + s.world->energy().gravity - e0);
  }
  const double t = 60 / s.frame_rate_hz;
  EXPECT_NEAR(s.world->body(box).v.z(), -g * t, 1e-9);
  EXPECT_NEAR(s.world->body(box).x.x(), 3.0, 1e-12);
  EXPECT_LE(most, 1e-9);  // J: a swing of 0.44 J loses, never gains
  // The bob swung: about 0.3 rad of its 1 m rod's angle, back and forth.
  EXPECT_GT(s.world->body(bob).v.norm(), 0.1);
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

// Debian's sample models with floors, as imported (MuJoCo's step, 10
// iterations on a floor): the humanoid falls and lands, the mug rests;
// the energy watch sees no energy created in 1.8 s. At 2 iterations the
// humanoid's landing created 5.3 kJ in a frame, at 5 12 J.
TEST(MjcfPhysics, SampleModelsOnFloorsLandWithoutCreatingEnergy) {
  int run = 0;
  for (const char* sample : {"humanoid/humanoid.xml", "mug/mug.xml"}) {
    const std::string path = std::string("/usr/share/mujoco/model/") + sample;
    if (!std::filesystem::exists(path)) continue;
    Scene s = loadScene(path);
    EXPECT_EQ(s.world->settings().iterations, 10) << sample;
    EnergyWatch watch(s);
    for (int f = 0; f < 120; ++f) {
      s.world->step(1.0 / s.frame_rate_hz);
      const auto created = watch.check(s);
      EXPECT_FALSE(created.has_value()) << sample << ": " << created->created_J << " J at " << created->time_s << " s";
    }
    ++run;
  }
  if (run == 0) GTEST_SKIP() << "libmujoco-samples is not installed";
}

}  // namespace
}  // namespace reeve::test
