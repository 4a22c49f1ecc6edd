// The `reeve` command line: run a scene to PNG/MP4/CSV, validate it, generate
// or segment one, or measure speed and accuracy (bench).
#include <CLI/CLI.hpp>

#include <fenv.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "bench_command.h"
#include "commands.h"
#include "generate_command.h"
#include "import_command.h"
#include "reeve/engine/fp_exceptions.h"
#include "segment_command.h"
#include "view_server.h"
#include "reeve/scene/scene.h"

int main(int argc, char** argv) {
  // REEVE_TRAP_FP=1: an invalid operation, a division by zero or an overflow
  // stops the program (SIGFPE) where it happens, as in the tests, which run
  // every reeve so (README, "Hardening").
  if (const char* trap = std::getenv("REEVE_TRAP_FP"); trap && std::strcmp(trap, "1") == 0)
    feenableexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
  CLI::App app{"Reeve: cable-driven machines simulated with XPBD cable joints (Müller et al. 2018)."};
  app.set_version_flag("--version", std::string("reeve ") + REEVE_VERSION);
  app.require_subcommand(1);

  reeve::RunOptions run;
  CLI::App* run_cmd = app.add_subcommand("run", "Simulate a scene; write PNG frames, an MP4 video and/or a CSV.");
  run_cmd->add_option("scene", run.scene, "Scene JSON file (default: the built-in Simple scene)");
  // The same ranges as the scene schema's solver settings.
  run_cmd->add_option("--frames", run.frames, "Frames to simulate, 1..100000000 (default: the scene's duration)")
      ->check(CLI::Range(1, 100000000));
  run_cmd->add_option("--substeps", run.substeps, "Substeps per frame, 1..100000 (default: the scene's)")
      ->check(CLI::Range(1, 100000));
  run_cmd->add_option("--iterations", run.iterations, "Solver iterations per substep, 1..100000 (default: the scene's)")
      ->check(CLI::Range(1, 100000));
  run_cmd->add_option("--threads", run.threads,
                      "Threads to step the scene's islands on, 1..1024 (default: the cores this process may run on; "
                      "shared only where a substep's islands take 20 us or more); the results are the same for any "
                      "number")
      ->check(CLI::Range(1, 1024));
  run_cmd->add_option("--solver", run.solver,
                      "direct (joints and cables solved together) or gauss-seidel (the paper's); overrides the scene")
      ->check(CLI::IsMember({"direct", "gauss-seidel"}));
  run_cmd->add_option("--projection", run.projection,
                      "The direct solver's: end (XPBD, loses a swing's energy) or start (SHAKE, keeps it); overrides "
                      "the scene")
      ->check(CLI::IsMember({"end", "start"}));
  run_cmd->add_option("--png", run.png_dir, "Write frame_NNNNN.png files into this folder");
  run_cmd->add_option("--video", run.video, "Write an H.264 MP4 video (needs the ffmpeg program)");
  run_cmd->add_option("--csv", run.csv, "Write time, body positions and cable tensions per frame");
  run_cmd->add_option("--html", run.html, "Write a replay to open in a browser: one HTML file, works offline");
  run_cmd->add_option("--events", run.events, "Write link switches, merges and splits as JSON lines");
  run_cmd->add_option("--width", run.width, "Image width in pixels")->check(CLI::Range(16, 8192))->capture_default_str();
  run_cmd->add_option("--height", run.height, "Image height in pixels")->check(CLI::Range(16, 8192))->capture_default_str();
  run_cmd->footer(
      "Exit codes: 0 done; 1 the run failed (I/O, a full disk, rendering, ffmpeg, a non-finite state, and with\n"
      "--strict energy created or a span wound empty); 2 the scene is invalid; 3 an output exists (pass --force); 64\n"
      "a bad command line or outputs that clash; 130 or 143 stopped by SIGINT or SIGTERM after a whole frame, with\n"
      "every output closed.\n");
  run_cmd->add_flag("--force", run.force, "Overwrite existing output files");
  run_cmd->add_flag("--strict", run.strict,
                    "Stop with exit 1 where the energy ledger shows energy created or a span is wound empty (by default "
                    "a warning)");

  reeve::ViewOptions view;
  std::string view_solver;
  CLI::App* view_cmd = app.add_subcommand(
      "view", "Run a scene live in a browser: play, pause, step, drag bodies, plot tensions (Ctrl-C stops).");
  view_cmd->add_option("scene", view.scene, "Scene JSON file (default: the built-in Simple scene); reloaded when it changes");
  view_cmd->add_option("--port", view.port, "Port to listen on; 0 picks a free one")
      ->check(CLI::Range(0, 65535))->capture_default_str();
  view_cmd->add_option("--host", view.host,
                       "Address to listen on (default 127.0.0.1, this machine only; another prints a warning)")
      ->capture_default_str();
  view_cmd->add_option("--substeps", view.overrides.substeps, "Substeps per frame, 1..100000 (default: the scene's)")
      ->check(CLI::Range(1, 100000));
  view_cmd->add_option("--iterations", view.overrides.iterations, "Solver iterations per substep, 1..100000")
      ->check(CLI::Range(1, 100000));
  view_cmd->add_option("--threads", view.overrides.threads,
                       "Threads to step the scene's islands on, 1..1024 (default: the cores this process may run "
                       "on), as reeve run")
      ->check(CLI::Range(1, 1024));
  view_cmd->add_option("--solver", view_solver, "direct or gauss-seidel (default: the scene's)")
      ->check(CLI::IsMember({"direct", "gauss-seidel"}));
  view_cmd->footer(
      "Open the printed address in a browser; on a remote machine, forward the port (ssh -L 8765:localhost:8765\n"
      "HOST) and open http://localhost:8765/. Exit codes: 0 stopped by Ctrl-C; 1 the viewer's files are missing or\n"
      "the address is taken; 2 the scene is invalid; 64 a bad command line.\n");

  std::string validate_scene;
  CLI::App* validate_cmd = app.add_subcommand("validate", "Check a scene file and report the first error.");
  validate_cmd->add_option("scene", validate_scene, "Scene JSON file")->required();

  reeve::SegmentCommandOptions segment;
  double rope_mass = 0.0;
  CLI::App* segment_cmd = app.add_subcommand(
      "segment", "Write SCENE with a cable replaced by a chain of rigid segments (the paper's baseline).");
  segment_cmd->add_option("scene", segment.scene, "Scene JSON file")->required();
  segment_cmd->add_option("--cable", segment.segment.cable, "Name of the cable to replace")->required();
  segment_cmd->add_option("--segments", segment.segment.segments, "Number of rigid segments")
      ->required()->check(CLI::Range(1, 100000));
  segment_cmd->add_option("--radius", segment.segment.radius_m, "Segment radius, m (default 0.01)")
      ->check(CLI::PositiveNumber);
  CLI::Option* rope_mass_opt = segment_cmd->add_option(
      "--rope-mass", rope_mass, "Total rope mass, kg (default 1 % of the lighter end body)")
      ->check(CLI::PositiveNumber);
  int segment_substeps = 0, segment_iterations = 0;
  CLI::Option* segment_substeps_opt = segment_cmd->add_option(
      "--substeps", segment_substeps, "Substeps a frame of the output (default the input's)")
      ->check(CLI::Range(1, 1000000));
  CLI::Option* segment_iterations_opt = segment_cmd->add_option(
      "--iterations", segment_iterations, "Iterations a substep of the output (default the input's)")
      ->check(CLI::Range(1, 1000000));
  segment_cmd->add_option("-o,--output", segment.output,
                          "Output scene (default SCENE_segments.json beside SCENE)");
  segment_cmd->add_flag("--force", segment.force, "Overwrite an existing output file");

  reeve::GenerateHilbertOptions hilbert;
  CLI::App* generate_cmd = app.add_subcommand("generate", "Write a generated scene file.");
  generate_cmd->require_subcommand(1);
  CLI::App* hilbert_cmd = generate_cmd->add_subcommand(
      "hilbert", "The paper's Hilbert-curve machine (Fig. 18): wheels along a 3D Hilbert curve, one cable, a motor.");
  hilbert_cmd->add_option("--level", hilbert.level, "Curve level: 8^level wheels (1..4; default 2)")
      ->check(CLI::Range(1, 4));
  hilbert_cmd->add_option("--slack", hilbert.slack_m, "Slack of every span, m (default 0: taut)")
      ->check(CLI::NonNegativeNumber);
  hilbert_cmd->add_option("--end", hilbert.end,
                          "brake (a drum braked with 10 N m, the paper's; the default) or load (10 kg, 3 m down)")
      ->check(CLI::IsMember({"brake", "load"}));
  hilbert_cmd->add_option("--wheel-kg", hilbert.wheel_kg, "Mass of every wheel, kg (default 1)")
      ->check(CLI::PositiveNumber);
  hilbert_cmd->add_option("-o,--output", hilbert.output,
                          "Output scene (default hilbert<level>.json, or hilbert<level>_loose.json with slack)");
  hilbert_cmd->add_flag("--force", hilbert.force, "Overwrite an existing output file");

  reeve::ImportCommandOptions import_options;
  std::string wheels = "fixed";
  CLI::App* import_cmd = app.add_subcommand("import", "Write the Reeve scene a model of another format makes.");
  import_cmd->require_subcommand(1);
  CLI::App* mjcf_cmd = import_cmd->add_subcommand(
      "mjcf", "A MuJoCo model (MJCF XML): bodies, joints and spatial tendons over wrap cylinders (scenes/README.md).");
  mjcf_cmd->add_option("model", import_options.model, "MJCF file (.xml)")->required();
  mjcf_cmd->add_option("-o,--output", import_options.output, "Scene JSON file to write (default: standard output)");
  mjcf_cmd->add_option("--wheels", wheels,
                       "fixed: wrap cylinders are frictionless fixed pulleys, as in MuJoCo (default); turning: wheels "
                       "hinged on their axes with the geoms' masses, the tendon rolling on them")
      ->check(CLI::IsMember({"fixed", "turning"}));
  std::vector<std::string> controls;
  mjcf_cmd->add_option("--control", controls,
                       "NAME=VALUE: the control (MuJoCo's ctrl) of the actuator NAME, held constant while the scene "
                       "runs; repeat for more actuators (default 0: at rest)");
  mjcf_cmd->add_flag("--force", import_options.force, "Overwrite an existing output file");

  CLI::App* bench_cmd = nullptr;
  const std::function<int()> bench = reeve::addBenchCommand(app, bench_cmd);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : reeve::kExitUsage;
  }
  if (*run_cmd) return reeve::runCommand(run);
  if (*view_cmd) {
    if (!view_solver.empty()) view.overrides.solver = reeve::solverMethodFromName(view_solver);
    return reeve::viewCommand(view);
  }
  if (*hilbert_cmd) return reeve::generateHilbertCommand(hilbert);
  if (*mjcf_cmd) {
    import_options.mjcf.wheels = wheels == "turning" ? reeve::MjcfWheels::Turning : reeve::MjcfWheels::Fixed;
    for (const std::string& c : controls) {
      const auto eq = c.find('=');
      char* end = nullptr;
      double value = 0.0;
      if (eq != std::string::npos) {
        const reeve::FloatingPointExceptionsMasked overflow_is_tested;  // "1e999" is checked below
        value = std::strtod(c.c_str() + eq + 1, &end);
      }
      if (eq == std::string::npos || eq == 0 || end == c.c_str() + eq + 1 || *end != '\0' || !std::isfinite(value)) {
        std::cerr << "reeve: --control: expected NAME=VALUE with a finite number, got \"" << c << "\"\n";
        return reeve::kExitUsage;
      }
      import_options.mjcf.controls[c.substr(0, eq)] = value;
    }
    return reeve::importCommand(import_options);
  }
  if (*bench_cmd) return bench();
  if (*segment_cmd) {
    if (*rope_mass_opt) segment.segment.rope_mass_kg = rope_mass;
    if (*segment_substeps_opt) segment.segment.substeps = segment_substeps;
    if (*segment_iterations_opt) segment.segment.iterations = segment_iterations;
    std::string line = "reeve segment";
    for (int i = 1 + 1; i < argc; ++i) line += std::string(" ") + argv[i];
    segment.segment.command_line = line;
    return reeve::segmentCommand(segment);
  }
  return reeve::validateCommand(validate_scene);
}
