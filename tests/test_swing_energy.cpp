// Numerical damping (issue 29): a pendulum's swing energy kept over 100
// periods. XPBD projects each row along its gradient at the end of the
// substep, which is first order and loses (omega h)^2 of the energy a
// substep (a hanging pendulum; one held up by a spring gains instead);
// the direct solver projects along the gradient at the substep's start
// (SHAKE), which keeps it to a bounded O(h^2) oscillation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "atwood_machine.h"
#include "reeve/scene/scene.h"

namespace reeve::test_swing_energy {
namespace {

constexpr double kG = 9.81;

// A 1 kg bob 1 m below its pivot, released at `angle` rad: held by a cable
// (`holder` "cable"), a hinge or a ball joint.
std::string pendulum(const std::string& holder, double angle, int substeps, int iterations, const char* projection,
                     double mass_kg = 1.0) {
  const double x = std::sin(angle), y = -std::cos(angle);
  std::string s = R"({"name": "pendulum", "duration_s": 1,
    "solver": {"frame_rate_hz": 60, "substeps": )" +
                  std::to_string(substeps) + R"(, "iterations": )" + std::to_string(iterations) +
                  R"(, "projection": ")" + projection + R"("},
    "bodies": [{"name": "pin", "shape": {"type": "sphere", "radius_m": 0.01}, "static": true, "position_m": [0, 0, 0]},
               {"name": "bob", "shape": {"type": "sphere", "radius_m": 0.05}, "mass_kg": )" +
                  std::to_string(mass_kg) + R"(,
                "position_m": [)" +
                  std::to_string(x) + ", " + std::to_string(y) + ", 0]}]";
  if (holder == "cable")
    s += R"(, "cables": [{"name": "rope", "links": [
      {"body": "pin", "type": "attachment", "point_m": [0, 0, 0]},
      {"body": "bob", "type": "attachment", "point_m": [0, 0, 0]}]}]})";
  else if (holder == "hinge")
    s += R"(, "hinges": [{"body": "bob", "anchor_m": [0, 0, 0], "axis": [0, 0, 1]}]})";
  else
    s += R"(, "joints": [{"type": "spherical", "body": "bob", "anchor_m": [0, 0, 0]}]})";
  return s;
}

struct Swing {
  double oscillation = 0.0;  // largest |E - E_0| / E_swing: the stored velocity is a half step's, O(h omega)
  double amplitude = 0.0;    // the swing energy at the last turning point less at the first, / E_swing
};

Swing swing(const std::string& holder, double angle, int substeps, int iterations, const char* projection,
            int periods, double mass_kg = 1.0) {
  Scene scene = parseScene(pendulum(holder, angle, substeps, iterations, projection, mass_kg), "<pendulum>");
  World& world = *scene.world;
  const BodyId bob = 1;
  const auto total = [&] {
    const WorldEnergy e = world.energy();
    return e.kinetic + e.gravity + e.elastic;
  };
  const double bottom = -mass_kg * kG;  // -m g . x at the lowest point, 1 m below the pin
  const double e0 = total(), swing0 = e0 - bottom;
  const double period = 2.0 * 3.14159265358979 * std::sqrt(1.0 / kG);
  const int frames = static_cast<int>(std::lround(periods * period * 60.0));
  // Heights, to find the turning points (a parabola through the highest
  // frame and its neighbours).
  std::vector<double> y(1, world.body(bob).x.y());
  Swing out;
  for (int f = 0; f < frames; ++f) {
    world.step(1.0 / 60.0);
    y.push_back(world.body(bob).x.y());
    out.oscillation = std::max(out.oscillation, std::abs(total() - e0) / swing0);
  }
  std::vector<double> peaks;
  for (int k = 1; k + 1 < static_cast<int>(y.size()); ++k)
    if (y[k] > y[k - 1] && y[k] > y[k + 1]) {
      const double a = 0.5 * (y[k - 1] + y[k + 1]) - y[k], b = 0.5 * (y[k + 1] - y[k - 1]);
      peaks.push_back(y[k] - b * b / (4.0 * a));
    }
  if (peaks.size() >= 2 && peaks.front() > -1.0) out.amplitude = (peaks.back() - peaks.front()) / (peaks.front() + 1.0);
  return out;
}

TEST(SwingEnergy, AtTheStartProjectionAPendulumKeepsItsSwingEnergyFor100Periods) {
  // A 1 m pendulum released at 0.1 rad, held by a cable, a hinge and a
  // ball joint. Its swing energy (the height of each turning point) after
  // 100 periods: measured within 6e-7 of the start's at 10 x 2 and 1 x 10
  // (3e-7 at 32 x 32); held to 1e-5, a hundredth of what the issue asks
  // (1e-3 and 1e-2), where the end projection loses 96 to 100 %. The
  // energy read each frame (the ledger pairs the stored half-step
  // velocity with the height half a step back under the start
  // projection) ripples by (h omega)^2 / 2 of it: measured 1.37e-5 at 10 x
  // 2 and 1.37e-3 at 1 x 10, bounded, not drift; held to (h omega)^2. (The
  // end pairing rippled by h omega / 2: 2.6e-3 at 10 x 2.)
  const double omega = std::sqrt(kG / 1.0);
  for (const char* holder : {"cable", "hinge", "ball"})
    for (const auto& [n, it] : {std::pair{10, 2}, {1, 10}}) {
      const Swing s = swing(holder, 0.1, n, it, "start", 100);
      const double h_omega = omega / (60.0 * n);
      std::printf("[ measured ] start, %-5s %2d x %2d: swing energy after 100 periods %+.2e, ripple %.2e ((h omega)^2 "
                  "%.2e)\n",
                  holder, n, it, s.amplitude, s.oscillation, h_omega * h_omega);
      EXPECT_LT(std::abs(s.amplitude), 1e-5) << holder << " " << n << " x " << it;
      EXPECT_LT(s.oscillation, h_omega * h_omega) << holder << " " << n << " x " << it;
    }
}

TEST(SwingEnergy, AtTheEndProjectionXpbdLosesTheSwingAndNeverGainsIt) {
  // XPBD as written (the default, and Gauss-Seidel always): each substep
  // loses about (omega h)^2 of the energy. Measured after 100 periods:
  // -96 % at 10 x 2, -64 % at 32 x 2 (-28 % at 100 x 2), all of it at
  // 1 x 10; more substeps lose less.
  double previous = -1.0;
  for (const int n : {10, 32}) {
    const Swing s = swing("hinge", 0.1, n, 2, "end", 100);
    std::printf("[ measured ] end, hinge %3d x 2: swing energy after 100 periods %+.2e\n", n, s.amplitude);
    EXPECT_LT(s.amplitude, 0.0);
    EXPECT_GT(s.amplitude, previous);
    previous = s.amplitude;
  }
}

TEST(SwingEnergy, AnInvertedPendulumOnATrapezoidalSpringGainsAtTheEndAndKeepsItsEnergyAtTheStart) {
  // "Never gains" above is the hanging pendulum's. The end projection
  // takes each row's force along its gradient at the substep's end: on
  // the curvature of the rows, implicit Euler, which loses energy where
  // the curvature holds the body toward its rest (hanging) and gains
  // where it pushes it away. A 1 kg bob 1 m above its hinge, held up by a
  // torsional spring of twice m g L (trapezoidal: it keeps its own energy
  // and damps nothing), released 0.1 rad over: stable, omega = sqrt(g / L)
  // (a 2 s period). Its energy over 50 periods, of the swing's 1/2 (k - m
  // g L) 0.1^2. The end takes the hinge's curvature, a negative stiffness
  // mu = m g L, at x_+ where the trapezoidal rule would take (x_+ + 2 x_0
  // + x_-) / 4: a force mu h v more, working mu h^2 v^2 a substep, so the
  // swing energy E grows by mu h^2 / I of itself a substep (<v^2> = E / I):
  // over N substeps by expm1(N mu h^2 / I), 4.12 at 10 x 2 and 0.666 at 32
  // x 2; Gauss-Seidel, which projects at the end too, the same. The start
  // keeps it; so the bow held at full draw (DESIGN.md, "The held bow").
  // Hanging on a spring of m g L (swing 1/2 (k + m g L) 0.1^2), the end
  // loses it.
  const auto run = [](bool inverted, int substeps, const char* projection, const char* method = "direct",
                      double mass = 1.0) {
    const auto exact = [](double v) {  // every digit: a stiffness of 2e-5 N m/rad too
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", v);
      return std::string(text);
    };
    const double L = 1.0, k = (inverted ? 2.0 : 1.0) * mass * kG * L, tilt = 0.1;
    const double y = inverted ? L : -L;
    const std::string json = R"({"name": "inverted", "duration_s": 100,
      "solver": {"substeps": )" + std::to_string(substeps) + R"(, "iterations": 2, "method": ")" + method +
                             R"(", "projection": ")" + projection + R"("},
      "bodies": [{"name": "pin", "shape": {"type": "sphere", "radius_m": 0.01}, "static": true, "position_m": [0, 0, 0]},
                 {"name": "bob", "shape": {"type": "sphere", "radius_m": 0.05}, "mass_kg": )" +
                             exact(mass) + R"(,
                  "position_m": [)" + std::to_string(-y * std::sin(tilt)) + ", " +
                             std::to_string(y * std::cos(tilt)) + R"(, 0],
                  "orientation": {"axis": [0, 0, 1], "angle_rad": )" + std::to_string(tilt) + R"(}}],
      "hinges": [{"body": "bob", "other": "pin", "anchor_m": [0, 0, 0], "axis": [0, 0, 1],
                  "drive": {"mode": "angle", "target_rad": 0, "stiffness_N_m_per_rad": )" +
                             exact(k) + R"(, "integration": "trapezoidal"}}]})";
    Scene scene = parseScene(json, "<inverted pendulum>");
    World& world = *scene.world;
    const auto total = [&] {
      const WorldEnergy e = world.energy();
      return e.kinetic + e.gravity + e.elastic;
    };
    const double e0 = total(), swing = 0.5 * (inverted ? k - mass * kG * L : k + mass * kG * L) * tilt * tilt;
    double most = 0.0;  // the largest |change| on the way
    for (int f = 0; f < 6000; ++f) {  // 100 s, 50 periods
      world.step(1.0 / 60.0);
      most = std::max(most, std::abs(total() - e0) / swing);
    }
    return std::pair{(total() - e0) / swing, most};
  };
  const double end10 = run(true, 10, "end").first, end32 = run(true, 32, "end").first;
  const double start10 = run(true, 10, "start").second, hanging10 = run(false, 10, "end").first;
  const double gauss_seidel10 = run(true, 10, "end", "gauss-seidel").first;  // the end projection too
  std::printf("[ measured ] inverted on a trapezoidal spring, 50 periods: end %+.3e (10 x 2), %+.3e (32 x 2), "
              "Gauss-Seidel %+.3e (10 x 2); start within %.3e (10 x 2); hanging, end %+.3e (10 x 2)\n",
              end10, end32, gauss_seidel10, start10, hanging10);
  // The estimate to 15 %: it is first order in omega h, and as the swing
  // grows (to 0.22 rad at 10 x 2) gravity's stiffness m g L cos(theta)
  // falls (measured: 0.92 and 0.95 of it).
  const double I = 1.0 + 0.4 * 0.05 * 0.05;  // the bob about the hinge, kg m^2
  for (const auto& [substeps, gain] : {std::pair{10, end10}, std::pair{32, end32}, std::pair{10, gauss_seidel10}}) {
    const double h = 1.0 / (60.0 * substeps), predicted = std::expm1(6000.0 * substeps * kG * h * h / I);
    EXPECT_NEAR(gain, predicted, 0.15 * predicted) << substeps;
  }
  // The gain is mu h^2 / I a substep, mu = m g L and I = m (L^2 + 0.4
  // r^2): the bob's mass cancels. A bob of 1e-6 or 1e6 kg on a spring
  // scaled with it gains what the 1 kg one does, under both solvers.
  for (const double mass : {1e-6, 1e6}) {
    EXPECT_NEAR(run(true, 10, "end", "direct", mass).first, end10, 1e-6 * end10) << mass;
    EXPECT_NEAR(run(true, 10, "end", "gauss-seidel", mass).first, gauss_seidel10, 1e-6 * gauss_seidel10) << mass;
  }
  // The start's swing beats by 1.3 % over about 300 s and comes back to
  // 5e-6 (measured, not derived): bounded, against the end's 378 %.
  EXPECT_LT(start10, 0.02);
  EXPECT_LT(hanging10, -0.1);
}

TEST(SwingEnergy, TheStartProjectionKeepsTheAtwoodMachinesExactAtEveryWheelMass) {
  // Straight spans over a rotor: the start's gradients are the end's. Under
  // a constant acceleration a = (m2 - m1) g / (m1 + m2 + I / r^2) each
  // substep adds a h to the velocity, so after t it is a t exactly, and
  // the tensions are m1 (g + a) and m2 (g - a); wheels from 1e-6 to 1e6 kg,
  // one substep and ten. Speeds to 1e-9, or to the rounding of positions
  // near 3 m read over a substep (1e-15 x 3 m / h < 1e-12 m/s) where the
  // 1e6 kg wheel leaves a at 1e-5 m/s^2. Tensions to 1e-9 of m g, plus the
  // solve's rounding, which a light wheel magnifies by its system's
  // condition number, about m / M (1e-6 kg: 1e-8 N measured either sign as
  // the tangent arithmetic's last digits change).
  for (const double M : {1e-6, 2.0, 1e6})
    for (const auto& [n, it] : {std::pair{1, 1}, {10, 2}}) {
      Atwood m(1.0, 2.0, n, it, M, Projection::Start);
      for (int f = 0; f < 30; ++f) m.world.step(1.0 / 60.0);
      const double a = m.acceleration(), t = m.world.time(), speed = 1e-9 * a * t + 1e-12;
      EXPECT_NEAR(-m.world.body(m.box2).v.y(), a * t, speed) << M << " kg, " << n << " x " << it;
      EXPECT_NEAR(-m.world.body(m.wheel).omega.z() * m.r, a * t, speed) << M << " kg, " << n << " x " << it;
      const double tension = 1e-9 + 1e-15 * m.m2 / M;  // of m g: 1e-9, and a few epsilon x m / M
      EXPECT_NEAR(m.cables.tension(m.cable, 0), m.m1 * (m.g + a), tension * m.m1 * m.g) << M << " kg";
      EXPECT_NEAR(m.cables.tension(m.cable, 1), m.m2 * (m.g - a), tension * m.m2 * m.g) << M << " kg";
    }
}

TEST(SwingEnergy, TheStartProjectionIsTheSameAtEveryBobMassAndIterationCount) {
  // Mass scaling: bobs of 1e-6 to 1e6 kg swing alike (measured: the same
  // digits). More iterations only converge the chord iteration: the swing
  // energy after 20 periods is within 2.5e-7 at one iteration and 3.7e-7
  // from two, never worse than that as iterations are added.
  for (const int it : {1, 2, 16}) {
    const Swing reference = swing("hinge", 0.1, 10, it, "start", 20, 1.0);
    EXPECT_LT(std::abs(reference.amplitude), 1e-6) << it << " iterations";
    for (const double m : {1e-6, 1e6}) {
      const Swing s = swing("hinge", 0.1, 10, it, "start", 20, m);
      EXPECT_NEAR(s.amplitude, reference.amplitude, 1e-9) << m << " kg, " << it << " iterations";
    }
  }
}

TEST(SwingEnergy, ADoublePendulumKeepsItsEnergyAtTheStartProjection) {
  // Two 1 kg, 1 m rods hinged end to end, released horizontal: chaotic
  // within a second. Its energy over 10 s, against the 2 m g L = 19.6 J
  // that the fall from horizontal to hanging releases. Measured: end
  // -33 % at 10 x 2, -88 % at 1 x 10; start within 3.7e-4 at 10 x 2
  // (-5.4e-5 after 10 s; 2.4e-3 with the end pairing of velocity and
  // height) and -44 % at 1 x 10, where the lower rod whips its rows'
  // gradients past the 0.2 turn limit (direct_solver.cpp:
  // kStartTurnLimit) and they keep the end's.
  for (const char* projection : {"end", "start"})
    for (const auto& [n, it] : {std::pair{10, 2}, {1, 10}}) {
      const std::string json = R"({"name": "double", "duration_s": 10,
        "solver": {"substeps": )" + std::to_string(n) + R"(, "iterations": )" + std::to_string(it) +
                               R"(, "projection": ")" + projection + R"("},
        "bodies": [{"name": "upper", "shape": {"type": "box", "half_extents_m": [0.5, 0.02, 0.02]}, "mass_kg": 1,
                    "position_m": [0.5, 0, 0]},
                   {"name": "lower", "shape": {"type": "box", "half_extents_m": [0.5, 0.02, 0.02]}, "mass_kg": 1,
                    "position_m": [1.5, 0, 0]}],
        "hinges": [{"body": "upper", "anchor_m": [0, 0, 0], "axis": [0, 0, 1]},
                   {"body": "lower", "other": "upper", "anchor_m": [1, 0, 0], "axis": [0, 0, 1]}]})";
      Scene scene = parseScene(json, "<double>");
      World& world = *scene.world;
      const auto total = [&] {
        const WorldEnergy e = world.energy();
        return e.kinetic + e.gravity + e.elastic;
      };
      const double e0 = total(), scale = 2.0 * kG;
      double worst = 0.0;
      for (int f = 0; f < 600; ++f) {
        world.step(1.0 / 60.0);
        worst = std::max(worst, std::abs(total() - e0) / scale);
      }
      const double end = (total() - e0) / scale;
      std::printf("[ measured ] double pendulum, %s, %2d x %2d: energy after 10 s %+.2e of 2 m g L, largest change %.2e\n",
                  projection, n, it, end, worst);
      if (std::string(projection) == "end") {
        EXPECT_LT(end, -0.1) << n << " x " << it;  // XPBD's loss
      } else if (n == 10) {
        EXPECT_LT(worst, 1e-3);
      }
    }
}

}  // namespace
}  // namespace reeve::test_swing_energy
