// Closed forms of the generated machines (machines.h), from Newton's laws
// and virtual work; the tests and benchmarks measure the simulation
// against these. Wheels are solid cylinders, so a wheel of mass M and
// radius r adds I / r^2 = M / 2 to the mass the cable drives. g along -y.
#pragma once

#include <vector>

namespace reeve::machines {

/// Atwood machine, boxes m1 < m2 over a wheel of mass M on a fixed axle:
/// (m1 + m2 + M/2) a = (m2 - m1) g; the heavy box falls with a (m/s^2).
/// The light side pulls T1 = m1 (g + a), the heavy side T2 = m2 (g - a).
struct AtwoodMotion {
  double acceleration, tension_light, tension_heavy;
};
inline AtwoodMotion atwoodMotion(double m1, double m2, double wheel_kg, double g) {
  const double a = (m2 - m1) * g / (m1 + m2 + 0.5 * wheel_kg);
  return {a, m1 * (g + a), m2 * (g - a)};
}

/// The zig-zag over K wheels of mass M each: every wheel turns at v / r,
/// so (m1 + m2 + K M/2) a = (m2 - m1) g, and each wheel needs
/// (T_out - T_in) r = I a / r, i.e. T rises by M a / 2 per wheel from
/// T_0 = m1 (g + a) to T_K = m2 (g - a). Returns a and T_0 .. T_K (N).
struct ChainMotion {
  double acceleration;
  std::vector<double> tensions;
};
inline ChainMotion zigzagMotion(int K, double m1, double m2, double wheel_kg, double g) {
  ChainMotion motion;
  motion.acceleration = (m2 - m1) * g / (m1 + m2 + 0.5 * K * wheel_kg);
  for (int k = 0; k <= K; ++k) motion.tensions.push_back(m1 * (g + motion.acceleration) + 0.5 * k * wheel_kg * motion.acceleration);
  return motion;
}

/// Block and tackle (machines.h): when the lower block rises by y the
/// counterweight falls by 4 y, and the cable runs over lower sheave A,
/// upper A, lower B and upper B at 1, 2, 3 and 4 times dy/dt relative to
/// each (the tie end is still; each moving sheave doubles the speed of the
/// cable it passes on plus its own). Virtual work with kinetic energy
/// 1/2 y'^2 (m_L + 16 m_c + (1 + 4 + 9 + 16) I / r^2) and potential
/// (m_L - 4 m_c) g y, m_L the lower block with its two sheaves:
///   y'' = (4 m_c - m_L) g / (m_L + 16 m_c + 15 M_s).
/// Strand tensions from the counterweight up: T_4 = m_c (g - 4 y''), and
/// across the sheave with speed factor n the tension falls by n I y'' / r^2
/// = n M_s y'' / 2 towards the tie. Returns y'' and T_0 (tie) .. T_4.
inline ChainMotion blockAndTackleMotion(double block_kg, double sheave_kg, double counterweight_kg, double g) {
  const double m_L = block_kg + 2.0 * sheave_kg;
  ChainMotion motion;
  const double a = (4.0 * counterweight_kg - m_L) * g / (m_L + 16.0 * counterweight_kg + 15.0 * sheave_kg);
  motion.acceleration = a;
  motion.tensions.assign(5, 0.0);
  motion.tensions[4] = counterweight_kg * (g - 4.0 * a);
  for (int n = 4; n >= 1; --n) motion.tensions[n - 1] = motion.tensions[n] - n * 0.5 * sheave_kg * a;
  return motion;
}

}  // namespace reeve::machines
