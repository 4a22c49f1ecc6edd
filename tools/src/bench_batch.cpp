#include "bench_batch.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "batch.h"
#include "bench_format.h"
#include "bench_threads.h"

namespace reeve {
namespace {

// ms per scene-frame of `copies` fresh copies of `file` stepped `frames`
// frames on `threads`, after a frame stepped untimed (which builds the
// solvers' structures).
double measure(const std::filesystem::path& file, int copies, int threads, int frames) {
  ThreadPool pool(threads);
  std::vector<Scene> scenes;
  for (int c = 0; c < copies; ++c) scenes.push_back(loadScene(file));
  std::vector<BatchItem> items;
  for (Scene& s : scenes) items.push_back({&s, nullptr});
  stepBatch(items, 1, pool);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<BatchOutcome> out = stepBatch(items, frames, pool);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  for (const BatchOutcome& o : out)
    if (o.stopped) throw std::runtime_error(file.filename().string() + ": " + *o.stopped);
  return ms / (static_cast<double>(frames) * copies);
}

}  // namespace

int benchBatch(const BatchBenchOptions& o) {
  if (o.copies < 1 || o.frames < 1 || o.repeats < 1)
    throw std::invalid_argument("--copies, --frames and --repeats: expected at least 1");
  const std::vector<int> threads = threadCounts(o.threads);
  for (const std::string& name : o.scenes)
    if (!std::filesystem::is_regular_file(o.scenes_dir / (name + ".json")))
      throw std::invalid_argument("--only: no scene file " + (o.scenes_dir / (name + ".json")).string());
  bench::checkOutput(o.output);
  bench::Environment env = bench::environment();
  env.threads_used = threads.back();
  bench::printEnvironment(stdout, env);
  std::printf("# %d copies of each scene stepped side by side (reeve.Batch), %d timed frames, median of %d runs\n",
              o.copies, o.frames, o.repeats);
  std::printf("# speedup: over one thread on the fastest core; ideal_speedup: the cores' summed rates over it; "
              "busy_speedup: their rates with that many cores busy at once, timed beside each run\n");
  bench::Table table(
      {"scene", "copies", "threads", "frames", "ms_per_scene_frame", "speedup", "ideal_speedup", "busy_speedup"});
  const std::vector<int> cores = allowedCores();
  for (const std::string& name : o.scenes) {
    const std::filesystem::path file = o.scenes_dir / (name + ".json");
    const auto median_of_runs = [&](int threads) {
      std::vector<double> runs;
      for (int r = 0; r < o.repeats; ++r) runs.push_back(measure(file, o.copies, threads, o.frames));
      return median(runs);
    };
    const std::vector<double> per_core = timeOnEachCore([&] { return median_of_runs(1); }, cores);
    printCoreTimes(name, per_core, "ms a scene-frame");
    const double one = *std::min_element(per_core.begin(), per_core.end());
    for (const int t : threads) {
      if (t == 1) {
        table.add({name, std::to_string(o.copies), "1", std::to_string(o.frames), fixed(one, "%.4g"), "1.00", "1.00",
                   "1.00"});
        continue;
      }
      // Each run beside t one-thread runs on the t fastest cores at once:
      // the host's load on them changes from second to second.
      const std::vector<int> busy_cores = fastestCores(cores, per_core, t);
      std::vector<double> runs, busy;
      for (int r = 0; r < o.repeats; ++r) {
        runs.push_back(measure(file, o.copies, t, o.frames));
        const auto side_by_side = [&] { return measure(file, o.copies, 1, o.frames); };
        busy.push_back(busySpeedup(one, timeOnCoresAtOnce(side_by_side, busy_cores)));
      }
      const double ms = median(runs);
      table.add({name, std::to_string(o.copies), std::to_string(t), std::to_string(o.frames), fixed(ms, "%.4g"),
                 fixed(one / ms, "%.2f"), fixed(idealSpeedup(per_core, t), "%.2f"), fixed(median(busy), "%.2f")});
    }
  }
  table.print(stdout);
  bench::writeOutputs(o.output, table, env, "batch");
  return 0;
}

}  // namespace reeve
