// `reeve bench trade`: error against closed forms versus cost.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "reeve/bench/bench.h"
#include "reeve/bench/timing.h"
#include "solvers.h"
#include "trade_cases.h"

namespace reeve::bench {
namespace {

// One case at one budget: the errors come from the first timed run (all
// runs are the same computation).
class TradeRun : public FrameRun {
 public:
  TradeRun(ClosedFormCase& c, int substeps, int iterations, SolverKind solver)
      : case_(c), substeps_(substeps), iterations_(iterations), solver_(solver) {}
  void reset() override {
    scene_ = case_.make();
    scene_.world->settings().substeps = substeps_;
    scene_.world->settings().iterations = iterations_;
    scene_.world->settings().solver = solver_;
    case_.start(scene_);
  }
  void step() override { scene_.world->step(1.0 / 60.0); }
  int lastIterations() const override { return scene_.world->lastStepIterations(); }
  void observe(int frame) override {
    if (scene_.world->firstNonFiniteBody()) finite_ = false;
    if (finite_) case_.observe(scene_, frame);
    if (frame + 1 == case_.frames() && finite_) errors_ = case_.errors(scene_);
  }
  bool finite() const { return finite_; }
  const Errors& errors() const { return errors_; }

 private:
  ClosedFormCase& case_;
  int substeps_, iterations_;
  SolverKind solver_;
  Scene scene_;
  bool finite_ = true;
  Errors errors_;
};

struct Point {
  std::string case_name, series;
  int substeps = 0, iterations = 0;
  double ms = 0, error = std::numeric_limits<double>::quiet_NaN();
  bool pareto = false;
};

// Marks, per case and series, the points no other point beats on both
// cost and error.
void markPareto(std::vector<Point>& points) {
  for (Point& p : points) {
    if (!std::isfinite(p.error)) continue;
    p.pareto = true;
    for (const Point& q : points)
      if (&q != &p && q.case_name == p.case_name && q.series == p.series && std::isfinite(q.error) &&
          q.ms <= p.ms && q.error <= p.error && (q.ms < p.ms || q.error < p.error)) {
        p.pareto = false;
        break;
      }
  }
}

// Per Atwood case and rope series: the smallest ratio of a rope point's
// error to the best Reeve error at no more ms/frame.
void printDominance(const std::vector<Point>& points) {
  std::map<std::pair<std::string, std::string>, std::pair<double, std::string>> worst;
  for (const Point& rope : points) {
    if (rope.series.rfind("rope", 0) != 0) continue;
    double best = std::numeric_limits<double>::infinity();
    for (const Point& q : points)
      if (q.case_name == rope.case_name && q.series.rfind("reeve", 0) == 0 && q.ms <= rope.ms &&
          std::isfinite(q.error))
        best = std::min(best, q.error);
    auto& w = worst.try_emplace({rope.case_name, rope.series}, std::numeric_limits<double>::infinity(), "").first->second;
    if (!std::isfinite(best)) {
      w = {0.0, "no Reeve point as cheap"};
      continue;
    }
    const double ratio = std::isfinite(rope.error) ? rope.error / std::max(best, 1e-300) : std::numeric_limits<double>::infinity();
    if (ratio < w.first) w = {ratio, ""};
  }
  if (worst.empty()) return;
  std::printf("\n# rope error / Reeve's best error at no more ms/frame (smallest over the rope's points):\n");
  for (const auto& [key, w] : worst)
    std::printf("#   %-20s %-22s %s\n", key.first.c_str(), key.second.c_str(),
                !w.second.empty() ? w.second.c_str()
                : std::isfinite(w.first) ? (number(w.first, 3) + " x").c_str()
                                         : "every rope point failed");
}

// Substeps for Reeve to cost what each rope point on a front costs: the
// grid's Reeve points stop at 50 substeps (well under a millisecond), the
// ropes' run to 100 ms, and "equal ms/frame" needs Reeve there too. Reeve's
// cost grows linearly with substeps; its series' dearest one-iteration
// point gives the cost of one. Rounded down to two significant figures,
// at most 1e5.
std::map<std::string, std::set<int>> matchedSubsteps(const std::vector<Point>& points, const std::string& reeve,
                                                     const std::vector<int>& grid_substeps) {
  const int grid_max = *std::max_element(grid_substeps.begin(), grid_substeps.end());
  std::map<std::string, std::set<int>> out;
  for (const Point& rope : points) {
    if (rope.series.rfind("rope", 0) != 0 || !rope.pareto) continue;
    double ms_per_substep = 0.0;
    for (const Point& q : points)
      if (q.case_name == rope.case_name && q.series == reeve && q.iterations == 1 && q.substeps == grid_max)
        ms_per_substep = q.ms / grid_max;
    if (!(ms_per_substep > 0.0)) continue;
    const double want = std::min(1e5, rope.ms / ms_per_substep);
    if (want <= grid_max) continue;
    const double scale = std::pow(10.0, std::floor(std::log10(want)) - 1.0);
    out[rope.case_name].insert(static_cast<int>(std::floor(want / scale) * scale));
  }
  return out;
}

}  // namespace

int trade(const TradeOptions& options) {
  checkOutput(options.output);
  std::vector<std::unique_ptr<ClosedFormCase>> cases = tradeCases(options.scenes_dir);
  std::set<std::string> names;
  for (auto& c : cases) names.insert(c->name());
  for (const std::string& name : options.only)
    if (!names.count(name)) throw std::invalid_argument("--only: no trade case called '" + name + "'");
  const auto wanted = [&](const std::string& name) {
    return options.only.empty() || std::find(options.only.begin(), options.only.end(), name) != options.only.end();
  };
  for (const std::string& solver : options.solvers) solverKind(solver);  // checks the names first
  const Environment env = environment();
  printEnvironment(stdout, env);
  std::printf("# error: the largest relative error against the closed form (worst: which); ms/frame: median of up to\n"
              "# %d runs (fewer once 2 s were timed). Frames of 1/60 s.\n", options.repeats);
  for (auto& c : cases)
    if (wanted(c->name())) std::printf("#   %-20s %s\n", c->name().c_str(), c->description().c_str());
  // (series, case) in report order: every cable case, then the ropes.
  std::vector<std::pair<std::string, ClosedFormCase*>> order;
  for (auto& c : cases)
    if (wanted(c->name()))
      for (const std::string& solver : options.solvers) order.push_back({"reeve " + solver, c.get()});
  std::vector<std::vector<std::unique_ptr<ClosedFormCase>>> ropes;
  for (const int n : options.rope_segments) {
    ropes.push_back(ropeCases(options.scenes_dir, n));
    for (auto& c : ropes.back())
      if (wanted(c->name()))
        for (const std::string& solver : options.solvers)
          order.push_back({"rope" + std::to_string(n) + " " + solver, c.get()});
  }

  Table table({"case", "series", "solver", "substeps", "iterations", "ms_per_frame", "error", "worst", "pareto",
               "detail"});
  std::vector<Point> points;
  std::vector<std::vector<std::string>> cells;
  TimingOptions timing;
  timing.repeats = options.repeats;
  timing.warmup_frames = 0;  // the runs are short; the first timed run warms up the rest
  timing.max_seconds = 2.0;
  const auto measure = [&](ClosedFormCase& c, const std::string& series, const std::string& solver, int substeps,
                           int iterations) {
    TradeRun run(c, substeps, iterations, solverKind(solver));
    Point p{c.name(), series, substeps, iterations};
    std::string worst, detail;
    try {
      p.ms = timeFrames(run, c.frames(), timing).median_ms;
      if (run.finite()) {
        const auto w = run.errors().worst();
        p.error = w.second;
        worst = w.first;
        for (const auto& [name, value] : run.errors().parts)
          detail += (detail.empty() ? "" : ";") + name + "=" + number(value, 6);
      } else {
        worst = "non-finite state";
      }
    } catch (const std::exception& e) {
      worst = std::string("failed: ") + e.what();
    }
    points.push_back(p);
    cells.push_back({c.name(), series, solver, std::to_string(substeps), std::to_string(iterations), number(p.ms, 4),
                     number(p.error, 4), worst, "", detail});
  };
  for (const auto& [series, c] : order) {
    const std::string solver = series.substr(series.find(' ') + 1);
    for (const int substeps : options.substeps)
      for (const int iterations : options.iterations) measure(*c, series, solver, substeps, iterations);
    std::fprintf(stderr, "trade: %s, %s done\n", c->name().c_str(), series.c_str());
  }
  markPareto(points);
  // Reeve (its first solver, one iteration) at the cost of the ropes' fronts.
  if (!ropes.empty() && !options.solvers.empty()) {
    const std::string solver = options.solvers.front();
    const auto matched = matchedSubsteps(points, "reeve " + solver, options.substeps);
    for (auto& c : cases)
      if (matched.count(c->name()))
        for (const int substeps : matched.at(c->name()))
          measure(*c, "reeve " + solver + " at the ropes' cost", solver, substeps, 1);
    markPareto(points);
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    cells[i][8] = points[i].pareto ? "1" : "0";
    table.add(cells[i]);
  }
  table.print(stdout);
  printDominance(points);
  writeOutputs(options.output, table, env, "trade");
  return 0;
}

}  // namespace reeve::bench
