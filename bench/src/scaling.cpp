// `reeve bench scaling`: how the cost of each solver grows with the number
// of cable joints, on machines that stand still (machines.h, "The series
// of reeve bench scaling"). Every cell runs in a child process of its own,
// so its peak memory is its own and a runaway cell can be killed.
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "reeve/bench/bench.h"
#include "reeve/bench/timing.h"
#include "reeve/machines/machines.h"
#include "solvers.h"

namespace reeve::bench {
namespace {

using machines::ScalingSpec;
using machines::StaticMachine;

// Frames stepped after building a machine and before timing it: lets the
// first solves (and any settling) pass.
constexpr int kWarmupFrames = 3;
constexpr double kFrameS = 1.0 / 60.0;

struct Series {
  std::string name;
  std::function<StaticMachine(const ScalingSpec&)> build;
};

const std::vector<Series>& allSeries() {
  static const std::vector<Series> series = {
      {"chain", machines::scalingChain},
      {"tackle_hinged", machines::tackleHinged},
      {"tackle_rolling", [](const ScalingSpec& s) { return machines::tackleRolling(s, true); }},
      {"tackle_stuck", [](const ScalingSpec& s) { return machines::tackleRolling(s, false); }},
      {"star_rigid", [](const ScalingSpec& s) { return machines::star(s, false); }},
      {"star_compliant", [](const ScalingSpec& s) { return machines::star(s, true); }},
      {"islands", [](const ScalingSpec& s) { return machines::islands(s); }},
      {"islands_braked", [](const ScalingSpec& s) { return machines::islands(s, true); }},
      {"wound", machines::wound},
      {"threaded", machines::threaded},
  };
  return series;
}

const Series& findSeries(const std::string& name) {
  for (const Series& s : allSeries())
    if (s.name == name) return s;
  throw std::invalid_argument("--series: no series called '" + name +
                              "' (chain, tackle_hinged, tackle_rolling, tackle_stuck, star_rigid, star_compliant, "
                              "islands, islands_braked, wound, threaded)");
}

// "SxI": substeps x iterations per frame.
struct FrameBudget {
  int substeps = 1, iterations = 1;
  std::string name() const { return std::to_string(substeps) + "x" + std::to_string(iterations); }
};

FrameBudget parseBudget(const std::string& text) {
  FrameBudget b;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", &b.substeps, &b.iterations, &extra) != 2 || b.substeps < 1 ||
      b.iterations < 1)
    throw std::invalid_argument("--budget: '" + text + "' is not SUBSTEPSxITERATIONS, e.g. 10x2");
  return b;
}

// The largest relative error of any enabled span's tension against the
// machine's closed form, and how many spans were enabled.
std::pair<double, int> staticsError(const StaticMachine& m) {
  double worst = 0.0;
  int joints = 0;
  const CableSystem& cables = *m.scene.cables;
  for (int c = 0; c < static_cast<int>(cables.cables().size()); ++c)
    for (int j = 0; j < static_cast<int>(cables.cables()[c].joints.size()); ++j) {
      if (!cables.jointEnabled(c, j)) continue;
      ++joints;
      worst = std::max(worst, std::abs(cables.tension(c, j) - m.tension_N) / m.tension_N);
    }
  return {worst, joints};
}

// A machine built and warmed up by reset() (not timed), then stepped.
class ScalingRun : public FrameRun {
 public:
  ScalingRun(const Series& series, const ScalingSpec& spec) : series_(series), spec_(spec) {}
  void reset() override {
    machine_ = series_.build(spec_);
    for (int f = 0; f < kWarmupFrames; ++f) step();
  }
  void step() override { machine_.scene.world->step(kFrameS); }
  int lastIterations() const override { return machine_.scene.world->lastStepIterations(); }
  const StaticMachine& machine() const { return machine_; }

 private:
  const Series& series_;
  ScalingSpec spec_;
  StaticMachine machine_;
};

// What a cell's child process writes back through its pipe: plain data.
struct CellReport {
  double ms_per_frame = 0, iterations = 0, statics_error = 0;
  int joints = 0;
  char problem[200] = {};  // why the numbers are missing or suspect ("" when none)
};

void setProblem(CellReport& r, const std::string& text) {
  std::snprintf(r.problem, sizeof r.problem, "%s", text.c_str());
}

// Runs one cell in this (child) process.
CellReport measure(const Series& series, const ScalingSpec& spec, int frames) {
  CellReport r;
  try {
    ScalingRun run(series, spec);
    TimingOptions timing;
    timing.repeats = 1;
    timing.warmup_frames = 0;  // reset() warms up the very run that is timed
    const FrameTiming t = timeFrames(run, frames, timing);
    r.ms_per_frame = t.median_ms;
    r.iterations = t.iterations_per_frame;
    if (const auto& bad = run.machine().scene.world->firstNonFinite()) {
      setProblem(r, std::string("non-finite ") + quantityName(bad->quantity) + " of body " +
                        std::to_string(bad->body) + " at t = " + number(bad->time_s, 3) + " s");
      r.statics_error = std::nan("");
    } else {
      std::tie(r.statics_error, r.joints) = staticsError(run.machine());
    }
  } catch (const std::exception& e) {
    setProblem(r, std::string("not built: ") + e.what());
    r.ms_per_frame = r.statics_error = std::nan("");
  }
  return r;
}

struct CellOutcome {
  bool ran = false;
  CellReport report;
  double peak_mb = std::nan("");
  std::string skipped;  // why it did not run or finish
};

// Reads the child's report from `fd` until `timeout_s` have passed; false
// when it did not come whole.
bool readReport(int fd, CellReport& report, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  auto* bytes = reinterpret_cast<char*>(&report);
  std::size_t got = 0;
  while (got < sizeof report) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) return false;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fd, bytes + got, sizeof report - got);
    if (n == 0 || (n < 0 && errno != EINTR)) return false;  // the child died first
    if (n > 0) got += static_cast<std::size_t>(n);
  }
  return true;
}

// Runs `cell` in a fork()ed child, killed after `timeout_s`; its peak
// resident memory is the child's own ru_maxrss.
CellOutcome runIsolated(const std::function<CellReport()>& cell, double timeout_s) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error(std::string("scaling: pipe: ") + std::strerror(errno));
  std::fflush(stdout);  // else the child inherits, and could repeat, unwritten output
  std::fflush(stderr);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("scaling: fork: ") + std::strerror(errno));
  if (pid == 0) {
    ::close(fds[0]);
    const CellReport report = cell();
    const ssize_t written = ::write(fds[1], &report, sizeof report);  // below PIPE_BUF: one write
    ::_exit(written == static_cast<ssize_t>(sizeof report) ? 0 : 1);
  }
  ::close(fds[1]);
  CellOutcome out;
  const bool whole = readReport(fds[0], out.report, timeout_s);
  ::close(fds[0]);
  if (!whole) ::kill(pid, SIGKILL);
  int status = 0;
  rusage usage{};
  while (::wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  out.peak_mb = usage.ru_maxrss / 1024.0;  // KiB on Linux
  if (whole) {
    out.ran = true;
  } else if (WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) {
    out.skipped = "killed after the cell timeout of " + number(timeout_s, 3) + " s";
  } else {
    out.skipped = WIFSIGNALED(status) ? "crashed (signal " + std::to_string(WTERMSIG(status)) + ")"
                                      : "the cell's process exited with " + std::to_string(WEXITSTATUS(status));
  }
  return out;
}

// A chain of K wheels and its ms a frame.
struct SizeTime {
  int k;
  double ms;
};

// Least-squares slope of log(ms) against log(K) over `points`; NaN with
// fewer than two distinct K.
double fittedExponent(const std::vector<SizeTime>& points) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const SizeTime& p : points) {
    const double x = std::log(p.k), y = std::log(p.ms);
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double d = n * sxx - sx * sx;
  return n >= 2 && d > 0 ? (n * sxy - sx * sy) / d : std::nan("");
}

// The exponent the report prints: over the cells run with K >= 16.
double reportedExponent(const std::vector<SizeTime>& points) {
  std::vector<SizeTime> large;
  std::copy_if(points.begin(), points.end(), std::back_inserter(large), [](const SizeTime& p) { return p.k >= 16; });
  return fittedExponent(large);
}

// ms/frame predicted at `k` from the last cell run, with the exponent so
// far (over K >= 16 once there are two such cells, else over all; 1, linear,
// from a single cell).
double predictedMs(const std::vector<SizeTime>& points, int k) {
  double exponent = reportedExponent(points);
  if (!std::isfinite(exponent)) exponent = fittedExponent(points);
  if (!std::isfinite(exponent)) exponent = 1.0;
  const SizeTime& last = points.back();
  return last.ms * std::pow(static_cast<double>(k) / last.k, exponent);
}

struct Sequence {
  const Series* series;
  SolverKind solver;
  FrameBudget budget;
};

std::vector<Sequence> sequences(const ScalingOptions& o) {
  std::vector<const Series*> chosen;
  if (o.series.empty())
    for (const Series& s : allSeries()) chosen.push_back(&s);
  for (const std::string& name : o.series) chosen.push_back(&findSeries(name));
  std::vector<FrameBudget> budgets;
  for (const std::string& b : o.budgets) budgets.push_back(parseBudget(b));
  std::vector<Sequence> out;
  for (const Series* s : chosen)
    for (const std::string& solver : o.solvers)
      for (const FrameBudget& b : budgets) out.push_back({s, solverKind(solver), b});
  return out;
}

// Runs one series x solver x budget over the K of `o` in increasing order,
// adding a row per K; returns the cells that ran.
std::vector<SizeTime> runSequence(const Sequence& seq, const ScalingOptions& o, Table& table) {
  std::vector<int> ks = o.k;
  std::sort(ks.begin(), ks.end());
  std::vector<SizeTime> points;
  std::string stop;  // once set, why every larger K is skipped
  for (const int k : ks) {
    const std::string solver = solverMethodName(seq.solver);
    std::vector<std::string> row = {seq.series->name, solver, seq.budget.name(), std::to_string(k)};
    if (stop.empty() && !points.empty()) {
      const double predicted = predictedMs(points, k);
      if (predicted > o.max_ms_per_frame)
        stop = "skipped: " + number(predicted, 3) + " ms/frame predicted from K = " + std::to_string(points.back().k) +
               ", over --max-ms-per-frame " + number(o.max_ms_per_frame, 4);
    }
    if (!stop.empty()) {
      row.insert(row.end(), {"", "", "", "", "", stop});
      table.add(row);
      continue;
    }
    ScalingSpec spec;
    spec.count = k;
    spec.budget = {seq.budget.substeps, seq.budget.iterations, seq.solver};
    std::fprintf(stderr, "scaling: %s %s %s K = %d\n", seq.series->name.c_str(), solver.c_str(),
                 seq.budget.name().c_str(), k);
    const CellOutcome cell = runIsolated([&] { return measure(*seq.series, spec, o.frames); }, o.cell_timeout_s);
    if (!cell.ran) {
      stop = "skipped: K = " + std::to_string(k) + " was " + cell.skipped;
      row.insert(row.end(), {"", "", number(cell.peak_mb, 3), "", "", "skipped: " + cell.skipped});
      table.add(row);
      continue;
    }
    const CellReport& r = cell.report;
    row.insert(row.end(), {r.joints ? std::to_string(r.joints) : "", number(r.ms_per_frame, 3), number(cell.peak_mb, 3),
                           number(r.iterations, 3), number(r.statics_error, 3), r.problem});
    table.add(row);
    if (std::isfinite(r.ms_per_frame) && r.ms_per_frame > 0) points.push_back({k, r.ms_per_frame});
  }
  return points;
}

}  // namespace

int scaling(const ScalingOptions& options) {
  checkOutput(options.output);
  const std::vector<Sequence> seqs = sequences(options);  // checks every name before measuring
  if (options.frames < 1) throw std::invalid_argument("--frames: must be at least 1");
  const Environment env = environment();
  printEnvironment(stdout, env);
  std::printf(
      "# Machines at rest (machines.h); K: wheels, falls, cables, machines or wraps. Each cell in a process of its\n"
      "# own: built, %d frames of 1/60 s stepped, then %d frames timed (ms/frame: their median; iterations: per\n"
      "# frame). peak_mb: the process's peak resident memory. statics_error: the largest relative error of a\n"
      "# span's tension against the closed form after the timed frames. A cell predicted (from the one before,\n"
      "# with the exponent so far) over %g ms/frame is skipped, one running over %g s is killed.\n",
      kWarmupFrames, options.frames, options.max_ms_per_frame, options.cell_timeout_s);
  Table table({"series", "solver", "budget", "K", "joints", "ms_per_frame", "peak_mb", "iterations", "statics_error",
               "note"});
  std::vector<std::pair<const Sequence*, double>> exponents;
  for (const Sequence& seq : seqs) exponents.push_back({&seq, reportedExponent(runSequence(seq, options, table))});
  table.print(stdout);
  std::printf("\n# fitted exponent p of ms/frame ~ K^p (least squares on log-log, cells run with K >= 16):\n");
  for (const auto& [seq, p] : exponents)
    std::printf("#   %-15s %-13s %-5s %s\n", seq->series->name.c_str(), solverMethodName(seq->solver),
                seq->budget.name().c_str(), std::isfinite(p) ? number(p, 3).c_str() : "(fewer than two cells)");
  writeOutputs(options.output, table, env, "scaling");
  return 0;
}

}  // namespace reeve::bench
