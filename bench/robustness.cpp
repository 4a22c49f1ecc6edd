// Accuracy and robustness of both solvers where Gauss-Seidel struggles
// (issue 9): wheels from 1e-6 to 1e6 times the load, loads of 1e4 and 1e5 N,
// sheaves on a moving block, a wheel on a swinging arm, long zig-zag
// cables, a fast wheel, a snap-taut jerk. For each case, budget and solver
// it prints the errors against the closed forms (machines/closed_forms.h),
// the largest axle offset and span stretch and the smallest rest length
// over the run. Prints only; nothing here passes or fails.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "reeve/machines/closed_forms.h"
#include "reeve/machines/machines.h"
#include "reeve/machines/probe.h"

namespace {

using namespace reeve;
using namespace reeve::machines;

struct Result {
  double acc_err = 0.0, tension_err = 0.0, axle = 0.0, stretch = 0.0, min_rest = 1e300;
  bool finite = true;
};

// Relative error, %.
double pct(double got, double want) { return 100.0 * (got - want) / std::abs(want); }

// Steps `frames` frames, tracking the axle offsets, stretch and rest
// lengths every frame and the tension error (`tension_err()`, %) from the
// second frame on; `acc_err()` reads the acceleration error at the end.
Result run(Scene& scene, int cable, const std::vector<HingeId>& axles, int frames,
           const std::function<double()>& acc_err, const std::function<double()>& tension_err) {
  Result r;
  for (int f = 0; f < frames; ++f) {
    scene.world->step(1.0 / scene.frame_rate_hz);
    if (scene.world->firstNonFiniteBody()) {
      r.finite = false;
      return r;
    }
    for (HingeId h : axles) r.axle = std::max(r.axle, axleOffset(*scene.world, h));
    r.stretch = std::max(r.stretch, maxStretch(*scene.cables, cable));
    r.min_rest = std::min(r.min_rest, minRestLength(*scene.cables, cable));
    if (f > 0) r.tension_err = std::max(r.tension_err, std::abs(tension_err()));
  }
  r.acc_err = acc_err();
  return r;
}

const char* solverName(SolverKind s) { return s == SolverKind::Direct ? "direct" : "gauss-seidel"; }

void print(const std::string& name, const Budget& b, const Result& r) {
  std::printf("%-42s %-12s %3d x %-3d ", name.c_str(), solverName(b.solver), b.substeps, b.iterations);
  if (!r.finite) {
    std::printf("diverged (non-finite)\n");
    return;
  }
  std::printf("%+10.4f %10.4f %10.2e %10.2e %10.3f\n", r.acc_err, r.tension_err, r.axle, r.stretch, r.min_rest);
}

Result atwoodCase(AtwoodSpec spec, int frames) {
  Atwood m = atwood(spec);
  const AtwoodMotion want = atwoodMotion(spec.light_kg, spec.heavy_kg, spec.wheel_kg, spec.gravity);
  World& w = *m.scene.world;
  return run(
      m.scene, m.cable, {m.axle}, frames, [&] { return pct(-w.body(m.heavy).v.y() / w.time(), want.acceleration); },
      [&] {
        return std::max(std::abs(pct(m.scene.cables->tension(m.cable, 0), want.tension_light)),
                        std::abs(pct(m.scene.cables->tension(m.cable, 1), want.tension_heavy)));
      });
}

Result zigzagCase(ZigZagSpec spec, int frames) {
  ZigZag m = zigzag(spec);
  const ChainMotion want = zigzagMotion(spec.wheels, spec.light_kg, spec.heavy_kg, spec.wheel_kg, spec.gravity);
  World& w = *m.scene.world;
  return run(
      m.scene, m.cable, m.axles, frames, [&] { return pct(-w.body(m.heavy).v.y() / w.time(), want.acceleration); },
      [&] {
        double worst = 0.0;
        for (int j = 0; j <= spec.wheels; ++j)
          worst = std::max(worst, std::abs(pct(m.scene.cables->tension(m.cable, j), want.tensions[j])));
        return worst;
      });
}

// Out of balance: the acceleration error (%); in balance (the closed form
// is 0): the lower block's drift (mm) in its place.
Result tackleCase(BlockAndTackleSpec spec, int frames) {
  BlockAndTackle m = blockAndTackle(spec);
  const ChainMotion want = blockAndTackleMotion(spec.block_kg, spec.sheave_kg, spec.counterweight_kg, spec.gravity);
  World& w = *m.scene.world;
  const double y0 = w.body(m.lower_block).x.y();
  return run(
      m.scene, m.cable, {m.lower_axles[0], m.lower_axles[1]}, frames,
      [&] {
        if (want.acceleration == 0.0) return 1e3 * (w.body(m.lower_block).x.y() - y0);
        return pct(w.body(m.lower_block).v.y() / w.time(), want.acceleration);
      },
      [&] {
        double worst = 0.0;
        for (int j = 0; j <= 4; ++j)
          worst = std::max(worst, std::abs(pct(m.scene.cables->tension(m.cable, j), want.tensions[j])));
        return worst;
      });
}

}  // namespace

int main() {
  std::printf("%-42s %-12s %9s %10s %10s %10s %10s %10s\n", "case", "solver", "sub x it", "acc err %",
              "max T err%", "axle m", "stretch", "min rest m");
  for (const SolverKind solver : {SolverKind::GaussSeidel, SolverKind::Direct}) {
    for (Budget b : {Budget{10, 2}, Budget{1, 10}}) {
      b.solver = solver;
      for (double ratio : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
        AtwoodSpec s;
        s.wheel_kg = ratio * s.light_kg;
        s.budget = b;
        char name[64];
        std::snprintf(name, sizeof name, "1 Atwood, wheel %.0e x light", ratio);
        print(name, b, atwoodCase(s, 30));
      }
      for (double ratio : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
        AtwoodSpec s;
        s.wheel_kg = ratio * s.light_kg;
        s.arm_kg = 1.0;
        s.budget = b;
        char name[64];
        std::snprintf(name, sizeof name, "2 Atwood on an arm, wheel %.0e x light", ratio);
        print(name, b, atwoodCase(s, 30));
      }
      for (double cw : {1.002, 1.5}) {
        BlockAndTackleSpec s;
        s.counterweight_kg = cw;
        s.budget = b;
        char name[64];
        std::snprintf(name, sizeof name, "2 tackle, sheaves 1e-3, cw %.3f%s", cw, cw == 1.002 ? " (drift mm)" : "");
        print(name, b, tackleCase(s, 60));
      }
      for (double load_N : {1e4, 1e5}) {
        AtwoodSpec s;
        s.light_kg = load_N / s.gravity;
        s.heavy_kg = 2.0 * s.light_kg;
        s.wheel_kg = 1.0;
        s.budget = b;
        char name[64];
        std::snprintf(name, sizeof name, "3 Atwood, loads %.0e N, 1 kg wheel", load_N);
        print(name, b, atwoodCase(s, 30));
      }
      for (double wheel_kg : {1e-3, 1.0})
        for (int K : {2, 8, 32, 128}) {
          ZigZagSpec s;
          s.wheels = K;
          s.wheel_kg = wheel_kg;
          s.budget = b;
          char name[64];
          std::snprintf(name, sizeof name, "4 zig-zag K = %d, wheels %g kg", K, wheel_kg);
          print(name, b, zigzagCase(s, 30));
        }
    }
    AtwoodSpec s;  // 1:100 on a 1 mm wheel: 20 turns per substep at the end
    s.radius_m = 0.001;
    s.heavy_kg = 100.0;
    s.wheel_kg = 1.0;
    s.budget = {1, 1, solver};
    print("5 Atwood 1:100, 1 mm wheel", s.budget, atwoodCase(s, 36));
  }
  std::printf("\n6 snap-taut: 2 kg box at 10 m/s meets 0.5 m of slack over a 1 kg wheel (no gravity)\n");
  std::printf("%-12s %-10s %12s %12s %14s\n", "solver", "sub x it", "v heavy", "v expected", "peak stretch");
  for (const SolverKind solver : {SolverKind::GaussSeidel, SolverKind::Direct})
    for (Budget b : {Budget{10, 1}, Budget{10, 2}, Budget{10, 10}, Budget{1, 10}}) {
      AtwoodSpec s;
      s.gravity = 0.0;
      s.slack_m = 0.5;
      s.heavy_speed_m_per_s = 10.0;
      s.wheel_kg = 1.0;
      b.solver = solver;
      s.budget = {1, b.iterations, solver};  // one substep per step(): the peak after every substep
      Atwood m = atwood(s);
      double peak = 0.0;
      for (int k = 0; k < 30 * b.substeps; ++k) {
        m.scene.world->step(1.0 / (60.0 * b.substeps));
        peak = std::max(peak, maxStretch(*m.scene.cables, m.cable));
      }
      const double v = s.heavy_kg * 10.0 / (s.light_kg + s.heavy_kg + 0.5 * s.wheel_kg);
      std::printf("%-12s %3d x %-4d %12.4f %12.4f %14.3e\n", solverName(solver), b.substeps, b.iterations,
                  -m.scene.world->body(m.heavy).v.y(), v, peak);
    }
  return 0;
}
