// `reeve bench extremes`: the stability map.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <map>
#include <string>
#include <vector>

#include "extremes_cells.h"
#include "reeve/bench/bench.h"
#include "solvers.h"

namespace reeve::bench {
namespace {

// Substeps per simulated second beyond which a cell is left out: 2000 Hz x
// 100 substeps (h = 5 us) costs Gauss-Seidel at 100 iterations a minute a
// cell and shows nothing 2000 x 10 does not.
constexpr double kMaxSubstepRate = 24000.0;

struct Cell {
  Condition condition;
  CellBudget budget;
};

std::vector<Cell> grid(const ExtremesOptions& o) {
  std::vector<Cell> cells;
  for (const std::string& machine : o.machines) {
    std::vector<Condition> list = conditions(machine);
    for (const std::string& name : o.conditions) {
      bool known = false;
      for (const std::string& m : o.machines)
        for (const Condition& c : conditions(m)) known |= c.name == name;
      if (!known) throw std::invalid_argument("--conditions: no condition called '" + name + "'");
    }
    for (const Condition& c : list) {
      if (!o.conditions.empty() && std::find(o.conditions.begin(), o.conditions.end(), c.name) == o.conditions.end())
        continue;
      for (const std::string& solver : o.solvers)
        for (const double rate : o.rates_hz)
          for (const int substeps : o.substeps)
            for (const int iterations : o.iterations)
              if (rate * substeps <= kMaxSubstepRate)
                cells.push_back({c, {rate, substeps, iterations, solverKind(solver)}});
    }
  }
  return cells;
}

// The cell called `key` in the full grid.
Cell findCell(const std::string& key) {
  const ExtremesOptions all;
  for (const Cell& c : grid(all))
    if (cellKey(c.condition, c.budget) == key) return c;
  throw std::invalid_argument("--cell: no cell '" + key +
                              "'; keys look like atwood/wheel_ratio=1e-6/30Hz/1x1/gauss-seidel");
}

// A cell's error against its closed form: the worse of its tension and
// speed errors where it has them; NaN where it has neither.
double cellError(const CellResult& r) {
  double e = std::nan("");
  for (const double x : {r.tension_error, r.speed_error})
    if (std::isfinite(x)) e = std::isfinite(e) ? std::max(e, x) : x;
  return e;
}

// More iterations at fixed substeps must never give a worse answer (issue
// 29): per machine, condition, rate, substeps and solver, each iteration
// count's error against the fewer iterations' before it, beyond rounding
// (1e-9, or 1 % of the smaller). Returns one line per cell that is worse.
std::vector<std::string> worseWithIterations(const std::vector<Cell>& cells, const std::vector<CellResult>& results) {
  std::map<std::string, std::vector<std::pair<int, std::size_t>>> groups;  // without iterations: (iterations, cell)
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const CellBudget& b = cells[i].budget;
    groups[cells[i].condition.machine + "/" + cells[i].condition.name + "/" + shortNumber(b.rate_hz) + "/" +
           std::to_string(b.substeps) + "/" + solverMethodName(b.solver)]
        .push_back({b.iterations, i});
  }
  std::vector<std::string> worse;
  for (auto& [group, list] : groups) {
    std::sort(list.begin(), list.end());
    double best = std::nan("");  // the least error at fewer iterations
    int best_iterations = 0;
    for (const auto& [iterations, i] : list) {
      const double e = cellError(results[i]);
      if (!std::isfinite(e)) continue;
      if (std::isfinite(best) && e > 1.01 * best + 1e-9) {
        char line[512];
        std::snprintf(line, sizeof line, "%s: error %.3g at %d iterations, %.3g at %d",
                      cellKey(cells[i].condition, cells[i].budget).c_str(), e, iterations, best, best_iterations);
        worse.push_back(line);
      }
      if (!std::isfinite(best) || e < best) best = e, best_iterations = iterations;
    }
  }
  return worse;
}

}  // namespace

int extremes(const ExtremesOptions& options) {
  checkOutput(options.output);
  const std::vector<Cell> cells = options.cell.empty() ? grid(options) : std::vector<Cell>{findCell(options.cell)};
  const Environment env = environment();
  printEnvironment(stdout, env);
  std::printf(
      "# Stable: finished, finite, cable bookkeeping kept, peak span strain <= 1 %% + twice the static strain\n"
      "# compliance predicts, energy growth (max E - E0) / (max kinetic + sum m g x 1 cm) <= 1 %%. g = 10 (none\n"
      "# for jerks). Atwood 1 s, Simple 0.5 s, jerks 0.2 s past the snap. Errors are relative, at the last\n"
      "# frame. Cells above %g substeps per simulated second (2000 Hz x 100) are left out.\n",
      kMaxSubstepRate);
  Table table({"machine", "condition", "rate_hz", "substeps", "iterations", "solver", "finished", "finite",
               "peak_stretch", "stretch_limit", "energy_growth", "tension_error", "speed_error", "axle_offset_m",
               "stable", "cause", "key"});
  std::map<std::string, std::pair<int, int>> tally;  // solver: stable, total
  std::vector<std::string> unstable;
  std::vector<CellResult> results;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const Cell& cell = cells[i];
    const CellResult r = runCell(cell.condition, cell.budget);
    results.push_back(r);
    const std::string key = cellKey(cell.condition, cell.budget), solver = solverMethodName(cell.budget.solver);
    table.add({cell.condition.machine, cell.condition.name, shortNumber(cell.budget.rate_hz),
               std::to_string(cell.budget.substeps), std::to_string(cell.budget.iterations), solver,
               r.finished ? "1" : "0", r.finite ? "1" : "0", number(r.peak_stretch, 3), number(r.stretch_limit, 3),
               number(r.energy_growth, 3), number(r.tension_error, 3), number(r.speed_error, 3),
               number(r.axle_offset, 3), r.stable() ? "1" : "0", r.cause, key});
    auto& t = tally[solver];
    t.first += r.stable();
    ++t.second;
    if (!r.stable()) unstable.push_back("reeve bench extremes --cell '" + key + "'   # " + r.cause);
    if ((i + 1) % 100 == 0) std::fprintf(stderr, "extremes: %zu of %zu cells\n", i + 1, cells.size());
  }
  if (cells.size() <= 40) table.print(stdout);
  for (const auto& [solver, t] : tally)
    std::printf("%s: %d of %d cells stable (%.1f %%)\n", solver.c_str(), t.first, t.second, 100.0 * t.first / t.second);
  if (!unstable.empty()) {
    std::printf("unstable cells, each with the command that reproduces it:\n");
    for (const std::string& line : unstable) std::printf("  %s\n", line.c_str());
  }
  const std::vector<std::string> worse = worseWithIterations(cells, results);
  std::printf("cells whose error grows with iterations at fixed substeps (beyond 1 %% + 1e-9): %zu\n", worse.size());
  for (const std::string& line : worse) std::printf("  %s\n", line.c_str());
  writeOutputs(options.output, table, env, "extremes");
  return 0;
}

}  // namespace reeve::bench
