// Machines written as MuJoCo models, imported, against their closed forms.
#include <cmath>

#include "mjcf_fixture.h"

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
TEST(MjcfPhysics, AtwoodOverAWrapCylinderMeetsItsClosedForm) {
  const double m1 = 1.0, m2 = 2.0;
  const double wheel = 1000.0 * std::numbers::pi * 0.1 * 0.1 * 0.1;
  struct Case {
    MjcfWheels wheels;
    double a, light_tension;
  };
  const double a_fixed = (m2 - m1) * g / (m1 + m2), a_turning = (m2 - m1) * g / (m1 + m2 + wheel / 2.0);
  for (const Case& c : {Case{MjcfWheels::Fixed, a_fixed, m1 * (g + a_fixed)},
                        Case{MjcfWheels::Turning, a_turning, m1 * (g + a_turning)}}) {
    Scene s = importedScene("atwood", c.wheels);
    const BodyId heavy = bodyNamed(s, "heavy"), light = bodyNamed(s, "light");
    const double t = stepFrames(s, 20);
    const double v = s.world->body(heavy).v.z();
    EXPECT_NEAR(v, -c.a * t, 1e-7 * c.a * t) << (c.wheels == MjcfWheels::Turning ? "turning" : "fixed");
    EXPECT_NEAR(s.world->body(light).v.z(), c.a * t, 1e-7 * c.a * t);
    EXPECT_NEAR(s.cables->tension(0, 0), c.light_tension, 1e-7 * c.light_tension);
    // The boxes hang straight: nothing moves them sideways.
    EXPECT_NEAR(s.world->body(heavy).x.x(), 0.1, 1e-9);
  }
}

// models/lever.xml: a 2 kg link and a welded 1 kg tip held level by a
// tendon whose line of action passes r = 0.05 m from the hinge: at rest
// T = g (2 x 0.25 + 1 x 0.5) / r = 196.2 N, and the link stays level.
TEST(MjcfPhysics, LeverOnATendonOverAJointCylinderHoldsItsStatics) {
  for (const MjcfWheels wheels : {MjcfWheels::Fixed, MjcfWheels::Turning}) {
    Scene s = importedScene("lever", wheels);
    const BodyId link = bodyNamed(s, "link");
    stepFrames(s, 60);
    const double T = g * (2.0 * 0.25 + 1.0 * 0.5) / 0.05;
    EXPECT_NEAR(s.cables->tension(0, 0), T, 1e-6 * T);
    // The link's centre of mass, a third of the way out, stays at the axle's height.
    EXPECT_NEAR(s.world->body(link).x.z(), 0.0, 1e-8);
    EXPECT_NEAR(s.world->body(link).x.x(), (2.0 * 0.25 + 1.0 * 0.5) / 3.0, 1e-8);
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

}  // namespace
}  // namespace reeve::test
