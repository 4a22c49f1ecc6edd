// `reeve bench table1`: the paper's Table 1 (sec. 5) reproduced.
#include <algorithm>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "reeve/bench/bench.h"
#include "reeve/bench/timing.h"
#include "reeve/scene/energy.h"
#include "solvers.h"

namespace reeve::bench {
namespace {

// A Table 1 row: the paper's cable joints, one step per frame with its
// iterations (the bow: 10 substeps x 10, sec. 5) and its ms/frame on a
// 3.5 GHz Core i7. Simple at 10 iterations (0.036 ms) and Hilbert3 at
// 100 (60 ms) are from the text of sec. 5; the table gives 1 and 10.
struct PaperSetting {
  int substeps, iterations;
  double ms;
};
struct Machine {
  const char* name;
  const char* file;
  int paper_joints;  // 0: not given
  std::vector<PaperSetting> paper;
};

const std::vector<Machine>& machines() {
  static const std::vector<Machine> list = {
      {"Simple", "simple.json", 4, {{1, 1, 0.012}, {1, 10, 0.036}}},
      {"Servin", "servin.json", 16, {{1, 10, 0.25}}},
      {"Pulley", "pulley.json", 6, {{1, 15, 0.3}}},
      {"Hand", "hand.json", 28, {{1, 20, 1.7}}},
      {"Gym", "gym.json", 16, {{1, 20, 2.5}}},
      {"Hilbert2", "hilbert2.json", 62, {{1, 10, 1.8}}},
      {"Hilbert3", "hilbert3.json", 498, {{1, 10, 60.0}, {1, 100, 60.0}}},
      {"Bow", "bow.json", 0, {{10, 10, 25.0}}},
  };
  return list;
}

// A substep's cost split into what its iterations cost and what they do
// not (issue 30): the machine at `substeps` a frame, of 1 and of 10
// iterations, every one run (tolerance 0). A frame costs substeps x
// (fixed + n x per_iteration).
struct SplitCost {
  double fixed_us_per_substep = 0.0, ns_per_joint_iteration = 0.0;
};

struct Measured {
  std::string machine, solver;
  bool paper;
  int substeps, iterations;
  double median_ms, speedup, ns_per_joint_iteration;
  SplitCost split;  // the first paper row's; zero on the others
  double energy_created_J;
};

// A scene timed as SceneRun, its energy ledger watched off the clock
// (observe(): the first timed run): the largest energy created that the
// watch reported in a frame (EnergyWatch, scene/energy.h), 0 if none. A
// time is only worth comparing where the run it times is right.
class WatchedSceneRun : public SceneRun {
 public:
  using SceneRun::SceneRun;
  void reset() override {
    SceneRun::reset();
    watch_.emplace(scene());
  }
  void observe(int /*frame*/) override {
    if (const std::optional<EnergyCreated> made = watch_->check(scene()))
      created_J_ = std::max(created_J_, made->created_J);
  }
  double createdJ() const { return created_J_; }

 private:
  std::optional<EnergyWatch> watch_;
  double created_J_ = 0.0;
};

// The yardsticks: the smallest speed-up over the paper per
// solver, and whether cost stays linear in joints x iterations from
// Hilbert2 to Hilbert3 (their ns per joint-iteration at 1 x 10).
void printSummary(const std::vector<Measured>& rows, const std::vector<std::string>& solvers) {
  for (const std::string& solver : solvers) {
    const Measured* slowest = nullptr;
    const Measured *h2 = nullptr, *h3 = nullptr;
    for (const Measured& m : rows) {
      if (m.solver != solver || !m.paper) continue;
      if (!slowest || m.speedup < slowest->speedup) slowest = &m;
      if (m.substeps == 1 && m.iterations == 10) {
        if (m.machine == "Hilbert2") h2 = &m;
        if (m.machine == "Hilbert3") h3 = &m;
      }
    }
    if (slowest)
      std::printf("%s: smallest speed-up over the paper %sx (%s at %d x %d)\n", solver.c_str(),
                  number(slowest->speedup, 3).c_str(), slowest->machine.c_str(), slowest->substeps,
                  slowest->iterations);
    if (h3) std::printf("%s: Hilbert3 at 1 x 10: %s ms/frame\n", solver.c_str(), number(h3->median_ms, 3).c_str());
    if (h2 && h3)
      std::printf("%s: ns per joint-iteration at 1 x 10: Hilbert2 %s, Hilbert3 %s (ratio %s)\n", solver.c_str(),
                  number(h2->ns_per_joint_iteration, 3).c_str(), number(h3->ns_per_joint_iteration, 3).c_str(),
                  number(h3->ns_per_joint_iteration / h2->ns_per_joint_iteration, 3).c_str());
    if (h3)
      std::printf("%s: Hilbert3, every iteration run: %s us a substep besides its iterations, %s ns per joint and "
                  "iteration\n",
                  solver.c_str(), number(h3->split.fixed_us_per_substep, 3).c_str(),
                  number(h3->split.ns_per_joint_iteration, 3).c_str());
    std::string created;
    for (const Measured& m : rows)
      if (m.solver == solver && m.energy_created_J > 0.0)
        created += std::string(created.empty() ? "" : ", ") + m.machine + " " + std::to_string(m.substeps) + " x " +
                   std::to_string(m.iterations) + " (" + number(m.energy_created_J, 3) + " J)";
    std::printf("%s: energy created (the ledger's watch): %s\n", solver.c_str(),
                created.empty() ? "none" : created.c_str());
  }
}

// Measures SplitCost for `solver` on the scene in `file`.
SplitCost splitCost(const std::filesystem::path& file, const std::string& solver, int substeps, int joints,
                    int frames, const TimingOptions& timing) {
  double ms[2];
  const int iterations[2] = {1, 10};
  for (int k = 0; k < 2; ++k) {
    SceneRun run([&] {
      Scene s = loadScene(file);
      s.world->settings().substeps = substeps;
      s.world->settings().iterations = iterations[k];
      s.world->settings().tolerance = 0.0;
      s.world->settings().solver = solverKind(solver);
      return s;
    });
    ms[k] = timeFrames(run, frames, timing).median_ms / substeps;
  }
  const double per_iteration_ms = (ms[1] - ms[0]) / (iterations[1] - iterations[0]);
  return {1e3 * (ms[0] - per_iteration_ms), 1e6 * per_iteration_ms / joints};
}

int cableJoints(const Scene& s) {
  int joints = 0;
  for (const Cable& c : s.cables->cables()) joints += static_cast<int>(c.joints.size());
  return joints;
}

}  // namespace

int table1(const Table1Options& options) {
  checkOutput(options.output);
  for (const std::string& name : options.only) {
    bool known = false;
    for (const Machine& m : machines()) known |= name == m.name;
    if (!known) throw std::invalid_argument("--only: no Table 1 machine called '" + name + "'");
  }
  const Environment env = environment();
  printEnvironment(stdout, env);
  std::printf(
      "# Table 1 (Mueller et al. 2018, sec. 5). Absolute times depend on the machine; the paper's were measured\n"
      "# on a 3.5 GHz Core i7. ms/frame of physics: min / median / max over %d runs, each after a warm-up.\n",
      options.repeats);
  Table table({"machine", "setting", "solver", "substeps", "iterations", "frames", "joints", "paper_joints",
               "min_ms", "median_ms", "max_ms", "paper_ms", "speedup", "iterations_run", "ns_per_joint_iteration",
               "fixed_us_per_substep", "marginal_ns_per_joint_iteration", "energy_created_J"});
  std::vector<Measured> measured;
  TimingOptions timing;
  timing.repeats = options.repeats;
  for (const Machine& m : machines()) {
    if (!options.only.empty() && std::find(options.only.begin(), options.only.end(), m.name) == options.only.end())
      continue;
    const std::filesystem::path file = options.scenes_dir / m.file;
    const Scene probe = loadScene(file);
    const int joints = cableJoints(probe);
    const int frames = options.frames ? std::min(*options.frames, probe.frameCount()) : probe.frameCount();
    std::vector<PaperSetting> settings = m.paper;
    settings.push_back({probe.world->settings().substeps, probe.world->settings().iterations, 0.0});
    std::vector<SplitCost> split;  // per solver, at the paper's first setting's substeps
    for (const std::string& solver : options.solvers)
      split.push_back(splitCost(file, solver, m.paper.front().substeps, joints, frames, timing));
    for (std::size_t k = 0; k < settings.size(); ++k)
      for (std::size_t v = 0; v < options.solvers.size(); ++v) {
        const std::string& solver = options.solvers[v];
        const PaperSetting& at = settings[k];
        WatchedSceneRun run([&] {
          Scene s = loadScene(file);
          s.world->settings().substeps = at.substeps;
          s.world->settings().iterations = at.iterations;
          s.world->settings().solver = solverKind(solver);
          return s;
        });
        const FrameTiming t = timeFrames(run, frames, timing);
        const bool paper = k + 1 < settings.size();
        const double ns = 1e6 * t.median_ms / (joints * t.iterations_per_frame);
        table.add({m.name, paper ? "paper" : "default", solver, std::to_string(at.substeps),
                   std::to_string(at.iterations), std::to_string(frames), std::to_string(joints),
                   m.paper_joints ? std::to_string(m.paper_joints) : "", number(t.min_ms, 3), number(t.median_ms, 3),
                   number(t.max_ms, 3), paper ? number(at.ms, 3) : "", paper ? number(at.ms / t.median_ms, 3) : "",
                   number(t.iterations_per_frame, 3), number(ns, 3),
                   k == 0 ? number(split[v].fixed_us_per_substep, 3) : "",
                   k == 0 ? number(split[v].ns_per_joint_iteration, 3) : "", number(run.createdJ(), 3)});
        measured.push_back({m.name, solver, paper, at.substeps, at.iterations, t.median_ms,
                            paper ? at.ms / t.median_ms : 0.0, ns, k == 0 ? split[v] : SplitCost{}, run.createdJ()});
      }
    std::fprintf(stderr, "table1: %s done\n", m.name);
  }
  table.print(stdout);
  printSummary(measured, options.solvers);
  writeOutputs(options.output, table, env, "table1");
  return 0;
}

}  // namespace reeve::bench
