// Cost of the solver on big cable machines (issue 9): the generated level-3
// Hilbert machine (512 hinged wheels, one cable, a motor on the first), the
// zig-zag cable over K = 8 .. 512 wheels (ns per cable joint per iteration
// and a linear fit of cost against joints x iterations), the K = 32 zig-zag,
// and heap allocations inside World::step after the first frame (counted
// by replacing operator new in this program). Prints only.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <new>
#include <string>
#include <vector>

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

struct Timing {
  double min_ms, median_ms, max_ms;
  long allocations;  // inside World::step after the first frame, all repeats
};

// Builds a fresh scene with `make` for each of `repeats` runs, steps one
// frame as a warm-up, then times `frames` frames.
Timing time(const std::function<Scene()>& make, int frames, int repeats) {
  std::vector<double> ms;
  long allocations = 0;
  for (int r = 0; r < repeats; ++r) {
    Scene scene = make();
    const double dt = 1.0 / scene.frame_rate_hz;
    scene.world->step(dt);
    const long before = g_allocations;
    const auto t0 = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) scene.world->step(dt);
    ms.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / frames);
    allocations += g_allocations - before;
  }
  std::sort(ms.begin(), ms.end());
  return {ms.front(), ms[ms.size() / 2], ms.back(), allocations};
}

void row(const char* name, int joints, const Budget& b, const Timing& t) {
  const double ns = 1e6 * t.median_ms / (static_cast<double>(joints) * b.substeps * b.iterations);
  std::printf("%-30s %7d %4d x %-3d %9.4f %9.4f %9.4f %10.1f %7ld\n", name, joints, b.substeps, b.iterations,
              t.min_ms, t.median_ms, t.max_ms, ns, t.allocations);
}

}  // namespace

int main() {
  std::printf("%-30s %7s %9s %9s %9s %9s %10s %7s\n", "machine", "joints", "sub x it", "min ms", "median ms",
              "max ms", "ns/j/it", "allocs");
  const Budget paper{1, 10};
  {
    HilbertSpec s;
    s.budget = paper;
    const Timing t = time([&] { return std::move(hilbert(s).scene); }, 60, 5);
    row("hilbert3 (512 wheels)", 512, paper, t);
  }
  // Cost against joints x iterations over chains of 8 .. 512 wheels.
  std::vector<double> x, y;
  for (int K : {8, 32, 128, 512}) {
    ZigZagSpec s;
    s.wheels = K;
    s.budget = paper;
    const Timing t = time([&] { return std::move(zigzag(s).scene); }, 60, K <= 32 ? 21 : 5);
    char name[40];
    std::snprintf(name, sizeof name, "zig-zag K = %d", K);
    row(name, K + 1, paper, t);
    x.push_back((K + 1.0) * paper.iterations);
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
  std::printf("fit over the zig-zags: ns/frame = %.0f + %.1f x (joints x iterations); worst residual %.1f %%\n", a, b,
              100.0 * worst);
  return 0;
}
