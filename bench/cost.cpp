// Cost of both solvers (issue 9), side by side in one run: the paper's
// Simple scene and the Atwood machine at their scene settings, the
// generated level-3 Hilbert machine (512 hinged wheels, one cable, a motor
// on the first) and zig-zag cables over K = 8 .. 512 wheels at one step of
// 10 iterations per frame. Per row: ms per frame (min / median / max over
// repeats, after a warm-up run), the iterations the solver ran per
// frame (the direct solver stops once every row is met), ns per cable
// joint per iteration run, and the heap allocations inside World::step
// after the first frame (counted by replacing operator new in this
// program). Then a least-squares fit of the zig-zags' cost against cable
// joints x iterations run. Prints only; nothing here passes or fails.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <new>
#include <string>
#include <vector>

#include "reeve/bench/timing.h"
#include "reeve/machines/machines.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace {

using namespace reeve;
using namespace reeve::machines;

const char* solverName(SolverKind s) { return s == SolverKind::Direct ? "direct" : "gauss-seidel"; }

// The shared timing loop (reeve/bench/timing.h), counting the heap
// allocations of the timed runs after each run's first frame.
class CountingRun : public bench::SceneRun {
 public:
  using SceneRun::SceneRun;
  void reset() override {
    SceneRun::reset();
    first_ = true;
  }
  void observe(int) override {
    if (first_) before_ = g_allocations;
    else allocations_ += g_allocations - before_, before_ = g_allocations;
    first_ = false;
  }
  long allocations() const { return allocations_; }

 private:
  bool first_ = true;
  long before_ = 0, allocations_ = 0;
};

struct Timing {
  double min_ms, median_ms, max_ms;
  double iterations;  // run per frame, mean
  long allocations;   // inside World::step after the first frame, all repeats
};

// `frames` frames of a fresh scene from `make`, `repeats` times, after a
// warm-up.
Timing time(const std::function<Scene()>& make, int frames, int repeats) {
  CountingRun run(make);
  bench::TimingOptions options;
  options.repeats = repeats;
  options.observe_every_run = true;
  const bench::FrameTiming t = bench::timeFrames(run, frames, options);
  return {t.min_ms, t.median_ms, t.max_ms, t.iterations_per_frame, run.allocations()};
}

void header() {
  std::printf("%-24s %-12s %6s %9s %9s %9s %9s %7s %9s %7s\n", "machine", "solver", "joints", "sub x it", "min ms",
              "median ms", "max ms", "it run", "ns/j/it", "allocs");
}

void row(const std::string& name, SolverKind solver, int joints, int substeps, int iterations, const Timing& t) {
  const double ns = 1e6 * t.median_ms / (static_cast<double>(joints) * t.iterations);
  std::printf("%-24s %-12s %6d %4d x %-3d %9.4f %9.4f %9.4f %7.1f %9.1f %7ld\n", name.c_str(), solverName(solver),
              joints, substeps, iterations, t.min_ms, t.median_ms, t.max_ms, t.iterations, ns, t.allocations);
}

// The scene file `name` with `solver`.
Scene sceneFile(const std::string& name, SolverKind solver) {
  Scene s = loadScene(std::string(REEVE_SCENES_DIR) + "/" + name + ".json");
  s.world->settings().solver = solver;
  return s;
}

}  // namespace

int main() {
  header();
  const SolverKind solvers[] = {SolverKind::GaussSeidel, SolverKind::Direct};
  for (const char* name : {"simple", "atwood"})
    for (const SolverKind solver : solvers) {
      const Scene probe = sceneFile(name, solver);
      const SolverSettings& set = probe.world->settings();
      row(name, solver, static_cast<int>(probe.cables->cables()[0].joints.size()), set.substeps, set.iterations,
          time([&] { return sceneFile(name, solver); }, 60, 21));
    }
  const Budget paper{1, 10};
  for (const SolverKind solver : solvers) {
    HilbertSpec s;
    s.budget = paper;
    s.budget.solver = solver;
    row("hilbert3 (512 wheels)", solver, 512, 1, 10, time([&] { return std::move(hilbert(s).scene); }, 60, 5));
  }
  // The direct solver with tolerance 0 runs every iteration: the cost of one.
  const auto everyIteration = [](Scene scene) {
    scene.world->settings().tolerance = 0.0;
    return scene;
  };
  {
    HilbertSpec s;
    s.budget = paper;
    row("hilbert3, every iteration", SolverKind::Direct, 512, 1, 10,
        time([&] { return everyIteration(std::move(hilbert(s).scene)); }, 60, 5));
  }
  for (const int variant : {0, 1, 2}) {  // Gauss-Seidel, direct, direct running every iteration
    const SolverKind solver = variant == 0 ? SolverKind::GaussSeidel : SolverKind::Direct;
    std::vector<double> x, y;
    for (int K : {8, 32, 128, 512}) {
      ZigZagSpec s;
      s.wheels = K;
      s.budget = paper;
      s.budget.solver = solver;
      const Timing t = time(
          [&] {
            Scene scene = std::move(zigzag(s).scene);
            return variant == 2 ? everyIteration(std::move(scene)) : std::move(scene);
          },
          60, K <= 32 ? 21 : 5);
      row("zig-zag K = " + std::to_string(K) + (variant == 2 ? ", every it" : ""), solver, K + 1, 1, 10, t);
      x.push_back((K + 1.0) * t.iterations);
      y.push_back(1e6 * t.median_ms);  // ns per frame
    }
    // Least squares y = a + b x.
    const double n = static_cast<double>(x.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      sx += x[i];
      sy += y[i];
      sxx += x[i] * x[i];
      sxy += x[i] * y[i];
    }
    const double b = (n * sxy - sx * sy) / (n * sxx - sx * sx), a = (sy - b * sx) / n;
    double worst = 0.0;
    for (size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(a + b * x[i] - y[i]) / y[i]);
    std::printf("  fit, %s%s zig-zags: ns/frame = %.0f + %.1f x (joints x iterations run); worst residual %.1f %%\n",
                solverName(solver), variant == 2 ? " (every iteration)" : "", a, b, 100.0 * worst);
  }
  return 0;
}
