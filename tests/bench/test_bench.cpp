// `reeve bench` as a user runs it, on tiny grids: the errors it reports
// equal those computed here from runs of the same machines, a setting
// known to fail is reported unstable with the command that reproduces it,
// and its outputs follow the rules of every reeve output.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_threads.h"
#include "reeve/machines/closed_forms.h"
#include "reeve/machines/machines.h"
#include "reeve/machines/probe.h"
#include "reeve/scene/scene.h"
#include "temp_dir.h"

namespace reeve::test_bench {
namespace {

namespace fs = std::filesystem;

struct Result {
  int code;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

Result reeve(const test::TempDir& dir, const std::string& args) {
  const fs::path out = dir.path() / "stdout.txt", err = dir.path() / "stderr.txt";
  const std::string cmd = std::string("REEVE_TRAP_FP=1 ") + REEVE_BINARY + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

// A CSV (RFC 4180 quoting) as rows of column -> cell.
std::vector<std::map<std::string, std::string>> readCsv(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> lines;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        cells.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        cells.emplace_back();
      } else {
        cells.back() += c;
      }
    }
    lines.push_back(cells);
  }
  std::vector<std::map<std::string, std::string>> rows;
  for (std::size_t r = 1; r < lines.size(); ++r) {
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < lines[0].size() && c < lines[r].size(); ++c) row[lines[0][c]] = lines[r][c];
    rows.push_back(row);
  }
  return rows;
}

// "a=1;b=2" -> {a: 1, b: 2}
std::map<std::string, double> parts(const std::string& detail) {
  std::map<std::string, double> m;
  std::stringstream s(detail);
  for (std::string item; std::getline(s, item, ';');) {
    const auto eq = item.find('=');
    m[item.substr(0, eq)] = std::stod(item.substr(eq + 1));
  }
  return m;
}

double relative(double got, double want) { return std::abs(got - want) / std::abs(want); }

// Runs `reeve bench ARGS --csv FILE` and returns the CSV's rows (none, and
// a failure, when it exits non-zero); `out` gets what it printed.
std::vector<std::map<std::string, std::string>> benchRows(const test::TempDir& dir, const std::string& args,
                                                          std::string* out = nullptr) {
  const fs::path csv = dir.path() / "bench.csv";
  const Result r = reeve(dir, "bench " + args + " --csv " + csv.string());
  EXPECT_EQ(r.code, 0) << r.err;
  if (out) *out = r.out;
  return r.code == 0 ? readCsv(csv) : std::vector<std::map<std::string, std::string>>{};
}

TEST(BenchTrade, ReportsTheAtwoodAndSpoolErrorsOfADirectRun) {
  test::TempDir dir;
  const auto rows = benchRows(
      dir, "trade --only atwood_1_2,spool --substeps 1,10 --iterations 2 --solver direct --rope-segments 0 --repeats 1");
  ASSERT_EQ(rows.size(), 4u);
  int checked = 0;
  for (const auto& row : rows) {
    const int substeps = std::stoi(row.at("substeps"));
    EXPECT_EQ(row.at("iterations"), "2");
    EXPECT_EQ(row.at("series"), "reeve direct");
    EXPECT_FALSE(row.at("cpu").empty());
    EXPECT_FALSE(row.at("build_type").empty());
    const auto got = parts(row.at("detail"));
    // The same machine, run here: 1:2 kg over a 2 kg wheel, g = 9.81
    // (scenes/atwood.json), or 1 kg unwinding a 2 kg spool; 0.5 s.
    const bool atwood = row.at("case") == "atwood_1_2";
    Scene s = loadScene(fs::path(REEVE_SCENES_DIR) / (atwood ? "atwood.json" : "spool.json"));
    s.world->settings().substeps = substeps;
    s.world->settings().iterations = 2;
    s.world->settings().solver = SolverKind::Direct;
    const BodyId falling = *s.world->findBody(atwood ? "heavy" : "weight");
    const double y0 = s.world->body(falling).x.y(), g = 9.81, T = 0.5;
    for (int f = 0; f < 30; ++f) s.world->step(1.0 / 60.0);
    const double a = 2.0 * (y0 - s.world->body(falling).x.y()) / (T * T);
    std::map<std::string, double> want;
    if (atwood) {
      const machines::AtwoodMotion m = machines::atwoodMotion(1.0, 2.0, 2.0, g);
      want = {{"acceleration", relative(a, m.acceleration)},
              {"tension_light", relative(s.cables->tension(0, 0), m.tension_light)},
              {"tension_heavy", relative(s.cables->tension(0, 1), m.tension_heavy)}};
    } else {
      want = {{"acceleration", relative(a, g / 2.0)}, {"tension", relative(s.cables->tension(0, 0), g / 2.0)}};
    }
    ASSERT_EQ(got.size(), want.size()) << row.at("detail");
    double worst = 0.0;
    for (const auto& [name, value] : want) {
      ASSERT_TRUE(got.count(name)) << name;
      EXPECT_NEAR(got.at(name), value, 1e-5 * value + 1e-15) << row.at("case") << " " << name;
      worst = std::max(worst, value);
    }
    EXPECT_NEAR(std::stod(row.at("error")), worst, 1e-3 * worst);
    // Symplectic Euler puts the position ahead by h / T of the fall: the
    // acceleration error is 1 / (30 substeps) at 1, 1 / 300 at 10.
    if (atwood) {
      EXPECT_NEAR(got.at("acceleration"), 1.0 / (30.0 * substeps), 1e-3 / substeps);
    }
    ++checked;
  }
  EXPECT_EQ(checked, 4);
  // Ten substeps err less than one, so that point is always on the front.
  // Whether one substep is too depends on the clock (it is dominated if the
  // timer saw ten substeps as no dearer): the column must follow the
  // printed cost, never assert it.
  for (const char* name : {"atwood_1_2", "spool"}) {
    std::map<int, std::map<std::string, std::string>> bySubsteps;
    for (const auto& row : rows)
      if (row.at("case") == name) bySubsteps[std::stoi(row.at("substeps"))] = row;
    ASSERT_EQ(bySubsteps.size(), 2u) << name;
    const auto& one = bySubsteps.at(1);
    const auto& ten = bySubsteps.at(10);
    EXPECT_LT(std::stod(ten.at("error")), std::stod(one.at("error"))) << name;
    EXPECT_EQ(ten.at("pareto"), "1") << name;
    const double msOne = std::stod(one.at("ms_per_frame")), msTen = std::stod(ten.at("ms_per_frame"));
    if (msOne != msTen) {
      EXPECT_EQ(one.at("pareto"), msOne < msTen ? "1" : "0") << name << " " << msOne << " vs " << msTen;
    }
  }
}

TEST(BenchTrade, RunsReeveAtTheRopesCostAndItsErrorIsTheIntegratorsThere) {
  // The grid's Reeve points cost far less than the rope's; Reeve is run
  // again at as many substeps as a rope point's ms/frame buys, and compared
  // there. Its acceleration error is still symplectic Euler's 1 / (30 n).
  test::TempDir dir;
  std::string out;
  const auto rows = benchRows(
      dir, "trade --only atwood_1_2 --substeps 1,2 --iterations 1 --solver direct --rope-segments 20 --repeats 1",
      &out);
  int matched = 0;
  for (const auto& row : rows) {
    if (row.at("series") != "reeve direct at the ropes' cost") continue;
    const int substeps = std::stoi(row.at("substeps"));
    EXPECT_GT(substeps, 2);
    EXPECT_EQ(row.at("iterations"), "1");
    EXPECT_NEAR(parts(row.at("detail")).at("acceleration"), 1.0 / (30.0 * substeps), 1e-3 / substeps);
    ++matched;
  }
  EXPECT_GE(matched, 1);
  EXPECT_NE(out.find("#   atwood_1_2           rope20 direct"), std::string::npos) << out;
}

TEST(BenchExtremes, ReportsAStableDirectCellAsMeasuredHereAndTheKnownFailureAsUnstable) {
  test::TempDir dir;
  std::string out;
  const auto rows = benchRows(dir,
                              "extremes --machines atwood --conditions wheel_ratio=1e-6 --rates 30 --substeps 1 "
                              "--iterations 10 --solver direct,gauss-seidel",
                              &out);
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& row : rows) {
    if (row.at("solver") == "direct") {
      // The same cell run here: 1 and 2 kg over a 1 mg wheel, g = 10, 1 s at
      // 30 Hz, one substep of 10 iterations.
      machines::AtwoodSpec spec;
      spec.light_kg = 1.0;
      spec.heavy_kg = 2.0;
      spec.wheel_kg = 1e-6;
      spec.drop_m = 6.0;
      spec.budget = {1, 10, SolverKind::Direct};
      machines::Atwood m = machines::atwood(spec);
      double stretch = 0.0;
      for (int f = 0; f < 30; ++f) {
        m.scene.world->step(1.0 / 30.0);
        stretch = std::max(stretch, machines::maxStretch(*m.scene.cables, m.cable));
      }
      const machines::AtwoodMotion want = machines::atwoodMotion(1.0, 2.0, 1e-6, 10.0);
      const double tension_error = std::max(relative(m.scene.cables->tension(m.cable, 0), want.tension_light),
                                            relative(m.scene.cables->tension(m.cable, 1), want.tension_heavy));
      EXPECT_EQ(row.at("stable"), "1") << row.at("cause");
      EXPECT_NEAR(std::stod(row.at("tension_error")), tension_error, 1e-2 * tension_error + 1e-12);
      EXPECT_NEAR(std::stod(row.at("peak_stretch")), stretch, 1e-2 * stretch + 1e-15);
      EXPECT_LT(tension_error, 1e-6);
    } else {
      // Gauss-Seidel with a wheel 1e-6 of the load: the cable pulls the
      // wheel off its axle (README, solver methods); the span stretches.
      EXPECT_EQ(row.at("stable"), "0");
      EXPECT_GT(std::stod(row.at("peak_stretch")), 0.01);
      EXPECT_NE(row.at("cause").find("stretch"), std::string::npos) << row.at("cause");
    }
  }
  EXPECT_NE(out.find("direct: 1 of 1 cells stable"), std::string::npos) << out;
  EXPECT_NE(out.find("reeve bench extremes --cell 'atwood/wheel_ratio=1e-6/30Hz/1x10/gauss-seidel'"),
            std::string::npos)
      << out;
}

TEST(BenchExtremes, ListsTheCellsWhoseErrorGrowsWithIterations) {
  // A 100 m/s jerk at one substep of 30 Hz (issue 29, item 3): the wheel
  // turns radians in one solve, and the direct solver's answer is the
  // momentum-conserving one at 1, 2 and 10 iterations (before held rolling
  // ends: exact at 1, off at 2 and more); Gauss-Seidel's now comes nearer
  // it with each (it was worse at 2 than at 1 until its rotor ends read
  // their turn from the rotor: DESIGN, twenty-first session). A wheel 1e-3
  // of the load, whose sweeps do not converge, is worse at 10 than at 2
  // under Gauss-Seidel, which the check must list.
  test::TempDir dir;
  const Result r = reeve(dir,
                         "bench extremes --machines atwood --conditions jerk_slack=1_speed=100,wheel_ratio=0.001 "
                         "--rates 30 --substeps 1 --iterations 1,2,10 --solver direct,gauss-seidel");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("direct: 6 of 6 cells stable"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cells whose error grows with iterations at fixed substeps"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("/direct: error"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("jerk_slack=1_speed=100/30Hz/1x2/gauss-seidel: error"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("jerk_slack=1_speed=100/30Hz/1x10/gauss-seidel: error"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("atwood/wheel_ratio=0.001/30Hz/1x10/gauss-seidel: error"), std::string::npos) << r.out;
}

TEST(BenchExtremes, AMilligramsBeadAtOneIterationOfThirtyAndSixtyHertzMakesNoEnergy) {
  // The map's last unstable direct cells: the bead 1e-3 of its load, bent
  // 5 or 30 cm, one substep of one iteration. Not placed, its sideways
  // mode ((omega h)^2 = 22 at 30 Hz under the load's 10 N) was left 5.5 mm
  // long by the one Newton step, and the next frames gave back 32 to 109 %
  // of the map's energy scale (or a span 1.5 % long); Gauss-Seidel's spans
  // stretched 3.5 to 4.7 times. Placed (light_bodies.h), no energy may
  // grow, and the spans stay within 1e-4, a hundredth of the map's limit.
  test::TempDir dir;
  const fs::path csv = dir.path() / "bead.csv";
  const Result r = reeve(dir,
                         "bench extremes --machines bead --conditions bead_ratio=0.001_offset=0.05,bead_ratio=0.001_offset=0.3 "
                         "--rates 30,60 --substeps 1 --iterations 1 --solver direct,gauss-seidel --csv " + csv.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = readCsv(csv);
  ASSERT_EQ(rows.size(), 8u);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.at("condition") + " " + row.at("rate_hz") + " Hz " + row.at("solver"));
    EXPECT_EQ(row.at("stable"), "1");
    EXPECT_LE(std::stod(row.at("energy_growth")), 1e-9);
    EXPECT_LT(std::stod(row.at("peak_stretch")), 1e-4);
  }
}

TEST(BenchExtremes, ALightBeadBetweenTwoCablesIsStableAtTwoIterationsAndAtTen) {
  // The bead 1e-6 and 1e-3 of its 1 kg load, the chain starting bent 0.3
  // m. At 10 x 2 the direct solver's Newton steps did not settle the 1e-6
  // bead's tightrope as the chain lined up: its spans ended millimetres
  // long, and taking that back in one substep threw the load up (energy
  // grew 107 % of the map's scale); Gauss-Seidel's sweeps moved the bead,
  // not the load, and its spans stretched past 1 %. Taken as massless
  // (engine/src/light_bodies.h), it hangs within 1e-7 of its cables' lengths under
  // both. So does the 1e-3 bead since it is taken so too (kMasslessShare
  // 2e-3): before, Gauss-Seidel's sweeps stretched its spans 1.1 to 247 %
  // here, and the direct solver's by 2.4e-3 at 1 x 2.
  test::TempDir dir;
  const fs::path csv = dir.path() / "bead.csv";
  const Result r = reeve(dir,
                         "bench extremes --machines bead --conditions bead_ratio=1e-6_offset=0.3,bead_ratio=0.001_offset=0.3 "
                         "--rates 60 --substeps 1,10 --iterations 2,10 --solver direct,gauss-seidel --csv " + csv.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("direct: 8 of 8 cells stable"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("gauss-seidel: 8 of 8 cells stable"), std::string::npos) << r.out;
  const auto rows = readCsv(csv);
  ASSERT_EQ(rows.size(), 16u);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.at("condition") + " " + row.at("substeps") + "x" + row.at("iterations") + " " + row.at("solver"));
    EXPECT_EQ(row.at("tension_error"), "");  // no closed form for the swing
    EXPECT_LE(std::stod(row.at("energy_growth")), 1e-9);
    EXPECT_EQ(row.at("stable"), "1");
    // Strain: the placed beads' spans within 1e-7 at 2 iterations too.
    EXPECT_LT(std::stod(row.at("peak_stretch")), 1e-7);
  }
}

TEST(BenchExtremes, TheReproduceCommandRunsThatOneCell) {
  test::TempDir dir;
  const Result r = reeve(dir, "bench extremes --cell 'atwood/load_N=1e5/30Hz/1x1/gauss-seidel'");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("gauss-seidel: 0 of 1 cells stable"), std::string::npos) << r.out;
  const Result bad = reeve(dir, "bench extremes --cell 'atwood/nope/30Hz/1x1/direct'");
  EXPECT_EQ(bad.code, 64);
  EXPECT_NE(bad.err.find("no cell 'atwood/nope/30Hz/1x1/direct'"), std::string::npos) << bad.err;
}

TEST(BenchTable1, ReportsTheSceneTheEnvironmentAndTheSpeedUpItMeasured) {
  test::TempDir dir;
  std::string out;
  const auto rows = benchRows(dir, "table1 --only Simple --solver direct --repeats 1 --frames 10", &out);
  for (const char* key : {"# cpu: ", "# compiler: ", "# build type: ", "# date: ", "# threads: "})
    EXPECT_NE(out.find(key), std::string::npos) << key;
  ASSERT_EQ(rows.size(), 3u);  // paper 1 x 1, paper 1 x 10, scene default 10 x 2
  // The split of a substep's cost, once per machine and solver (its first
  // row): a number. Not its sign: it is the difference of two timings, 1
  // and 10 iterations of 10 frames of Simple (tens of us), which the load
  // of a full suite beside it can turn round (it read -3140 ns once).
  EXPECT_TRUE(std::isfinite(std::stod(rows[0].at("marginal_ns_per_joint_iteration"))));
  EXPECT_NE(rows[0].at("fixed_us_per_substep"), "");
  EXPECT_EQ(rows[1].at("fixed_us_per_substep"), "");
  // Each row's run watched by the energy ledger, off the clock: Simple
  // creates none (test_energy_scenes.cpp at four budgets).
  EXPECT_NE(out.find("direct: energy created (the ledger's watch): none"), std::string::npos) << out;
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("energy_created_J"), "0");
    EXPECT_EQ(row.at("joints"), "4");
    EXPECT_EQ(row.at("frames"), "10");
    const double min = std::stod(row.at("min_ms")), median = std::stod(row.at("median_ms"));
    EXPECT_GT(median, 0.0);
    EXPECT_LE(min, median);
    if (row.at("setting") == "paper") {
      const double paper = std::stod(row.at("paper_ms"));
      EXPECT_EQ(paper, row.at("iterations") == "1" ? 0.012 : 0.036);
      EXPECT_NEAR(std::stod(row.at("speedup")), paper / median, 1e-2 * paper / median);
    } else {
      EXPECT_EQ(row.at("substeps") + "x" + row.at("iterations"), "10x2");
      EXPECT_EQ(row.at("speedup"), "");
    }
  }
}

// The machines of `reeve bench scaling` at K = 4 stand still with every
// span at its closed-form tension (machines.h), solved directly at 10 x 2.
void expectStatics(const machines::StaticMachine& m, const std::string& name, double tolerance = 1e-6) {
  for (int f = 0; f < 5; ++f) m.scene.world->step(1.0 / 60.0);
  ASSERT_FALSE(m.scene.world->firstNonFinite()) << name;
  const CableSystem& cables = *m.scene.cables;
  int spans = 0;
  for (int c = 0; c < static_cast<int>(cables.cables().size()); ++c)
    for (int j = 0; j < static_cast<int>(cables.cables()[c].joints.size()); ++j) {
      ASSERT_TRUE(cables.jointEnabled(c, j)) << name << " cable " << c << " span " << j;
      EXPECT_LT(relative(cables.tension(c, j), m.tension_N), tolerance) << name << " cable " << c << " span " << j;
      ++spans;
    }
  EXPECT_GT(spans, 0) << name;
}

TEST(ScalingMachines, MeetTheirClosedFormStaticsAtFourWithTheDirectSolver) {
  machines::ScalingSpec spec;
  spec.count = 4;
  spec.load_kg = 1.5;
  spec.budget = {10, 2, SolverKind::Direct};
  expectStatics(machines::scalingChain(spec), "chain");
  expectStatics(machines::tackleHinged(spec), "tackle_hinged");
  expectStatics(machines::tackleRolling(spec), "tackle_rolling");
  expectStatics(machines::tackleRolling(spec, false), "tackle_stuck");
  expectStatics(machines::islands(spec), "islands");
  expectStatics(machines::islands(spec, true), "islands_braked");  // each brake holds with no torque
  expectStatics(machines::wound(spec), "wound");
  expectStatics(machines::threaded(spec), "threaded");
  EXPECT_DOUBLE_EQ(machines::tackleHinged(spec).tension_N, 15.0);  // W / K: the block weighs K m
}

// A rope threaded through 512 bars (2048 spans, 3.9 km): its tie point
// jammed at the first bar's hole 1.9 m away at the first substep while a
// jam's reach was 1e-3 of the cable's whole length (3.9 m), and the first
// and last spans read no tension. Both solvers hold every fall at m g.
TEST(ScalingMachines, ARopeThreadedThroughManyBarsHoldsEveryFallAtItsLoad) {
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel}) {
    machines::ScalingSpec spec;
    spec.count = 512;
    spec.budget = {1, 10, solver};
    expectStatics(machines::threaded(spec), solver == SolverKind::Direct ? "threaded direct" : "threaded gs", 1e-9);
  }
}

// The compliant star starts in its equilibrium, yet its first substep
// leaves it off by an error that falls as h^2 (1.4e-5 at 10 substeps a
// frame, 1.1e-3 at 1): at 100 substeps it is within 1e-6.
TEST(ScalingMachines, TheCompliantStarHoldsItsConeTensionAsTheSubstepShrinks) {
  machines::ScalingSpec spec;
  spec.count = 4;
  spec.budget = {10, 2, SolverKind::Direct};
  expectStatics(machines::star(spec, true), "star_compliant 10 x 2", 1e-4);
  spec.budget.substeps = 100;
  expectStatics(machines::star(spec, true), "star_compliant 100 x 2", 1e-6);
}

// Four rigid cables hold the effector redundantly: the direct solver need
// not share the load evenly (it puts it on one opposite pair), but the
// cables' pull balances the weight, and no cable pushes.
TEST(ScalingMachines, TheRigidStarCarriesTheEffectorsWeight) {
  machines::ScalingSpec spec;
  spec.count = 4;
  spec.budget = {10, 2, SolverKind::Direct};
  const machines::StaticMachine m = machines::star(spec, false);
  EXPECT_DOUBLE_EQ(m.tension_N, 10.0 / std::cos(std::numbers::pi / 6.0));  // m g / cos theta
  for (int f = 0; f < 5; ++f) m.scene.world->step(1.0 / 60.0);
  // Redundant (four cables to one point), each carries its share: the
  // limit of equal elastic cables (DESIGN.md, "One solver for every
  // topology"). Before hubs one opposite pair carried it all.
  for (int c = 0; c < 4; ++c) EXPECT_LT(relative(m.scene.cables->tension(c, 0), m.tension_N), 1e-5) << c;
}

TEST(ScalingMachines, OddFallCountsBalanceToo) {
  machines::ScalingSpec spec;
  spec.count = 5;
  spec.budget = {10, 2, SolverKind::Direct};
  expectStatics(machines::tackleHinged(spec), "tackle_hinged");
  expectStatics(machines::tackleRolling(spec), "tackle_rolling");
  expectStatics(machines::tackleRolling(spec, false), "tackle_stuck");
}

TEST(BenchScaling, RunsTheChainAndPrintsItsTable) {
  test::TempDir dir;
  const Result r = reeve(dir, "bench scaling --k 4 --frames 1 --series chain");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("# cpu:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("statics_error"), std::string::npos) << r.out;
  for (const char* cell : {"chain  ", "direct", "gauss-seidel", "1x10", "10x2", "fitted exponent"})
    EXPECT_NE(r.out.find(cell), std::string::npos) << cell << "\n" << r.out;
  EXPECT_EQ(reeve(dir, "bench scaling --series nope").code, 64);
  EXPECT_EQ(reeve(dir, "bench scaling --budget 10").code, 64);
}

TEST(BenchBatch, StepsCopiesOnOneAndMoreThreadsAndPrintsTheSpeedUp) {
  test::TempDir dir;
  const fs::path csv = dir.path() / "batch.csv";
  const Result r =
      reeve(dir, "bench batch --only atwood --copies 3 --threads 2 --frames 2 --repeats 1 --csv " + csv.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("# threads: 2 used"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ms_per_scene_frame  speedup  ideal_speedup  busy_speedup"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("1.00"), std::string::npos) << r.out;  // 1 thread, the baseline, always run
  const std::string table = slurp(csv);
  EXPECT_NE(table.find("atwood,3,1,2,"), std::string::npos) << table;
  EXPECT_NE(table.find("atwood,3,2,2,"), std::string::npos) << table;
  // One thread was timed on each core: the baseline is the fastest, and
  // two threads can at most reach the two fastest cores' rates summed.
  const std::string head = "# atwood, one thread on each core:";
  const std::size_t at = r.out.find(head);
  ASSERT_NE(at, std::string::npos) << r.out;
  std::vector<double> per_core;
  std::istringstream cores(r.out.substr(at + head.size(), r.out.find('\n', at) - at - head.size()));
  for (std::string cell; std::getline(cores, cell, ',');) per_core.push_back(std::stod(cell));
  ASSERT_GE(per_core.size(), 1u);
  std::sort(per_core.begin(), per_core.end());
  const double ideal = 1.0 + (per_core.size() > 1 ? per_core[0] / per_core[1] : 0.0);
  std::map<std::string, std::string> one, two;
  std::istringstream rows(table);
  for (std::string line; std::getline(rows, line);) {
    if (line.rfind("atwood,3,", 0) != 0) continue;
    std::vector<std::string> cells;
    std::istringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    ASSERT_GE(cells.size(), 8u) << line;
    (cells[2] == "1" ? one : two) = {{"ms", cells[4]}, {"speedup", cells[5]}, {"ideal", cells[6]}, {"busy", cells[7]}};
  }
  EXPECT_NEAR(std::stod(one.at("ms")), per_core[0], 1e-3 * per_core[0]);
  EXPECT_EQ(one.at("ideal"), "1.00");
  EXPECT_EQ(one.at("busy"), "1.00");  // one thread: no other core busy
  EXPECT_NEAR(std::stod(two.at("ideal")), ideal, 0.006) << table;
  EXPECT_GT(std::stod(two.at("busy")), 0.0) << table;  // timed (its arithmetic: BenchThreads below)
  EXPECT_EQ(reeve(dir, "bench batch --only nope").code, 64);
  EXPECT_EQ(reeve(dir, "bench batch --copies 0").code, 64);
}

TEST(BenchThreads, EachThreadRunsOnItsOwnCoreAndTheirRatesAddUp) {
  // timeOnCoresAtOnce: one thread pinned to each core given, all timed
  // together (the ceiling busy cores leave: reeve bench batch, islands).
  const std::vector<int> cores = allowedCores();
  ASSERT_FALSE(cores.empty());
  std::mutex mutex;
  std::vector<int> ran_on;
  const std::vector<double> ms = timeOnCoresAtOnce(
      [&] {
        const int cpu = sched_getcpu();
        const std::lock_guard lock(mutex);
        ran_on.push_back(cpu);
        return 1.0 + cpu;
      },
      cores);
  ASSERT_EQ(ms.size(), cores.size());
  for (std::size_t i = 0; i < cores.size(); ++i) EXPECT_EQ(ms[i], 1.0 + cores[i]) << i;  // each on its core
  std::sort(ran_on.begin(), ran_on.end());
  EXPECT_EQ(ran_on, cores);
  // A run that throws: the error reaches the caller, after every thread joined.
  EXPECT_THROW(timeOnCoresAtOnce([]() -> double { throw std::runtime_error("boom"); }, cores), std::runtime_error);
  // The fastest cores by one thread's time, and the busy rates summed: two
  // threads at 1 and 2 ms against one alone at 1 ms run 1.5 times its rate.
  EXPECT_EQ(fastestCores({3, 5, 7}, {2.0, 1.0, 1.5}, 2), (std::vector<int>{5, 7}));
  EXPECT_EQ(fastestCores({3, 5, 7}, {2.0, 1.0, 1.5}, 9), (std::vector<int>{5, 7, 3}));
  EXPECT_EQ(fastestCores({3, 5}, {1.0}, 2), (std::vector<int>{-1, -1}));  // not timed core by core: unpinned
  EXPECT_EQ(timeOnCoresAtOnce([] { return 2.0; }, {-1, -1}), (std::vector<double>{2.0, 2.0}));
  EXPECT_DOUBLE_EQ(busySpeedup(1.0, {1.0, 2.0}), 1.5);
  EXPECT_DOUBLE_EQ(busySpeedup(1.0, {1.25, 1.25}), 1.6);
  EXPECT_EQ(median({3.0, 1.0, 2.0}), 2.0);  // of the timed runs
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 3.0);
}

TEST(BenchOutputs, RefusesToOverwriteAndRejectsUnknownNames) {
  test::TempDir dir;
  const fs::path csv = dir.path() / "kept.csv";
  std::ofstream(csv) << "mine\n";
  const Result r = reeve(dir, "bench extremes --cell 'atwood/load_ratio=1/30Hz/1x1/direct' --csv " + csv.string());
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("exists; pass --force"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(csv), "mine\n");
  EXPECT_EQ(reeve(dir, "bench trade --only nope").code, 64);
  EXPECT_EQ(reeve(dir, "bench table1 --only Nope").code, 64);
  EXPECT_EQ(reeve(dir, "bench extremes --conditions nope").code, 64);
  EXPECT_EQ(reeve(dir, "bench trade --solver jacobi").code, 64);
}

TEST(BenchOutputs, PlotsAPng) {
  test::TempDir dir;
  const fs::path png = dir.path() / "map.png";
  const Result r = reeve(dir, "bench extremes --machines atwood --conditions load_ratio=1,wheel_ratio=1e-6 --rates 30 "
                              "--substeps 1 --iterations 1 --plot " + png.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string bytes = slurp(png);
  ASSERT_GT(bytes.size(), 1000u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  for (const auto& entry : fs::directory_iterator(dir.path()))  // no partial files left
    EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace reeve::test_bench
