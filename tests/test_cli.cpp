// The `reeve` program as a user runs it: outputs, refusals to overwrite,
// and exit codes for bad scenes and missing tools.
#include <gtest/gtest.h>
#include <png.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <filesystem>
#include <iterator>
#include <regex>
#include <utility>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_fixture.h"

namespace {

namespace fs = std::filesystem;
using test::Cli;
using test::reeve;
using test::Result;

// Pixels of an RGB(A) PNG, read with libpng; empty on failure.
std::vector<unsigned char> readPng(const std::string& file, int& w, int& h) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, file.c_str())) return {};
  image.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> px(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, px.data(), 0, nullptr)) return {};
  w = static_cast<int>(image.width);
  h = static_cast<int>(image.height);
  return px;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
  return cells;
}

TEST_F(Cli, RunOfTheDefaultSceneWritesFramesAndCsv) {
  const Result r = reeve("run --frames 3 --png " + path("frames") + " --csv " + path("out.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find(path("out.csv")), std::string::npos) << "says where the CSV went";
  for (int f = 0; f < 3; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.png", f);
    int w = 0, h = 0;
    const auto px = readPng(path("frames/") + name, w, h);
    ASSERT_FALSE(px.empty()) << name << " is not a readable PNG";
    EXPECT_EQ(w, 1280);
    EXPECT_EQ(h, 720);
    std::set<int> colours;
    for (size_t i = 0; i + 2 < px.size(); i += 3 * 97) colours.insert(px[i] << 16 | px[i + 1] << 8 | px[i + 2]);
    EXPECT_GT(colours.size(), 20u) << name << " looks blank";
  }
  EXPECT_FALSE(fs::exists(path("frames/frame_00003.png")));

  std::ifstream csv(path("out.csv"));
  std::string header, line;
  std::getline(csv, header);
  const auto cols = split(header);
  const std::vector<std::string> expected_start = {"time_s", "left_top.x_m", "left_top.y_m", "left_top.z_m"};
  ASSERT_GE(cols.size(), 1 + 3 * 3 + 3 * 4u);
  EXPECT_EQ(cols[0], "time_s");
  for (const char* col : {"left_bottom.y_m", "right.z_m", "wheel_left.x_m", "cable.0.tension_N",
                          "cable.3.rest_length_m", "cable.3.length_m"})
    EXPECT_NE(std::find(cols.begin(), cols.end(), col), cols.end()) << col;
  int rows = 0;
  while (std::getline(csv, line)) {
    if (rows == 0) {
      EXPECT_EQ(split(line)[0], "0") << "the first row is the scene as loaded";
    }
    ++rows;
    EXPECT_EQ(split(line).size(), cols.size());
  }
  EXPECT_EQ(rows, 1 + 3) << "t = 0 and a row per frame";
}

TEST_F(Cli, TheBrakedLevel3HilbertMachineIsOneCommandAwayAndRunsAtThePapersBudget) {
  // The paper's Fig. 18 machine: 512 wheels of 10 g, the last a drum paying
  // out against a 10 N m brake (DESIGN, "A cap the last solve ended at...").
  // Written, it says how; run at its 1 x 10, every span pulls the brake's
  // 40 N (0.25 m drums; up to 3.5 % more out of plane).
  Result r = reeve("generate hilbert --level 3 --end brake --wheel-kg 0.01 -o " + path("braked.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string scene = test::slurp(path("braked.json"));
  EXPECT_NE(scene.find("reeve generate hilbert --level 3 --end brake --wheel-kg 0.01"), std::string::npos);
  EXPECT_EQ(scene.find("\"load\""), std::string::npos);
  r = reeve("run " + path("braked.json") + " --frames 120 --csv " + path("braked.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream csv(path("braked.csv"));
  std::string header, row, last;
  std::getline(csv, header);
  while (std::getline(csv, row)) last = row;
  const std::vector<std::string> names = split(header), values = split(last);
  ASSERT_EQ(names.size(), values.size());
  int spans = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i].rfind("rope.", 0) != 0 || names[i].find(".tension_N") == std::string::npos) continue;
    ++spans;
    EXPECT_GT(std::stod(values[i]), 40.0 * (1.0 - 1e-6)) << names[i];
    EXPECT_LT(std::stod(values[i]), 40.0 * 1.04) << names[i];
  }
  EXPECT_EQ(spans, 511);
  EXPECT_EQ(reeve("generate hilbert --level 3 --end rope -o " + path("x.json")).code, 64);
  EXPECT_EQ(reeve("generate hilbert --wheel-kg 0 -o " + path("x.json")).code, 64);
}

TEST_F(Cli, EventsAreLoggedAsJsonLinesAndStoredCableIsInTheCsv) {
  // The pendulum with a peg meets the peg near 0.74 s and leaves it near 1.9 s.
  const Result r = reeve(std::string("run ") + REEVE_SCENES_DIR + "/merge_split.json --frames 150 --events " +
                         path("events.jsonl") + " --csv " + path("peg.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream events(path("events.jsonl"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(events, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[0].find(R"("event":"split")"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find(R"("cable":"string")"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find(R"("link":1)"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find(R"("event":"merge")"), std::string::npos) << lines[1];
  std::ifstream csv(path("peg.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find("string.link1.stored_m"), std::string::npos) << header;
}

TEST_F(Cli, ThreadsChangeNoDigitOfTheCsvAndAreChecked) {
  // gym.json's machines: the CSV on 2 threads is the CSV on 1, every digit.
  const std::string scene = std::string(REEVE_SCENES_DIR) + "/gym.json";
  ASSERT_EQ(reeve("run " + scene + " --frames 30 --threads 1 --csv " + path("one.csv")).code, 0);
  ASSERT_EQ(reeve("run " + scene + " --frames 30 --threads 2 --csv " + path("two.csv")).code, 0);
  std::ifstream one(path("one.csv")), two(path("two.csv"));
  const std::string a((std::istreambuf_iterator<char>(one)), {}), b((std::istreambuf_iterator<char>(two)), {});
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, b);
  const Result zero = reeve("run --frames 1 --threads 0");
  EXPECT_EQ(zero.code, 64);
  EXPECT_NE(zero.err.find("--threads"), std::string::npos) << zero.err;
  const Result view = reeve("view --threads 1025");
  EXPECT_EQ(view.code, 64);
  EXPECT_NE(view.err.find("--threads"), std::string::npos) << view.err;
}

TEST_F(Cli, ExistingOutputsAreNotOverwrittenWithoutForce) {
  const std::string csv = write("keep.csv", "my data\n");
  const Result r = reeve("run --frames 2 --csv " + csv);
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("--force"), std::string::npos) << r.err;
  std::ifstream f(csv);
  std::string content((std::istreambuf_iterator<char>(f)), {});
  EXPECT_EQ(content, "my data\n");
  EXPECT_EQ(reeve("run --frames 2 --force --csv " + csv).code, 0);
}

TEST_F(Cli, VideoIsAnH264Mp4WithOneFramePerStep) {
  const Result r = reeve("run --frames 5 --width 320 --height 180 --video " + path("v.mp4"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string probe = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                            "stream=codec_name,pix_fmt,nb_read_frames -of csv=p=0 " + path("v.mp4") +
                            " > " + path("probe.txt");
  ASSERT_EQ(std::system(probe.c_str()), 0);
  std::ifstream f(path("probe.txt"));
  std::string line;
  std::getline(f, line);
  EXPECT_EQ(line, "h264,yuv420p,5");
}

TEST_F(Cli, MissingFfmpegIsAClearError) {
  const Result r = reeve("run --frames 2 --video " + path("v.mp4"), "PATH=" + path("empty"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("ffmpeg"), std::string::npos) << r.err;
}

TEST_F(Cli, BadScenesExitWithCode2AndNameFilePathExpectedAndFound) {
  const std::string base =
      R"({"name": "t", "solver": {}, "bodies": [{"name": "w", "shape": {"type": "cylinder", "radius_m": RADIUS, "half_length_m": 0.1}, "mass_kg": 1, "position_m": [0, 0, 0]}]})";
  const std::string bad_radius = write("bad_radius.json", std::regex_replace(base, std::regex("RADIUS"), "-0.5"));
  const Result r = reeve("validate " + bad_radius);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad_radius.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/bodies/0/shape/radius_m"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("-0.5"), std::string::npos) << r.err;

  const std::string syntax = write("syntax.json", "{\n  \"solver\": {,\n}");
  const Result s = reeve("run " + syntax + " --frames 1");
  EXPECT_EQ(s.code, 2);
  EXPECT_NE(s.err.find("syntax.json:2:"), std::string::npos) << s.err;

  const std::string good = write("good.json", std::regex_replace(base, std::regex("RADIUS"), "0.5"));
  const Result ok = reeve("validate " + good);
  EXPECT_EQ(ok.code, 0) << ok.err;

  EXPECT_EQ(reeve("validate " + path("missing.json")).code, 2);

  // A wheel of radius 1e-300 m (no inertia about its axle) and one of
  // density 1e308 (mass 1.6e307 kg): validate and run give the same scene
  // error, no abort.
  const std::string thin = std::regex_replace(base, std::regex("RADIUS"), "1e-300");
  const std::string dense = std::regex_replace(std::regex_replace(base, std::regex("RADIUS"), "0.5"),
                                               std::regex(R"("mass_kg": 1)"), R"("density_kg_per_m3": 1e308)");
  for (const auto& [name, text] : {std::pair{"thin.json", thin}, {"dense.json", dense}}) {
    const std::string extreme = write(name, text);
    const Result v = reeve("validate " + extreme), run = reeve("run " + extreme + " --frames 1");
    EXPECT_EQ(v.code, 2) << v.err;
    EXPECT_EQ(run.code, 2) << run.err;
    EXPECT_EQ(v.err, run.err);
    EXPECT_NE(v.err.find(std::string(name) + ": /bodies/0/"), std::string::npos) << v.err;
  }
}

// Issue 27: a 2 MB scene of a million nested arrays crashed validate and
// run with a stack overflow; now the depth limit is a scene error.
TEST_F(Cli, AMillionNestedArraysAreASceneErrorNotACrash) {
  const std::string deep = write("deep.json", R"({"name": "deep", "solver": {}, "bodies": )" +
                                                  std::string(1000000, '[') + std::string(1000000, ']') + "}");
  for (const char* command : {"validate ", "run --frames 1 "}) {
    const Result r = reeve(command + deep);
    EXPECT_EQ(r.code, 2) << command << r.err;
    EXPECT_NE(r.err.find("deep.json: /bodies/0/0/"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("expected arrays and objects nested at most 64 deep"), std::string::npos) << r.err;
  }
}

TEST_F(Cli, AStateThatBecomesNonFiniteStopsTheRunNamingTheBodyAndQuantity) {
  // The Simple scene at one frame per 1e100 s: within every limit, but its
  // first substep (1e99 s) flings the boxes 1e199 m and the cable spins the
  // wheels past what a double holds. (Traps off: with them the program
  // stops at the overflow itself, which is what REEVE_TRAP_FP is for.)
  std::string scene = test::slurp(std::string(REEVE_SCENES_DIR) + "/simple.json");
  const auto set = [&](const std::string& from, const std::string& to) { scene.replace(scene.find(from), from.size(), to); };
  set(R"("frame_rate_hz": 60)", R"("frame_rate_hz": 1e-100)");
  set(R"("duration_s": 5.0)", R"("duration_s": 1e102)");
  const Result r = reeve("run " + write("slow.json", scene) + " --csv " + path("out.csv"), "REEVE_TRAP_FP=0");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("reeve: the simulation became non-finite at t = "), std::string::npos) << r.err;
  const std::regex named("at t = [0-9.e+]+ s: (body '(wheel_left|wheel_right|left_top|left_bottom|right)' "
                         "(position|orientation|velocity|angular velocity)|the tension between '[a-z_]+' and "
                         "'[a-z_]+'); nothing of that frame was written");
  EXPECT_TRUE(std::regex_search(r.err, named)) << r.err;
  EXPECT_FALSE(fs::exists(path("out.csv")));
}

TEST_F(Cli, ASpanStartingFarPastItsRestLengthIsPulledInWithoutDiverging) {
  // The fuzzer's first finding: hilbert2_loose with one rolling link moved
  // to wheel21, which the cable then meets twice; the span from it to
  // wheel24 starts 1.1 m past its rest length. At one substep a frame the
  // direct solve must turn wheels radians to pull it in. With the span
  // ends held body-fixed it swung them round the rims and diverged
  // (thousands of rad/s) until a rest length went negative and the run
  // stopped ("the cable bookkeeping broke"). Since issue 29 a rolling end
  // stays at its tangent point within a solve and winds cable instead: the
  // span is pulled in at once, a jerk that puts in energy nothing paid for,
  // which the ledger says (--strict: an error), and the run ends.
  const std::string scene = std::string(REEVE_FUZZ_REGRESSIONS_DIR) + "/hilbert2_loose_wheel21_twice.json";
  const Result r = reeve("run " + scene + " --frames 60 --csv " + path("out.csv"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("bookkeeping broke"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("reeve: warning: energy created at t = 0.0166667 s"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(path("out.csv")));
  const Result strict = reeve("run " + scene + " --frames 60 --strict --csv " + path("strict.csv"));
  EXPECT_EQ(strict.code, 1) << strict.err;

  // The cause is visible before anything runs: validate (still exit 0, the
  // scene is valid) and run warn of the span that starts stretched, at its
  // JSON path; the span is 2.24 m between centres, given 1.13 m.
  const std::regex warning("reeve: warning: " + std::regex_replace(scene, std::regex(R"([.\\/])"), R"(\$&)") +
                           ": /cables/0/rest_length_m/23: cable 'rope' span 23 starts (1\\.[0-9]+) m longer "
                           "than its rest length of 1\\.13 m");
  const Result v = reeve("validate " + scene);
  EXPECT_EQ(v.code, 0) << v.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(v.err, m, warning)) << v.err;
  EXPECT_GT(std::stod(m[1]), 0.1 * 1.13) << "past the warning's threshold";
  EXPECT_TRUE(std::regex_search(r.err, warning)) << r.err;
  // No shipped scene starts a span stretched that far.
  for (const auto& entry : fs::directory_iterator(REEVE_SCENES_DIR)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "scene.schema.json") continue;
    const Result shipped = reeve("validate " + entry.path().string());
    EXPECT_EQ(shipped.code, 0) << shipped.err;
    EXPECT_EQ(shipped.err.find("warning"), std::string::npos) << shipped.err;
  }
}

TEST_F(Cli, RestLengthsThatAFrictionlessPinholeSharesOutAreWarnedOf) {
  // Issue 28, item 10: spans of 2 m and 4 m through a frictionless pinhole,
  // given rest lengths of 3 and 3 m. The cable slides through the hole, so
  // the run shares its 6 m in proportion to the lengths and the first CSV
  // row reads 2 and 4: said at load now, not silently.
  const std::string scene = write("pinhole.json", R"({"name": "resplit", "duration_s": 0.1, "solver": {"substeps": 10},
    "bodies": [{"name": "wall", "static": true, "shape": {"type": "box", "half_extents_m": [0.05, 0.05, 0.05]}, "position_m": [-2, 0, 0]},
               {"name": "post", "static": true, "shape": {"type": "box", "half_extents_m": [0.05, 0.05, 0.05]}, "position_m": [0, 0, 0]},
               {"name": "load", "shape": {"type": "box", "half_extents_m": [0.05, 0.05, 0.05]}, "mass_kg": 1, "position_m": [0, -4, 0]}],
    "cables": [{"name": "rope", "rest_length_m": [3, 3], "links": [
      {"body": "wall", "type": "attachment", "point_m": [0, 0, 0]},
      {"body": "post", "type": "pinhole", "point_m": [0, 0, 0]},
      {"body": "load", "type": "attachment", "point_m": [0, 0, 0]}]}]})");
  const Result v = reeve("validate " + scene);
  EXPECT_EQ(v.code, 0) << v.err;
  EXPECT_NE(v.err.find("pinhole.json: /cables/0/rest_length_m: cable 'rope' slides through its frictionless pinholes "
                       "or wraps, so the spans joined there share one rest length in proportion to their lengths: "
                       "[3, 3] is read as [2, 4] (the sum, 6 m, kept)"),
            std::string::npos)
      << v.err;
  const Result r = reeve("run " + scene + " --frames 1 --csv " + path("out.csv"));
  EXPECT_EQ(r.code, 0) << r.err;
  const std::string csv = test::slurp(path("out.csv"));
  const std::size_t row = csv.find('\n') + 1;
  // t = 0: time, the load's position, then tension, rest length and length of each span.
  EXPECT_EQ(csv.compare(row, 20, "0,0,-4,0,0,2,2,0,4,4"), 0) << csv;
}

// Issue 27: the schema allows 1e10 iterations a frame, and validate said
// "ok" to a run of days. Settings whose predicted cost passes a minute per
// simulated second are warned of (exit status unchanged), with the
// prediction; the shipped scenes' settings are not (the test above).
TEST_F(Cli, SettingsThatWillTakeHoursAreWarnedOfBeforeTheRun) {
  std::string text = test::slurp(std::string(REEVE_SCENES_DIR) + "/hilbert3.json");
  const std::string settings = R"("substeps":1,"iterations":10)";
  const std::size_t at = text.find(settings);
  ASSERT_NE(at, std::string::npos);
  const std::string slow = write("slow.json", text.replace(at, settings.size(), R"("substeps":100,"iterations":1000)"));
  const std::regex warning(R"(reeve: warning: .*slow\.json: /solver: 100 substeps x 1000 iterations a frame at 60 Hz \(direct\) predict about ([0-9.e+]+) s of computing per simulated second \(([0-9.e+]+) h for the scene's ([0-9.]+) s\): lower substeps or iterations, or expect to wait)");
  const Result v = reeve("validate " + slow);
  EXPECT_EQ(v.code, 0) << v.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(v.err, m, warning)) << v.err;
  // The hours are the rate times the scene's duration (both printed to two
  // digits).
  EXPECT_NEAR(std::stod(m[2]), std::stod(m[1]) * std::stod(m[3]) / 3600.0, 0.06 * std::stod(m[2]));
  const Result r = reeve("run " + slow + " --frames 1 --substeps 1 --iterations 1");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("/solver"), std::string::npos) << "the settings run are the ones judged: " << r.err;
  const Result slow_run = reeve("run " + slow + " --frames 1 --substeps 40");  // the direct solver converges early
  EXPECT_EQ(slow_run.code, 0) << slow_run.err;
  EXPECT_NE(slow_run.err.find("/solver: 40 substeps x 1000 iterations"), std::string::npos) << slow_run.err;
}

// Gauss-Seidel turns a trapezoidal spring's bodies by first-order
// corrections and needs omega h below about 1 (a lone disc on one: 3 times
// its start swing at w h = 2.3, 317 times at 6.8; the bow at the paper's
// 10 x 10 thrown 2e7 m): validate and run say so first, with the substeps
// that bring it below. omega^2 = k / I, I about the axle: a 3 kg disc of
// 0.2 m on its centre, m r^2 / 2; a 1.2 kg bar 1 m long hinged at its end,
// m (L^2 + t^2) / 12 + m (L / 2)^2 (the parallel axis).
TEST_F(Cli, TrapezoidalSpringsTooStiffForGaussSeidelAreWarnedOfWithTheSubstepsTheyNeed) {
  const auto scene = [&](const std::string& name, const std::string& method, int substeps, const std::string& body,
                         const std::string& anchor) {
    return write(name + ".json", R"({"name": ")" + name + R"(", "duration_s": 0.1,
      "solver": {"method": ")" + method + R"(", "substeps": )" + std::to_string(substeps) + R"(, "gravity_m_per_s2": [0, 0, 0]},
      "bodies": [)" + body + R"(],
      "hinges": [{"body": "spun", "anchor_m": )" + anchor + R"(, "axis": [0, 0, 1],
        "drive": {"mode": "angle", "target_rad": 0.5, "stiffness_N_m_per_rad": 10000, "integration": "trapezoidal"}}]})");
  };
  const std::string disc = R"({"name": "spun", "shape": {"type": "cylinder", "radius_m": 0.2, "half_length_m": 0.05}, "mass_kg": 3, "position_m": [0, 0, 0]})";
  const std::string bar = R"({"name": "spun", "shape": {"type": "box", "half_extents_m": [0.5, 0.05, 0.05]}, "mass_kg": 1.2, "position_m": [0.5, 0, 0]})";
  const double k = 1e4, frame = 1.0 / 60.0;
  const double w_disc = std::sqrt(k / (0.5 * 3.0 * 0.2 * 0.2));
  const double w_bar = std::sqrt(k / (1.2 * (1.0 + 0.01) / 12.0 + 1.2 * 0.25));
  const std::regex warning(R"(/solver: 1 trapezoidal spring at ([0-9]+) substeps a frame: omega h up to ([0-9.]+) \(the hinge of 'spun' and the world, 1e\+04 N m/rad\), where Gauss-Seidel needs it below 1 or may blow up; use the direct solver \("method": "direct"\), ([0-9]+) substeps or more, or "integration": "implicit")");
  struct Case {
    std::string name, body, anchor;
    int substeps;
    double w;
  };
  for (const Case& c : {Case{"disc", disc, "[0, 0, 0]", 2, w_disc}, Case{"bar", bar, "[0, 0, 0]", 1, w_bar}}) {
    SCOPED_TRACE(c.name);
    const Result v = reeve("validate " + scene(c.name, "gauss-seidel", c.substeps, c.body, c.anchor));
    EXPECT_EQ(v.code, 0) << v.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(v.err, m, warning)) << v.err;
    EXPECT_EQ(std::stoi(m[1]), c.substeps);
    EXPECT_NEAR(std::stod(m[2]), c.w * frame / c.substeps, 0.05 * c.w * frame / c.substeps);
    const int enough = std::stoi(m[3]);
    EXPECT_EQ(enough, static_cast<int>(std::ceil(c.w * frame)));
    // At the substeps it names, and under the direct solver, none.
    const Result fine = reeve("validate " + scene(c.name + "_fine", "gauss-seidel", enough, c.body, c.anchor));
    EXPECT_EQ(fine.err.find("trapezoidal"), std::string::npos) << fine.err;
    const Result direct = reeve("validate " + scene(c.name + "_direct", "direct", c.substeps, c.body, c.anchor));
    EXPECT_EQ(direct.err.find("trapezoidal"), std::string::npos) << direct.err;
  }
  // The run judges the settings it runs: the shipped bow (300 substeps,
  // direct) warns of nothing; under Gauss-Seidel at the paper's 10 it does.
  const std::string bow = std::string(REEVE_SCENES_DIR) + "/bow.json";
  const Result own = reeve("run " + bow + " --frames 1 --solver gauss-seidel");
  EXPECT_EQ(own.err.find("trapezoidal"), std::string::npos) << own.err;
  const Result paper = reeve("run " + bow + " --frames 1 --solver gauss-seidel --substeps 10 --iterations 10");
  EXPECT_NE(paper.err.find("6 trapezoidal springs at 10 substeps a frame"), std::string::npos) << paper.err;
}

TEST_F(Cli, AThousandJointsOnTwoBodiesRunWithoutACostWarning) {
  // The fuzzer's third finding (issue 27's long run): springs.json with
  // 1,435 joints between a few bodies, 7,000 rows that the direct solver
  // coupled densely: 4 GB and over 10 s for one substep, and the cost
  // model, linear in the rows, said nothing; it was taught to warn. Since
  // issue 29 those bodies are hubs (direct_solver.h), their rows couple to
  // their own 6 freedoms only: 33 ms a frame here, and the model, which
  // knows hubs, no longer warns.
  const std::string scene = std::string(REEVE_FUZZ_REGRESSIONS_DIR) + "/springs_1435_joints_on_two_bodies.json";
  const Result v = reeve("validate " + scene);
  EXPECT_EQ(v.code, 0) << v.err;
  EXPECT_EQ(v.err.find("/solver:"), std::string::npos) << v.err;
  const Result r = reeve("run " + scene + " --frames 1");
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST_F(Cli, AWheelCarriedFurtherThanItsSizeInASubstepIsSaidToBeTheCause) {
  // The fuzzer's fourth finding: gear_1_to_4 with gravity 184,539 m/s^2
  // sideways and the small wheel hinged 1 m off its centre. Integration
  // carries it 3.2 m in the first substep, so the belt's update sees it
  // unwrapped (-1 m of cable stored on it). Not a diverged solve (it did not
  // turn): the run says what moved and how far.
  const std::string scene = std::string(REEVE_FUZZ_REGRESSIONS_DIR) + "/gear_belt_at_18000_g.json";
  const Result r = reeve("run " + scene + " --frames 3 --substeps 4 --iterations 4");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("cable 'belt': link 0 stores a negative length of cable"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("body 'small' moved 3.2 m in that substep, more than its own size (0.25 m)"),
            std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("The solve diverged"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("Gauss-Seidel"), std::string::npos) << r.err;  // it ran direct: no hint to use it
}

TEST_F(Cli, ARunThatBlowsUpUnderGaussSeidelPointsToTheDirectSolver) {
  // The bow's trapezoidal limb springs (omega h above 1 at 600 Hz) under
  // Gauss-Seidel at the paper's 10 x 10: its sweeps do not converge, and a
  // cam is thrown 2e7 m at 0.255 s (the cable bookkeeping breaks). The
  // direct solver runs the same budget through (a run that fails under it
  // is not told to use it: the gear above).
  const std::string bow = std::string(REEVE_SCENES_DIR) + "/bow.json";
  const Result gs = reeve("run " + bow + " --frames 20 --substeps 10 --iterations 10 --solver gauss-seidel");
  EXPECT_EQ(gs.code, 1) << gs.err;
  EXPECT_NE(gs.err.find("the cable bookkeeping broke"), std::string::npos) << gs.err;
  EXPECT_NE(gs.err.find("This run used Gauss-Seidel"), std::string::npos) << gs.err;
  EXPECT_NE(gs.err.find("--solver direct"), std::string::npos) << gs.err;
  const Result direct = reeve("run " + bow + " --frames 20 --substeps 10 --iterations 10 --solver direct");
  EXPECT_EQ(direct.code, 0) << direct.err;
}

TEST_F(Cli, ADrumHaulingOverAWheelFixedInTheWorldStopsTheRunSayingWhatToChange) {
  // A kinematic drum hauls a rigid cable over a wheel fixed in the world
  // (static, no mu): nothing can pull the drum's span in, and a run that
  // went on would leave the load where it is with the span stretched
  // unseen (Kinematic.ADrumHauling... in the tests of the physics).
  const std::string scene = write("winch.json", R"({"name": "winch",
    "solver": {"frame_rate_hz": 60, "substeps": 10, "iterations": 2}, "duration_s": 1,
    "bodies": [
      {"name": "drum", "shape": {"type": "cylinder", "radius_m": 0.1, "half_length_m": 0.05}, "position_m": [-1, 0, 0],
       "motion": [{"t_s": 0, "angular_velocity_rad_per_s": [0, 0, -2]}]},
      {"name": "sheave", "shape": {"type": "cylinder", "radius_m": 0.1, "half_length_m": 0.05}, "static": true,
       "position_m": [1, 0.5, 0]},
      {"name": "load", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": 5,
       "position_m": [1.1, -1, 0]}],
    "cables": [{"name": "rope", "links": [
      {"body": "drum", "type": "rolling", "orientation": "ccw", "stored_m": 2},
      {"body": "sheave", "type": "rolling", "orientation": "cw"},
      {"body": "load", "type": "attachment", "point_m": [0, 0.1, 0]}]}]})");
  const Result r = reeve("run " + scene + " --csv " + path("out.csv"));
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("a rigid cable was stretched at t = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cable 'rope': its run from 'drum' to 'sheave' is "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Give such a wheel \"mu\""), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("bookkeeping broke"), std::string::npos) << r.err;
  // Given mu 0 it slides over the wheel: the run goes through.
  const std::string sliding =
      write("sliding.json", std::regex_replace(test::slurp(scene), std::regex(R"("orientation": "cw")"),
                                               R"("orientation": "cw", "mu": 0)"));
  const Result ok = reeve("run " + sliding);
  EXPECT_EQ(ok.code, 0) << ok.err;
}

TEST_F(Cli, ASpoolThatRunsOutOfCableStopsTheRunSayingSo) {
  // The fuzzer's second finding (fuzz/regressions/gear_spool_runs_out.json),
  // made a plain machine: gear_1_to_4 with the small hub's rope given no
  // stored cable and its weight doubled, so it outweighs the gear. The
  // weight pays 1e-5 m out of the hub in the first substep: not a
  // diverged solve, and the run must not say it was; a plain rolling end
  // cannot pay out what it does not hold, a hybrid one would tie the
  // cable there.
  const std::string scene = std::string(REEVE_TEST_SCENES_DIR) + "/gear_spool_runs_out.json";
  const Result r = reeve("run " + scene + " --frames 30");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("cable 'rope_small': link 0 stores a negative length of cable"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Its rolling end ran out of cable"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("make it a \"hybrid\" link"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("diverged"), std::string::npos) << r.err;
}

TEST_F(Cli, AStoneFlungFasterThanADoubleCanSquareIsRefusedAtLoad) {
  // 1e308 m/s: its kinetic energy overflows. It once ran and stopped on
  // the non-finite guard (tested in test_correction.cpp); now it never
  // starts, and nothing is written.
  const std::string scene = write("fling.json", R"({"name": "fling", "solver": {}, "bodies": [
    {"name": "stone", "shape": {"type": "sphere", "radius_m": 0.1}, "mass_kg": 1,
     "position_m": [0, 0, 0], "linear_velocity_m_per_s": [1e308, 0, 0]}]})");
  const Result r = reeve("run " + scene + " --frames 5 --csv " + path("out.csv"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("fling.json: /bodies/0/linear_velocity_m_per_s/0: expected a number of magnitude at most 1e153"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("out.csv")));
}

TEST_F(Cli, BodiesPlacedOverlappingArePushedApartAndTheRunSaysSo) {
  // A box 2 mm into the ground and a cube 0.5 mm into the box: pushed
  // apart before the first substep (World::settleInitialOverlaps), the
  // pairs named deepest first, with their depths; the run goes on (exit 0),
  // its ledger reading the lift as energy made (0.064 J, m g times the
  // push), not the 0.1 mm / h launch it was. The same scene placed
  // touching says nothing.
  const auto scene = [&](const std::string& file, double box_y, double cube_y) {
    return write(file, R"({"name": "overlaps", "solver": {"substeps": 100, "iterations": 1}, "ground": {},
      "bodies": [
        {"name": "box", "shape": {"type": "box", "half_extents_m": [0.2, 0.1, 0.2]}, "mass_kg": 2,
         "position_m": [0, )" + std::to_string(box_y) + R"(, 0], "collides": true},
        {"name": "cube", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": 1,
         "position_m": [0, )" + std::to_string(cube_y) + R"(, 0], "collides": true}]})");
  };
  const Result r = reeve("run " + scene("overlaps.json", 0.098, 0.2975) + " --frames 10");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string ground = "reeve: note: the ground and 'box' overlapped by 0.002 m as placed; pushed apart before "
                             "the first step";
  const std::string cube = "reeve: note: 'box' and 'cube' overlapped by 0.0005 m as placed";
  ASSERT_NE(r.err.find(ground), std::string::npos) << r.err;
  ASSERT_NE(r.err.find(cube), std::string::npos) << r.err;
  EXPECT_LT(r.err.find(ground), r.err.find(cube)) << r.err;
  std::smatch made;
  ASSERT_TRUE(std::regex_search(r.err, made, std::regex(R"(energy created at t = [0-9.e+-]+ s: \+([0-9.e+-]+) J)")))
      << r.err;
  EXPECT_NEAR(std::stod(made[1]), 9.81 * (2.0 * 0.002 + 1.0 * 0.0025), 1e-4) << r.err;
  const Result touching = reeve("run " + scene("touching.json", 0.1, 0.3) + " --frames 10");
  ASSERT_EQ(touching.code, 0) << touching.err;
  EXPECT_EQ(touching.err.find("overlapped"), std::string::npos) << touching.err;
}

TEST_F(Cli, SegmentWritesAValidSegmentedRopeSceneAndRefusesToOverwrite) {
  const std::string atwood = std::string(REEVE_SCENES_DIR) + "/atwood.json";
  const Result r = reeve("segment " + atwood + " --cable rope --segments 12 -o " + path("rope.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(reeve("validate " + path("rope.json")).code, 0);
  std::ifstream f(path("rope.json"));
  const std::string text((std::istreambuf_iterator<char>(f)), {});
  EXPECT_NE(text.find("\"rope_seg_011\""), std::string::npos);
  EXPECT_EQ(text.find("\"rope_seg_012\""), std::string::npos);
  EXPECT_EQ(reeve("segment " + atwood + " --cable rope --segments 12 -o " + path("rope.json")).code, 3);
  const Result unknown = reeve("segment " + atwood + " --cable string --segments 12 -o " + path("x.json"));
  EXPECT_EQ(unknown.code, 64);
  EXPECT_NE(unknown.err.find("rope"), std::string::npos) << "lists the cable names: " << unknown.err;
  // The output's budget, given: the run says it runs at it.
  ASSERT_EQ(reeve("segment " + atwood + " --cable rope --segments 12 --substeps 60 --iterations 1 -o " +
                  path("rope60.json")).code,
            0);
  const Result run = reeve("run " + path("rope60.json") + " --frames 1");
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_NE(run.out.find("60 substeps x 1 iterations"), std::string::npos) << run.out;
  const Result zero = reeve("segment " + atwood + " --cable rope --segments 12 --substeps 0 -o " + path("y.json"));
  EXPECT_EQ(zero.code, 64);
  EXPECT_NE(zero.err.find("--substeps"), std::string::npos) << zero.err;
}

TEST_F(Cli, SolverMethodComesFromTheSceneUnlessOverridden) {
  const std::string atwood = std::string(REEVE_SCENES_DIR) + "/atwood.json";
  const Result scene = reeve("run " + atwood + " --frames 2");
  ASSERT_EQ(scene.code, 0) << scene.err;
  EXPECT_NE(scene.out.find("10 substeps x 2 iterations, direct)"), std::string::npos) << scene.out;
  const Result paper = reeve("run " + atwood + " --frames 2 --solver gauss-seidel --substeps 1 --iterations 10");
  ASSERT_EQ(paper.code, 0) << paper.err;
  EXPECT_NE(paper.out.find("1 substeps x 10 iterations, gauss-seidel)"), std::string::npos) << paper.out;
  const Result bad = reeve("run " + atwood + " --solver jacobi");
  EXPECT_EQ(bad.code, 64);
  EXPECT_NE(bad.err.find("--solver: jacobi not in {direct,gauss-seidel}"), std::string::npos) << bad.err;
}

TEST_F(Cli, TheStartProjectionIsTheSceneOrTheFlagsAndTheDirectSolversOnly) {
  const std::string scene = write("swing.json", R"({"name": "swing", "duration_s": 0.1,
    "solver": {"projection": "start"},
    "bodies": [{"name": "bob", "shape": {"type": "sphere", "radius_m": 0.05}, "mass_kg": 1, "position_m": [0.1, -1, 0]}],
    "joints": [{"type": "spherical", "body": "bob", "anchor_m": [0, 0, 0]}]})");
  const Result from_scene = reeve("run " + scene);
  ASSERT_EQ(from_scene.code, 0) << from_scene.err;
  EXPECT_NE(from_scene.out.find("direct, start projection)"), std::string::npos) << from_scene.out;
  const Result ended = reeve("run " + scene + " --projection end");
  ASSERT_EQ(ended.code, 0) << ended.err;
  EXPECT_EQ(ended.out.find("start projection"), std::string::npos) << ended.out;
  const Result swept = reeve("run " + scene + " --solver gauss-seidel");
  EXPECT_EQ(swept.code, 64);
  EXPECT_NE(swept.err.find("the start projection (the scene's solver/projection) is the direct solver's"),
            std::string::npos) << swept.err;
  const Result flagged = reeve("run --frames 2 --projection start --solver gauss-seidel");
  EXPECT_EQ(flagged.code, 64);
  EXPECT_NE(flagged.err.find("(--projection start)"), std::string::npos) << flagged.err;
  EXPECT_EQ(reeve("run --frames 2 --projection middle").code, 64);
}

TEST_F(Cli, UsageErrorsAndHelp) {
  EXPECT_EQ(reeve("run --frames -3").code, 64);
  const Result zero = reeve("run --frames 0");
  EXPECT_EQ(zero.code, 64);
  EXPECT_NE(zero.err.find("--frames: Value 0 not in range 1 to 100000000"), std::string::npos) << zero.err;
  EXPECT_EQ(reeve("run --substeps 100001").code, 64);  // the scene schema's range
  EXPECT_EQ(reeve("frobnicate").code, 64);
  const Result run_help = reeve("run --help");
  EXPECT_NE(run_help.out.find("=1280"), std::string::npos) << run_help.out;  // defaults shown
  EXPECT_NE(run_help.out.find("Exit codes: 0 done; 1 the run failed"), std::string::npos) << run_help.out;
  const Result help = reeve("--help");
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.out.find("run"), std::string::npos);
  const Result version = reeve("--version");
  EXPECT_EQ(version.code, 0);
  EXPECT_NE(version.out.find("reeve "), std::string::npos);
}

}  // namespace

TEST_F(Cli, ImportMjcfWritesTheSceneSaysWhatIsLeftOutAndRunsTheModelDirectly) {
  const std::string atwood = std::string(REEVE_MJCF_MODELS) + "/atwood.xml";
  const Result r = reeve("import mjcf " + atwood + " -o " + path("atwood.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(reeve("validate " + path("atwood.json")).code, 0);
  EXPECT_EQ(reeve("import mjcf " + atwood + " -o " + path("atwood.json")).code, 3);
  EXPECT_EQ(reeve("import mjcf " + atwood + " -o " + path("atwood.json") + " --force --wheels turning").code, 0);
  EXPECT_NE(test::slurp(path("atwood.json")).find("\"hinges\""), std::string::npos) << "the pulley turns on a hinge";
  const Result out = reeve("import mjcf " + atwood);
  ASSERT_EQ(out.code, 0) << out.err;
  EXPECT_EQ(out.out.rfind("{", 0), 0u) << "the scene on standard output";
  EXPECT_EQ(reeve("import mjcf " + atwood + " --wheels square").code, 64);
  // `reeve run` and `validate` read the model as it is.
  const Result run = reeve("run " + atwood + " --frames 3 --csv " + path("atwood.csv"));
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_NE(test::slurp(path("atwood.csv")).find("heavy.z_m"), std::string::npos);
  const std::string damped = write("damped.xml", "<mujoco>\n<worldbody>\n<body>\n<joint type=\"hinge\" frictionloss=\"1\"/>\n"
                                                 "<geom size=\"0.1\"/>\n</body>\n</worldbody>\n</mujoco>\n");
  const Result validate = reeve("validate " + damped);
  EXPECT_EQ(validate.code, 0) << validate.err;
  EXPECT_NE(validate.err.find("1 part of the model is not imported:\n  " + damped + ":4: <joint>: frictionloss not imported"), std::string::npos)
      << validate.err;
  // Controls held constant: a motor pulling a tendon is a winch.
  const std::string actuators = std::string(REEVE_MJCF_MODELS) + "/actuators.xml";
  const Result held = reeve("import mjcf " + actuators + " --control spin=0.5 --control lift=-20");
  ASSERT_EQ(held.code, 0) << held.err;
  EXPECT_NE(held.out.find("\"winch\""), std::string::npos);
  for (const char* control : {"spin", "=1", "spin=abc", "spin=1e999"})
    EXPECT_EQ(reeve("import mjcf " + actuators + " --control " + control).code, 64) << control;
  const std::string bad = write("bad.xml", "<mujoco>\n<worldbody>\n<body pos=\"1 2\"/>\n</worldbody>\n</mujoco>\n");
  for (const std::string command : {"run ", "validate ", "import mjcf "}) {
    const Result e = reeve(command + bad);
    EXPECT_EQ(e.code, 2) << command;
    EXPECT_NE(e.err.find(bad + ":3: <body>: expected pos of 3 numbers"), std::string::npos) << e.err;
  }
}
