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
// frames on `threads`, the median of `repeats` runs (each after a frame
// stepped untimed, which builds the solvers' structures).
double measure(const std::filesystem::path& file, int copies, int threads, int frames, int repeats) {
  std::vector<double> runs;
  ThreadPool pool(threads);
  for (int r = 0; r < repeats; ++r) {
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
    runs.push_back(ms / (static_cast<double>(frames) * copies));
  }
  std::sort(runs.begin(), runs.end());
  return runs[runs.size() / 2];
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
  std::printf("# speedup: over one thread on the fastest core; ideal_speedup: the cores' summed rates over it\n");
  bench::Table table({"scene", "copies", "threads", "frames", "ms_per_scene_frame", "speedup", "ideal_speedup"});
  for (const std::string& name : o.scenes) {
    const std::filesystem::path file = o.scenes_dir / (name + ".json");
    const std::vector<double> per_core =
        timeOnEachCore([&] { return measure(file, o.copies, 1, o.frames, o.repeats); });
    printCoreTimes(name, per_core, "ms a scene-frame");
    const double one = *std::min_element(per_core.begin(), per_core.end());
    for (const int t : threads) {
      const double ms = t == 1 ? one : measure(file, o.copies, t, o.frames, o.repeats);
      table.add({name, std::to_string(o.copies), std::to_string(t), std::to_string(o.frames), fixed(ms, "%.4g"),
                 fixed(one / ms, "%.2f"), fixed(idealSpeedup(per_core, t), "%.2f")});
    }
  }
  table.print(stdout);
  bench::writeOutputs(o.output, table, env, "batch");
  return 0;
}

}  // namespace reeve
