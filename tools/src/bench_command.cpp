#include "bench_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>
#include <stdexcept>

#include "bench_batch.h"
#include "bench_islands.h"
#include "commands.h"
#include "reeve/bench/bench.h"
#include "reeve/scene/scene.h"

namespace reeve {
namespace {

void addOutput(CLI::App* cmd, bench::Output& out, bool plot) {
  cmd->add_option("--csv", out.csv, "Write the table as CSV (with the CPU, compiler, build type and date)");
  if (plot) cmd->add_option("--plot", out.plot, "Draw the results as a PNG (python3 with matplotlib)");
  cmd->add_flag("--force", out.force, "Overwrite existing output files");
}

CLI::Option* addSolvers(CLI::App* cmd, std::vector<std::string>& solvers) {
  return cmd->add_option("--solver", solvers, "Solvers to run (default: direct gauss-seidel)")
      ->check(CLI::IsMember({"direct", "gauss-seidel"}))
      ->delimiter(',');
}

// The shipped scenes: beside an installed program (PREFIX/bin/reeve ->
// PREFIX/share/reeve/scenes), else in the source tree it was built from.
std::string shippedScenesDir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path installed = exe.parent_path().parent_path() / "share" / "reeve" / "scenes";
    if (std::filesystem::is_directory(installed, ec)) return installed.string();
  }
  return REEVE_SCENES_DIR;
}

// Runs a sub-command, turning its errors into exit codes and one line.
int guarded(const std::function<int()>& run) {
  try {
    return run();
  } catch (const bench::OutputExists& e) {
    std::fprintf(stderr, "reeve bench: %s\n", e.what());
    return kExitWouldOverwrite;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "reeve bench: %s\n", e.what());
    return kExitBadScene;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "reeve bench: %s\n", e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "reeve bench: %s\n", e.what());
    return kExitFailure;
  }
}

}  // namespace

std::function<int()> addBenchCommand(CLI::App& app, CLI::App*& bench_cmd) {
  bench_cmd = app.add_subcommand(
      "bench",
      "Measure speed and accuracy: Table 1, the speed/accuracy trade, stability at the extremes, scaling, batches.");
  bench_cmd->require_subcommand(1);
  bench_cmd->footer(
      "Prints the CPU, compiler, build type, date and threads with every result; never passes or fails on a "
      "time. Absolute times depend on the machine (the paper's: a 3.5 GHz Core i7).");
  const std::string scenes = shippedScenesDir();

  auto table1 = std::make_shared<bench::Table1Options>();
  table1->scenes_dir = scenes;
  CLI::App* t1 = bench_cmd->add_subcommand(
      "table1", "The paper's Table 1 machines at the paper's settings and at each scene's own: ms/frame and speed-up.");
  addOutput(t1, table1->output, true);
  t1->add_option("--scenes", table1->scenes_dir, "Folder of the scene files")->capture_default_str();
  t1->add_option("--only", table1->only, "Machines to run (Simple, Servin, Pulley, Hand, Gym, Hilbert2, Hilbert3, Bow)")
      ->delimiter(',');
  addSolvers(t1, table1->solvers);
  t1->add_option("--repeats", table1->repeats, "Timed runs per row (default 5)")->check(CLI::PositiveNumber);
  t1->add_option("--frames", table1->frames, "Frames per run (default: the scene's duration)")
      ->check(CLI::PositiveNumber);

  auto trade = std::make_shared<bench::TradeOptions>();
  trade->scenes_dir = scenes;
  CLI::App* tr = bench_cmd->add_subcommand(
      "trade", "Error against closed forms vs ms/frame over substeps x iterations; the segmented rope alongside.");
  addOutput(tr, trade->output, true);
  tr->add_option("--scenes", trade->scenes_dir, "Folder of the scene files")->capture_default_str();
  tr->add_option("--only", trade->only,
                 "Cases to run (atwood_1_2, atwood_1_100, atwood_light_wheel, simple_equilibrium, gear_1_to_4, "
                 "spool, elastic, pinhole, block_and_tackle)")
      ->delimiter(',');
  tr->add_option("--substeps", trade->substeps, "Substep counts (default 1,2,5,10,20,50)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  tr->add_option("--iterations", trade->iterations, "Iteration counts (default 1,2,5,10,20)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  addSolvers(tr, trade->solvers);
  tr->add_option("--rope-segments", trade->rope_segments,
                 "Segmented-rope series on the Atwood cases (default 20,100; 0 for none)")
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber);
  tr->add_option("--repeats", trade->repeats, "Timed runs per point, at most (default 3)")->check(CLI::PositiveNumber);

  auto ex = std::make_shared<bench::ExtremesOptions>();
  CLI::App* exc = bench_cmd->add_subcommand(
      "extremes", "A stability map over masses, compliance, frame rate, substeps, iterations, jerks, loads and a light bead.");
  addOutput(exc, ex->output, true);
  exc->add_option("--machines", ex->machines, "atwood, simple, bead (default all three)")
      ->delimiter(',')
      ->check(CLI::IsMember({"atwood", "simple", "bead"}));
  exc->add_option("--conditions", ex->conditions, "Conditions to run, e.g. wheel_ratio=1e-6 (default all)")
      ->delimiter(',');
  exc->add_option("--rates", ex->rates_hz, "Frame rates, Hz (default 30,60,240,2000)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  exc->add_option("--substeps", ex->substeps, "Substep counts (default 1,10,100)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  exc->add_option("--iterations", ex->iterations, "Iteration counts (default 1,2,10,100)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  addSolvers(exc, ex->solvers);
  exc->add_option("--cell", ex->cell, "Run only this cell, by the key the report prints");

  auto sc = std::make_shared<bench::ScalingOptions>();
  CLI::App* scc = bench_cmd->add_subcommand(
      "scaling", "ms/frame, peak memory and statics error of both solvers as the cable joints grow, per topology.");
  addOutput(scc, sc->output, true);
  scc->add_option("--series", sc->series,
                  "Series to run (chain, tackle_hinged, tackle_rolling, tackle_stuck, star_rigid, star_compliant, islands, "
                  "islands_braked, wound, threaded; default all)")
      ->delimiter(',');
  addSolvers(scc, sc->solvers);
  scc->add_option("--budget", sc->budgets, "Budgets per frame, SUBSTEPSxITERATIONS (default 1x10,10x2)")
      ->delimiter(',');
  scc->add_option("--k", sc->k, "Counts K (default 4,16,64,256,1024,4096)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  scc->add_option("--frames", sc->frames, "Timed frames per cell (default 10)")->check(CLI::PositiveNumber);
  scc->add_option("--max-ms-per-frame", sc->max_ms_per_frame,
                  "Skip a K whose ms/frame, extrapolated from the K before, passes this (default 2000)")
      ->check(CLI::PositiveNumber);
  scc->add_option("--cell-timeout-s", sc->cell_timeout_s, "Kill a cell running longer than this, s (default 60)")
      ->check(CLI::PositiveNumber);

  auto peers = std::make_shared<bench::PeersOptions>();
  CLI::App* pe = bench_cmd->add_subcommand(
      "peers", bench::peersAvailable()
                   ? "The Atwood machine and chains of pulleys as MuJoCo tendons, next to Reeve."
                   : "(not built: needs Debian's libmujoco-dev when configuring) MuJoCo next to Reeve.");
  addOutput(pe, peers->output, false);
  pe->add_option("--repeats", peers->repeats, "Timed runs per row (default 25)")->check(CLI::PositiveNumber);

  auto batch = std::make_shared<BatchBenchOptions>();
  batch->scenes_dir = scenes;
  CLI::App* ba = bench_cmd->add_subcommand(
      "batch", "Copies of a machine stepped side by side (reeve.Batch) on 1 to N threads: ms per scene-frame, speed-up.");
  addOutput(ba, batch->output, false);
  ba->add_option("--scenes", batch->scenes_dir, "Folder of the scene files")->capture_default_str();
  ba->add_option("--only", batch->scenes, "Scene files to run, without .json (default atwood,hand,hilbert2,hilbert3)")
      ->delimiter(',');
  ba->add_option("--copies", batch->copies, "Copies of each scene (default 64)")->check(CLI::PositiveNumber);
  ba->add_option("--threads", batch->threads, "Thread counts (default 1, 2 and the cores)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  ba->add_option("--frames", batch->frames, "Timed frames per run (default 30)")->check(CLI::PositiveNumber);
  ba->add_option("--repeats", batch->repeats, "Timed runs per row; the median is reported (default 3)")
      ->check(CLI::PositiveNumber);

  auto islands = std::make_shared<IslandsBenchOptions>();
  CLI::App* is = bench_cmd->add_subcommand(
      "islands", "One scene of separate Atwood machines, its islands solved on 1 to N threads: ms a frame, speed-up.");
  addOutput(is, islands->output, false);
  is->add_option("--machines", islands->machines, "Atwood machines in the scene (default 64)")->check(CLI::PositiveNumber);
  is->add_option("--threads", islands->threads, "Thread counts (default 1, 2 and the cores)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  is->add_option("--solver", islands->solvers, "Solvers to run (default: direct gauss-seidel)")
      ->check(CLI::IsMember({"direct", "gauss-seidel"}));
  is->add_option("--substeps", islands->substeps, "Substeps a frame (default 10)")->check(CLI::PositiveNumber);
  is->add_option("--iterations", islands->iterations, "Iterations a substep (default 2)")->check(CLI::PositiveNumber);
  is->add_option("--frames", islands->frames, "Timed frames per run (default 60)")->check(CLI::PositiveNumber);
  is->add_option("--repeats", islands->repeats, "Timed runs per row; the median is reported (default 5)")
      ->check(CLI::PositiveNumber);

  return [=]() {
    // Zero rope segments means none.
    std::erase(trade->rope_segments, 0);
    if (*t1) return guarded([&] { return bench::table1(*table1); });
    if (*tr) return guarded([&] { return bench::trade(*trade); });
    if (*exc) return guarded([&] { return bench::extremes(*ex); });
    if (*scc) return guarded([&] { return bench::scaling(*sc); });
    if (*ba) return guarded([&] { return benchBatch(*batch); });
    if (*is) return guarded([&] { return benchIslands(*islands); });
    return guarded([&] { return bench::peers(*peers); });
  };
}

}  // namespace reeve
