// Running a generated machine (reeve/machines/machines.h) against its
// closed form: the worst errors seen over a run, and the solver budgets
// issue 9 holds every machine to.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "reeve/machines/closed_forms.h"
#include "reeve/machines/machines.h"
#include "reeve/machines/probe.h"

namespace reeve::test {

/// A budget and the relative error it must meet: 0.1 % at 10 substeps of
/// 2 iterations, 1 % at one step of 10 iterations per frame.
struct Bound {
  machines::Budget budget;
  double tolerance;
};
inline const std::vector<Bound> kBounds = {{{10, 2}, 1e-3}, {{1, 10}, 1e-2}};

/// Worst values over a run: relative acceleration and tension errors, the
/// largest axle offset (m) and span stretch (strain).
struct Worst {
  double acceleration = 0.0, tension = 0.0, axle = 0.0, stretch = 0.0;
};

/// Steps `frames` frames of `scene`. Each frame: the axle offsets of
/// `axles`, the stretch of `cable`, and from the second frame on the
/// tension errors, `tensions(j)` against `expected[j]` for every joint j;
/// at the end the acceleration `acceleration()` against `expected_a`.
inline Worst runAgainst(Scene& scene, int cable, const std::vector<HingeId>& axles, int frames,
                        const std::function<double()>& acceleration, double expected_a,
                        const std::vector<double>& expected_tensions) {
  Worst w;
  for (int f = 0; f < frames; ++f) {
    scene.world->step(1.0 / scene.frame_rate_hz);
    for (const HingeId h : axles) w.axle = std::max(w.axle, machines::axleOffset(*scene.world, h));
    w.stretch = std::max(w.stretch, machines::maxStretch(*scene.cables, cable));
    if (f == 0) continue;  // the first frame's tensions start the motion from rest
    for (std::size_t j = 0; j < expected_tensions.size(); ++j)
      w.tension = std::max(w.tension, std::abs(scene.cables->tension(cable, static_cast<int>(j)) /
                                                   expected_tensions[j] - 1.0));
  }
  w.acceleration = std::abs(acceleration() / expected_a - 1.0);
  return w;
}

/// `x` as printf's %g prints it.
inline std::string str(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

/// The measurement, printed like the other tests' "[ measured ]" lines.
inline void print(const std::string& what, const machines::Budget& b, const Worst& w) {
  std::printf("[ measured ] %-40s %2d x %-2d a %.2e  T %.2e  axle %.1e m  stretch %.1e\n", what.c_str(),
              b.substeps, b.iterations, w.acceleration, w.tension, w.axle, w.stretch);
}

}  // namespace reeve::test
