// What `reeve run` writes, under faults: full disks, clashing names, names
// ffmpeg would read as protocols, body names that need CSV quoting, and
// runs that fail half-way (issue 12).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "cli_fixture.h"

namespace {

namespace fs = std::filesystem;
using test::Cli;
using test::reeve;
using test::Result;
using test::slurp;

const std::string kAtwood = std::string(REEVE_SCENES_DIR) + "/atwood.json";
const std::string kMergeSplit = std::string(REEVE_SCENES_DIR) + "/merge_split.json";  // has events

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// RFC 4180 fields of one record (quoted fields may hold commas, doubled
// quotes and line breaks); `text` from `pos`, which it moves past the record.
std::vector<std::string> record(const std::string& text, std::size_t& pos) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (; pos < text.size(); ++pos) {
    const char c = text[pos];
    if (quoted) {
      if (c == '"' && pos + 1 < text.size() && text[pos + 1] == '"') {
        fields.back() += '"';
        ++pos;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c == '\n') {
      ++pos;
      break;
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

TEST_F(Cli, AFullDiskIsAnErrorNamingTheFile) {
  for (const std::string& option : {std::string("--csv"), std::string("--events")}) {
    const Result r = reeve("run " + kMergeSplit + " " + option + " /dev/full");
    EXPECT_EQ(r.code, 1) << option;
    EXPECT_NE(r.err.find("/dev/full: cannot write: No space left on device"), std::string::npos) << r.err;
  }
}

TEST_F(Cli, ARunThatFailsLeavesNothingNewAndAReRunSucceeds) {
  // The events fail (a full disk) after the CSV has had rows and every PNG
  // frame is drawn: neither the CSV nor a frame nor the frames' folder nor
  // a temporary file is left, so the corrected run is not refused.
  const std::string csv = path("run.csv");
  const Result failed = reeve("run " + kMergeSplit + " --csv " + csv + " --events /dev/full --png " +
                              path("frames") + " --width 32 --height 24");
  EXPECT_EQ(failed.code, 1) << failed.err;
  EXPECT_TRUE(listing(dir_).empty()) << listing(dir_).front();
  const Result ok = reeve("run " + kMergeSplit + " --csv " + csv + " --events " + path("events.jsonl"));
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_EQ(listing(dir_), (std::vector<std::string>{"events.jsonl", "run.csv"}));
}

TEST_F(Cli, ForceWithFewerFramesLeavesNoOlderFrameBehind) {
  const std::string run = "run " + kAtwood + " --width 32 --height 24 --png " + path("frames");
  ASSERT_EQ(reeve(run + " --frames 5").code, 0);
  write("frames/notes.txt", "mine\n");
  write("frames/frame_12.png", "not a frame of reeve's numbering\n");
  const Result again = reeve(run + " --frames 2");
  EXPECT_EQ(again.code, 3) << "frames 0 and 1 exist";
  const Result forced = reeve(run + " --frames 2 --force");
  ASSERT_EQ(forced.code, 0) << forced.err;
  EXPECT_EQ(listing(fs::path(path("frames"))),
            (std::vector<std::string>{"frame_00000.png", "frame_00001.png", "frame_12.png", "notes.txt"}));
}

TEST_F(Cli, OutputsThatClashAreRefusedEvenWithForce) {
  const Result both = reeve("run " + kAtwood + " --frames 2 --csv " + path("x") + " --events " + path("x") + " --force");
  EXPECT_EQ(both.code, 64);
  EXPECT_NE(both.err.find("--events " + path("x") + " is the same file as --csv " + path("x")), std::string::npos)
      << both.err;
  const std::string scene = write("scene.json", slurp(kAtwood));
  const Result over = reeve("run " + scene + " --frames 2 --csv " + dir_.string() + "/./scene.json --force");
  EXPECT_EQ(over.code, 64);
  EXPECT_NE(over.err.find("is the same file as the scene"), std::string::npos) << over.err;
  EXPECT_EQ(slurp(scene), slurp(kAtwood));
  EXPECT_EQ(listing(dir_), std::vector<std::string>{"scene.json"});
}

TEST_F(Cli, AVideoNameIsAFileNeverAnFfmpegProtocol) {
  // "file:victim.mp4" once reached ffmpeg as its file protocol and replaced
  // victim.mp4 without --force. It names a file of that name.
  write("victim.mp4", "my video\n");
  const Result r = reeve("run " + kAtwood + " --frames 2 --width 64 --height 48 --video file:victim.mp4",
                         "cd " + dir_.string() + " &&");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(path("victim.mp4")), "my video\n");
  EXPECT_EQ(listing(dir_), (std::vector<std::string>{"file:victim.mp4", "victim.mp4"}));
  EXPECT_GT(fs::file_size(path("file:victim.mp4")), 0u);
}

// Issue 27: ffmpeg's failure used to show its temporary file's name
// ("/proc/.v.reeve-22295-9imp6fo1.mp4: No such file ... Broken pipe").
TEST_F(Cli, AVideoThatCannotBeWrittenIsNamedAsTheUserWroteItWithFfmpegsReason) {
  const Result r = reeve("run " + kAtwood + " --frames 2 --width 64 --height 48 --video /proc/v.mp4");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("cannot write the video '/proc/v.mp4': No such file or directory (ffmpeg, exit status 1)"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find(".reeve-"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("Broken pipe"), std::string::npos) << r.err;
}

// Issue 27: a signal was read only between frames, so a frame of hours
// (the schema allows 1e10 iterations a frame) could only be killed. Now it
// ends the frame under way within a solver iteration, writes the whole
// frames done (here none: the CSV has its header and t = 0) and says where
// it stopped.
TEST_F(Cli, AnInterruptInsideALongFrameEndsItAtOnce) {
  const std::string script =
      "set -m; cd " + dir_.string() + " && { REEVE_TRAP_FP=1 " REEVE_BINARY " run " + kAtwood +
      " --substeps 100000 --iterations 100000 --solver gauss-seidel --csv c.csv >out.txt 2>err.txt & };"
      " pid=$!; sleep 1; kill -INT $pid; t0=$(date +%s%N);"
      " for i in $(seq 3000); do kill -0 $pid 2>/dev/null || break; sleep 0.01; done;"
      " echo $(( ($(date +%s%N) - t0) / 1000000 )) > ms.txt; kill -KILL $pid 2>/dev/null; wait $pid;"
      " echo $? > code.txt";
  ASSERT_EQ(std::system(("bash -c '" + script + "'").c_str()), 0);
  const std::string err = slurp(path("err.txt"));
  EXPECT_EQ(std::stoi(slurp(path("code.txt"))), 130) << err;
  EXPECT_LT(std::stoi(slurp(path("ms.txt"))), 1000) << "ms from the signal to the exit";
  const std::regex said(R"(interrupted \(SIGINT\): stopped after 0 of 84 frames inside frame 1 \(at t = [0-9.e-]+ s, not written\); the outputs hold those 0 frames)");
  EXPECT_TRUE(std::regex_search(err, said)) << err;
  const std::string csv = slurp(path("c.csv"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 2) << "a header and t = 0";
}

TEST_F(Cli, BodyNamesWithCommasQuotesAndLineBreaksAreQuotedInTheCsvHeader) {
  std::string scene = slurp(kAtwood);
  const auto rename = [&](const std::string& from, const std::string& to) {
    for (std::size_t at; (at = scene.find(from)) != std::string::npos;) scene.replace(at, from.size(), to);
  };
  rename("\"light\"", R"("a,b")");
  rename("\"heavy\"", R"("say \"hi\"\nthere")");
  const Result r = reeve("run " + write("names.json", scene) + " --frames 3 --csv " + path("out.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string text = slurp(path("out.csv"));
  std::size_t pos = 0;
  const std::vector<std::string> header = record(text, pos);
  ASSERT_GE(header.size(), 7u);
  EXPECT_EQ(header[4], "a,b.x_m");
  EXPECT_EQ(header[7], "say \"hi\"\nthere.x_m");
  int rows = 0;
  while (pos < text.size()) {
    const std::vector<std::string> row = record(text, pos);
    EXPECT_EQ(row.size(), header.size()) << "row " << rows;
    for (const std::string& cell : row) EXPECT_NE(cell, "-0");
    ++rows;
  }
  EXPECT_EQ(rows, 1 + 3);
}

TEST_F(Cli, AnInterruptEndsTheFrameClosesEveryOutputAndExits128PlusTheSignal) {
  // SIGINT or SIGTERM 1.5 s into a long run of merge_split with every output:
  // the CSV holds whole rows of the frames done, the video as many frames
  // (ffmpeg is waited for, not killed), the events file is there, and the
  // count is printed. (bash with set -m: a background job of a shell
  // without job control inherits SIGINT ignored, and keeps it so, as
  // under nohup. A run still going 30 s after the signal is killed.)
  for (const auto& [signal, code] : {std::pair{"INT", 130}, {"TERM", 143}}) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const std::string script =
        "set -m; cd " + dir_.string() + " && { REEVE_TRAP_FP=1 " REEVE_BINARY " run " REEVE_SCENES_DIR
        "/merge_split.json --frames 10000000 --width 64 --height 48 --csv c.csv --events e.jsonl --video v.mp4"
        " >out.txt 2>err.txt & }; pid=$!; sleep 1.5; kill -" + std::string(signal) +
        " $pid; for i in $(seq 300); do kill -0 $pid 2>/dev/null || break; sleep 0.1; done;"
        " kill -KILL $pid 2>/dev/null; wait $pid; echo $? > " + path("code.txt");
    ASSERT_EQ(std::system(("bash -c '" + script + "'").c_str()), 0);
    EXPECT_EQ(std::stoi(slurp(path("code.txt"))), code) << slurp(path("err.txt"));
    const std::string err = slurp(path("err.txt"));
    const std::size_t at = err.find("stopped after ");
    ASSERT_NE(at, std::string::npos) << err;
    const int done = std::stoi(err.substr(at + 14));
    EXPECT_GT(done, 0);
    const std::string csv = slurp(path("c.csv"));
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), done + 2) << "a header, t = 0 and a row per frame";
    EXPECT_EQ(csv.back(), '\n');
    EXPECT_TRUE(fs::exists(path("e.jsonl")));
    const std::string probe = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                              "stream=nb_read_frames -of csv=p=0 " + path("v.mp4") + " > " + path("probe.txt");
    ASSERT_EQ(std::system(probe.c_str()), 0);
    EXPECT_EQ(std::stoi(slurp(path("probe.txt"))), done);
    EXPECT_EQ(listing(dir_), (std::vector<std::string>{"c.csv", "code.txt", "e.jsonl", "err.txt", "out.txt",
                                                       "probe.txt", "v.mp4"}))
        << "no temporary file left";
  }
}

TEST_F(Cli, EveryShippedScenesCsvIsTheSameBytesFromTwoProcesses) {
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(REEVE_SCENES_DIR)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "scene.schema.json") continue;
    const std::string name = entry.path().stem().string();
    std::string csv[2];
    for (int run = 0; run < 2; ++run) {
      const std::string file = path(name + std::to_string(run) + ".csv");
      const Result r = reeve("run " + entry.path().string() + " --frames 20 --csv " + file);
      ASSERT_EQ(r.code, 0) << name << ": " << r.err;
      csv[run] = slurp(file);
    }
    EXPECT_FALSE(csv[0].empty()) << name;
    EXPECT_TRUE(csv[0] == csv[1]) << name << ": the two runs differ";
    ++scenes;
  }
  EXPECT_GE(scenes, 17);
}

}  // namespace

namespace {

TEST_F(Cli, AWinchsPullIsACsvColumnAndABreakAnEventWithItsTension) {
  // 5 kg hauled at 1 m/s on an elastic rope (EA 500 N) that breaks at 80 N:
  // the pull is the weight until the haul's swing passes 80 N.
  const std::string scene = path("winch.json");
  std::ofstream(scene) << R"({"name": "winch", "solver": {"substeps": 20}, "duration_s": 1,
    "bodies": [{"name": "top", "static": true, "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "position_m": [0, 0, 0]},
               {"name": "load", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": 5, "position_m": [0, -2.1962, 0]}],
    "cables": [{"name": "rope", "compliance_m_per_N": 0.004, "breaking_tension_N": 80, "rest_length_m": [2],
      "links": [{"body": "load", "type": "attachment", "point_m": [0, 0, 0]}, {"body": "top", "type": "attachment", "point_m": [0, 0, 0]}],
      "winch": {"end": "last", "commands": [{"from_s": 0.5, "speed_m_per_s": 1}]}}]})";
  const std::string csv = path("winch.csv"), events = path("events.jsonl");
  const Result r = reeve("run " + scene + " --csv " + csv + " --events " + events);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string table = slurp(csv);
  std::size_t pos = 0;
  const auto header = record(table, pos);
  const auto column = std::find(header.begin(), header.end(), "rope.winch_pull_N");
  ASSERT_NE(column, header.end());
  // Frame 15 (0.25 s): hanging at rest, held by the winch, m g = 49 N.
  for (int row = 0; row < 15; ++row) record(table, pos);
  const auto at_rest = record(table, pos);
  EXPECT_NEAR(std::stod(at_rest[column - header.begin()]), 5 * 9.81, 0.05);
  const std::string log = slurp(events);
  EXPECT_NE(log.find("\"event\":\"break\""), std::string::npos) << log;
  EXPECT_NE(log.find("\"tension_N\":8"), std::string::npos) << log;
}

TEST_F(Cli, TheEnergyLedgerIsInTheCsvAndEnergyCreatedIsAWarningOrWithStrictAnError) {
  // The Atwood machine (1 and 2 kg over a 2 kg solid wheel): after 1.4 s at
  // a = g / 4 its kinetic energy is (m1 + m2 + M / 2) (a t)^2 / 2, and the
  // residual is never above 0 (nothing made, nothing put in).
  const std::string csv = path("atwood.csv");
  Result r = reeve("run " + kAtwood + " --csv " + csv);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("energy created"), std::string::npos) << r.err;
  const std::string table = slurp(csv);
  std::size_t pos = 0;
  const auto header = record(table, pos);
  const auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return static_cast<std::size_t>(it - header.begin());
  };
  const std::size_t kinetic = column("energy.kinetic_J"), residual = column("energy.residual_J");
  for (const char* name : {"energy.potential_J", "energy.elastic_J", "energy.drive_work_J", "energy.load_work_J",
                           "energy.winch_work_J", "energy.kinematic_work_J", "energy.damping_J", "energy.contact_J",
                           "energy.friction_J", "energy.cable_damping_J"})
    column(name);
  std::vector<std::string> row;
  while (pos < table.size()) {
    row = record(table, pos);
    EXPECT_LE(std::stod(row[residual]), 0.0) << "t = " << row[0];
  }
  const double v = 9.81 / 4.0 * 1.4;
  EXPECT_NEAR(std::stod(row[kinetic]), 0.5 * 4.0 * v * v, 1e-3 * 0.5 * 4.0 * v * v);
  // Gauss-Seidel at one substep and one sweep makes energy in the stiff
  // springs of springs.json (trapezoidal: w h above 1, DESIGN): warned of
  // by default; with --strict the run stops there and leaves no CSV.
  const std::string springs = std::string(REEVE_SCENES_DIR) + "/springs.json";
  const std::string budget = " --solver gauss-seidel --substeps 1 --iterations 1";
  r = reeve("run " + springs + budget);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("reeve: warning: energy created at t = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--strict makes this an error"), std::string::npos) << r.err;
  const std::string strict_csv = path("springs.csv");
  r = reeve("run " + springs + budget + " --strict --csv " + strict_csv);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("reeve: energy created at t = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("nothing of that frame was written (--strict)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(strict_csv));
}

TEST_F(Cli, ASpanWoundEmptyIsAWarningOrWithStrictAnError) {
  // Issue 28, item 9: a motor winds 1 m of span onto a pulley at 0.5 m/s,
  // hauling a slider along a rail to its rim (tests/test_spool.cpp has the
  // physics). The run says when the span ran out (2.12 s at 10 x 2), and
  // what to do; the event log has it; --strict stops there, writing nothing.
  const std::string scene = REEVE_TEST_SCENES_DIR "/span_wound_empty.json";
  Result r = reeve("run " + scene + " --events " + path("events.jsonl"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("reeve: warning: cable 'rope' ran out between 'pulley' (link 0) and 'slider' at t = 2.1"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("Stop the drive before, or give the span more cable"), std::string::npos) << r.err;
  EXPECT_NE(slurp(path("events.jsonl")).find(R"("event":"span_runs_out","link":0)"), std::string::npos);
  r = reeve("run " + scene + " --strict --csv " + path("wind.csv"));
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("ran out between 'pulley' (link 0)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(--strict)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("wind.csv")));
  // Item 14: on a stiff elastic rope (2e-6 m/N) at 1 x 10 the fight that
  // follows flings the slider (3.2e5 N; 3e5 J in a frame). Not a silent exit
  // 0: both the ledger and the span say so, and --strict makes it exit 1.
  std::string stiff = slurp(scene);
  stiff.replace(stiff.find(R"("name": "rope",)"), 15, R"("name": "rope", "compliance_m_per_N": 2e-6,)");
  const std::string stiff_scene = write("stiff.json", stiff);
  r = reeve("run " + stiff_scene + " --substeps 1 --iterations 10");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("reeve: warning: energy created at t = 2.1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("reeve: warning: cable 'rope' ran out between"), std::string::npos) << r.err;
  r = reeve("run " + stiff_scene + " --substeps 1 --iterations 10 --strict");
  EXPECT_EQ(r.code, 1) << r.err;
}

}  // namespace
