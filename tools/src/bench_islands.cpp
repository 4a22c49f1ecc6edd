#include "bench_islands.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "bench_format.h"
#include "bench_threads.h"
#include "reeve/engine/thread_pool.h"
#include "reeve/machines/machines.h"

namespace reeve {
namespace {

// K Atwood machines (machines::islands), 1 kg against 1 to 2.5 kg: each
// moves, and no two alike.
machines::StaticMachine atwoods(const IslandsBenchOptions& o, SolverKind solver, int threads) {
  machines::ScalingSpec spec;
  spec.count = o.machines;
  spec.budget = {o.substeps, o.iterations, solver};
  machines::StaticMachine m = machines::islands(spec);
  World& world = *m.scene.world;
  for (int k = 0; k < o.machines; ++k)
    world.setMass(*world.findBody("right" + std::to_string(k)), 1.0 + 0.5 * (k % 4));
  world.setThreads(threads);
  return m;
}

struct Measured {
  double ms = 0.0;                  // median ms a frame
  std::vector<unsigned char> bits;  // the bodies' state after the last run
};

// One timed run of `frames` frames (after one untimed, which builds the
// islands and solvers).
Measured measure(const IslandsBenchOptions& o, SolverKind solver, int threads) {
  Measured out;
  machines::StaticMachine m = atwoods(o, solver, threads);
  World& world = *m.scene.world;
  world.step(1.0 / 60.0);
  const auto start = std::chrono::steady_clock::now();
  for (int f = 0; f < o.frames; ++f) world.step(1.0 / 60.0);
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / o.frames;
  for (BodyId id = 0; id < world.bodyCount(); ++id) {
    const BodyState& b = world.body(id);
    for (const double v : {b.x.x(), b.x.y(), b.x.z(), b.q.w(), b.q.x(), b.q.y(), b.q.z(), b.v.x(), b.v.y(), b.v.z(),
                           b.omega.x(), b.omega.y(), b.omega.z()}) {
      unsigned char bytes[sizeof v];
      std::memcpy(bytes, &v, sizeof v);
      out.bits.insert(out.bits.end(), bytes, bytes + sizeof v);
    }
  }
  return out;
}

}  // namespace

int benchIslands(const IslandsBenchOptions& o) {
  if (o.machines < 1 || o.frames < 1 || o.repeats < 1 || o.substeps < 1 || o.iterations < 1)
    throw std::invalid_argument("--machines, --frames, --repeats and the budget: expected at least 1");
  const std::vector<int> threads = threadCounts(o.threads);
  bench::checkOutput(o.output);
  bench::Environment env = bench::environment();
  env.threads_used = threads.back();
  bench::printEnvironment(stdout, env);
  std::printf("# one scene of %d Atwood machines (islands), %d x %d, %d timed frames, median of %d runs\n",
              o.machines, o.substeps, o.iterations, o.frames, o.repeats);
  std::printf("# speedup: over one thread on the fastest core; ideal_speedup: the cores' summed rates over it; "
              "busy_speedup: their rates with that many cores busy at once, timed beside each run\n");
  bench::Table table({"machines", "solver", "threads", "frames", "ms_per_frame", "speedup", "ideal_speedup",
                      "busy_speedup", "same_bits"});
  const std::vector<int> cores = allowedCores();
  for (const std::string& name : o.solvers) {
    const SolverKind solver = name == "direct" ? SolverKind::Direct : SolverKind::GaussSeidel;
    // One thread on each core, the fastest core's the baseline: the
    // median of its runs, and its last run's bits.
    Measured one;
    bool cores_agree = true;
    const std::vector<double> per_core = timeOnEachCore(
        [&] {
          std::vector<double> runs;
          Measured m;
          for (int r = 0; r < o.repeats; ++r) {
            m = measure(o, solver, 1);
            runs.push_back(m.ms);
          }
          const double ms = m.ms = median(runs);
          cores_agree = cores_agree && (one.bits.empty() || m.bits == one.bits);
          if (one.bits.empty() || ms < one.ms) one = std::move(m);
          return ms;
        },
        cores);
    printCoreTimes(name, per_core, "ms a frame");
    for (const int t : threads) {
      if (t == 1) {
        table.add({std::to_string(o.machines), name, "1", std::to_string(o.frames), fixed(one.ms, "%.4g"), "1.00",
                   "1.00", "1.00", cores_agree ? "yes" : "NO"});
        continue;
      }
      // Each run beside t one-thread runs on the t fastest cores at once:
      // the host's load on them changes from second to second.
      const std::vector<int> busy_cores = fastestCores(cores, per_core, t);
      std::vector<double> runs, busy;
      bool same = cores_agree;
      std::atomic<bool> busy_same{true};  // the one-thread runs side by side end on the baseline's bits too
      for (int r = 0; r < o.repeats; ++r) {
        const Measured now = measure(o, solver, t);
        runs.push_back(now.ms);
        same = same && now.bits == one.bits;
        const auto side_by_side = [&] {
          const Measured m = measure(o, solver, 1);
          if (m.bits != one.bits) busy_same = false;
          return m.ms;
        };
        busy.push_back(busySpeedup(one.ms, timeOnCoresAtOnce(side_by_side, busy_cores)));
      }
      const double ms = median(runs);
      table.add({std::to_string(o.machines), name, std::to_string(t), std::to_string(o.frames), fixed(ms, "%.4g"),
                 fixed(one.ms / ms, "%.2f"), fixed(idealSpeedup(per_core, t), "%.2f"), fixed(median(busy), "%.2f"),
                 same && busy_same ? "yes" : "NO"});
    }
  }
  table.print(stdout);
  bench::writeOutputs(o.output, table, env, "islands");
  return 0;
}

}  // namespace reeve
