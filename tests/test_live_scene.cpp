// `reeve view`'s scene under the page's commands (tools/src/live_scene.h):
// it steps as `reeve run` does, bit for bit; its frame messages hold the
// state as the wire format says; every malformed command is refused and
// changes nothing; drags, drive targets and budgets do what they say.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "live_scene.h"
#include "reeve/scene/energy.h"
#include "scene_fixture.h"

namespace reeve::test_live_scene {
namespace {

namespace fs = std::filesystem;

fs::path atwoodFile() { return fs::path(REEVE_SCENES_DIR) / "atwood.json"; }

// `json` written to a file of its own (LiveScene reads scenes from files).
fs::path sceneFile(const std::string& name, const std::string& json) {
  const fs::path file = fs::temp_directory_path() / ("reeve_live_" + name + ".json");
  std::ofstream(file) << json;
  return file;
}

// A 1 kg box, 0.2 m a side, floating without gravity, and an arm on a
// hinge to the world with a rigid angle drive.
const char* kFloating = R"({"name": "floating", "duration_s": 2,
  "solver": {"frame_rate_hz": 60, "substeps": 10, "iterations": 2, "gravity_m_per_s2": [0, 0, 0]},
  "bodies": [
    {"name": "box", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": 1.0, "position_m": [0, 0, 0]},
    {"name": "arm", "shape": {"type": "box", "half_extents_m": [0.5, 0.05, 0.05]}, "mass_kg": 2.0, "position_m": [3.5, 0, 0]},
    {"name": "post", "static": true, "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "position_m": [0, -2, 0]}
  ],
  "hinges": [{"body": "arm", "anchor_m": [3, 0, 0], "axis": [0, 0, 1], "drive": {"mode": "angle", "target_rad": 0}}]})";

// The frame message (live_scene.h) read back.
struct Frame {
  std::uint32_t generation = 0, frame = 0, iterations = 0;
  double t = 0.0, physics_ms = 0.0;
  std::vector<double> bodies;  // 10 a body
  std::vector<double> hinges;  // 2 a hinge
  std::vector<std::vector<double>> joints;  // per cable, 2 a joint
  std::vector<std::vector<float>> spans;    // per cable, 6 a joint: start and end
  std::vector<std::vector<std::vector<float>>> paths, coils;
  std::vector<std::uint32_t> marker_kinds;
  std::vector<float> markers;  // 3 a marker
};

Frame readFrame(const std::string& message) {
  std::size_t at = 0;
  const auto take = [&](auto& value) {
    EXPECT_LE(at + sizeof value, message.size());
    std::memcpy(&value, message.data() + at, sizeof value);
    at += sizeof value;
  };
  const auto count = [&] {
    std::uint32_t n = 0;
    take(n);
    return n;
  };
  EXPECT_EQ(count(), message.size() - 4);
  EXPECT_EQ(message[4], static_cast<char>(kFrameMessage));
  at = 5;
  Frame f;
  take(f.generation);
  take(f.frame);
  take(f.t);
  take(f.iterations);
  take(f.physics_ms);
  f.bodies.resize(10 * count());
  for (double& v : f.bodies) take(v);
  f.hinges.resize(2 * count());
  for (double& v : f.hinges) take(v);
  f.joints.resize(count());
  f.spans.resize(f.joints.size());
  f.paths.resize(f.joints.size());
  f.coils.resize(f.joints.size());
  const auto polylines = [&](std::vector<std::vector<float>>& pieces) {
    pieces.resize(count());
    for (std::vector<float>& piece : pieces) {
      piece.resize(3 * count());
      for (float& v : piece) take(v);
    }
  };
  for (std::size_t c = 0; c < f.joints.size(); ++c) {
    const std::uint32_t joints = count();
    f.joints[c].resize(2 * joints);
    f.spans[c].resize(6 * joints);
    for (std::uint32_t j = 0; j < joints; ++j) {
      take(f.joints[c][2 * j]);
      take(f.joints[c][2 * j + 1]);
      for (int k = 0; k < 6; ++k) take(f.spans[c][6 * j + k]);
    }
    polylines(f.paths[c]);
    polylines(f.coils[c]);
  }
  f.marker_kinds.resize(count());
  f.markers.resize(3 * f.marker_kinds.size());
  for (std::size_t m = 0; m < f.marker_kinds.size(); ++m) {
    take(f.marker_kinds[m]);
    for (int k = 0; k < 3; ++k) take(f.markers[3 * m + k]);
  }
  EXPECT_EQ(at, message.size()) << "bytes left over";
  return f;
}

TEST(LiveScene, StepsAsReeveRunDoesBitForBitAndAgainAfterAReset) {
  LiveScene live(atwoodFile(), {});
  Scene run = loadScene(atwoodFile());
  for (int f = 0; f < 40; ++f) {
    live.stepFrame();
    test::frame(run);
  }
  const auto same = [&] {
    const World &a = *live.scene().world, &b = *run.world;
    EXPECT_EQ(a.time(), b.time());
    for (BodyId id = 0; id < a.bodyCount(); ++id) {
      EXPECT_EQ(a.body(id).x, b.body(id).x) << a.bodyDef(id).name;
      EXPECT_EQ(a.body(id).q.coeffs(), b.body(id).q.coeffs()) << a.bodyDef(id).name;
      EXPECT_EQ(a.body(id).v, b.body(id).v) << a.bodyDef(id).name;
    }
    for (int j = 0; j < 2; ++j) EXPECT_EQ(live.scene().cables->tension(0, j), run.cables->tension(0, j));
  };
  same();
  EXPECT_GT(run.cables->tension(0, 1), 10.0);  // the heavy side: a real load, not zeros
  ASSERT_FALSE(live.command(R"({"cmd": "reset"})"));
  EXPECT_EQ(live.sceneGeneration(), 2u);
  EXPECT_EQ(live.scene().world->time(), 0.0);
  for (int f = 0; f < 40; ++f) live.stepFrame();
  same();
}

// Three spools, three islands: on 2 threads sharing every run (as
// `reeve view --threads 2` would once they take 20 us), the same bits as
// reeve run on one.
TEST(LiveScene, StepsTheSameBitsOnTwoThreads) {
  const std::string file = std::string(REEVE_SCENES_DIR) + "/hybrid.json";
  LiveScene::Overrides two;
  two.threads = 2;
  LiveScene live(file, two);
  live.scene().world->setThreads(2, 0.0);
  Scene run = loadScene(file);
  run.world->setThreads(1);
  ASSERT_GE(run.world->islandCount(), 2);
  for (int f = 0; f < 60; ++f) {
    live.stepFrame();
    test::frame(run);
  }
  EXPECT_EQ(live.scene().world->threads(), 2);
  EXPECT_TRUE(live.scene().world->runsShared());
  const World &a = *live.scene().world, &b = *run.world;
  for (BodyId id = 0; id < a.bodyCount(); ++id) {
    EXPECT_EQ(a.body(id).x, b.body(id).x) << a.bodyDef(id).name;
    EXPECT_EQ(a.body(id).v, b.body(id).v) << a.bodyDef(id).name;
  }
}

TEST(LiveScene, FrameMessageHoldsTheStateAsTheWireFormatSays) {
  LiveScene live(atwoodFile(), {});
  for (int f = 0; f < 12; ++f) live.stepFrame();
  const Frame frame = readFrame(live.frameMessage());
  const World& world = *live.scene().world;
  const CableSystem& cables = *live.scene().cables;
  EXPECT_EQ(frame.generation, live.sceneGeneration());
  EXPECT_EQ(frame.frame, 12u);
  EXPECT_EQ(frame.t, world.time());
  EXPECT_EQ(frame.iterations, static_cast<std::uint32_t>(world.lastStepIterations()));
  ASSERT_EQ(frame.bodies.size(), 10u * world.bodyCount());
  for (BodyId id = 0; id < world.bodyCount(); ++id) {
    const BodyState& b = world.body(id);
    const double* v = &frame.bodies[10 * id];
    EXPECT_EQ(Vec3(v[0], v[1], v[2]), b.x);
    EXPECT_EQ(Eigen::Vector4d(v[3], v[4], v[5], v[6]), b.q.coeffs());  // x, y, z, w
    EXPECT_EQ(Vec3(v[7], v[8], v[9]), b.v);
  }
  ASSERT_EQ(frame.hinges.size(), 2u);
  EXPECT_EQ(frame.hinges[0], world.hingeAngle(0));
  EXPECT_LT(frame.hinges[0], -0.1);  // the wheel turned with the falling heavy box
  ASSERT_EQ(frame.joints.size(), 1u);
  ASSERT_EQ(frame.joints[0].size(), 4u);
  for (int j = 0; j < 2; ++j) {
    EXPECT_EQ(frame.joints[0][2 * j], cables.tension(0, j));
    EXPECT_EQ(frame.joints[0][2 * j + 1], cables.restLength(0, j));
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(frame.spans[0][6 * j + k], static_cast<float>(cables.startPoint(0, j)[k]));
      EXPECT_EQ(frame.spans[0][6 * j + 3 + k], static_cast<float>(cables.endPoint(0, j)[k]));
    }
  }
  // The path runs from the light box's tie point to the heavy box's.
  ASSERT_FALSE(frame.paths[0].empty());
  const std::vector<float>& first = frame.paths[0].front();
  const Vec3 light_tie = world.body(test::body(live.scene(), "light")).toWorld(Vec3(0, 0.1, 0));
  EXPECT_NEAR(first[0], light_tie.x(), 1e-6);
  EXPECT_NEAR(first[1], light_tie.y(), 1e-6);
  EXPECT_TRUE(frame.coils[0].empty());  // no spool
  // A marker at both ends of each span: the tie points green (attachment),
  // the wheel's two tangent points red (rolling), where the spans meet them.
  ASSERT_EQ(frame.marker_kinds.size(), 4u);
  int attachments = 0;
  for (std::size_t m = 0; m < 4; ++m) {
    attachments += frame.marker_kinds[m] == 1;
    EXPECT_TRUE(frame.marker_kinds[m] == 0 || frame.marker_kinds[m] == 1) << frame.marker_kinds[m];
  }
  EXPECT_EQ(attachments, 2);
  EXPECT_NEAR(frame.markers[0], light_tie.x(), 1e-6);
}

TEST(LiveScene, FrameMessageHoldsTheCoilOfASpoolsStoredCable) {
  LiveScene live(fs::path(REEVE_SCENES_DIR) / "spool.json", {});
  live.stepFrame();
  const Frame frame = readFrame(live.frameMessage());
  std::size_t coils = 0;
  for (const auto& cable : frame.coils) coils += cable.size();
  EXPECT_GE(coils, 1u);
  for (const auto& cable : frame.coils)
    for (const auto& coil : cable) EXPECT_GE(coil.size(), 6u);  // a spiral of points, not a dot
}

TEST(LiveScene, RefusesEveryMalformedCommandWithItsReasonAndChangesNothing) {
  LiveScene live(sceneFile("refusals", kFloating), {});
  for (int f = 0; f < 3; ++f) live.stepFrame();
  const std::string status = live.statusMessage(), frame = live.frameMessage();
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"", "not JSON"},
      {"{", "not JSON"},
      {"[1, 2]", "expected a JSON object"},
      {R"({"command": "play"})", "/cmd"},
      {R"({"cmd": 3})", "/cmd"},
      {R"({"cmd": "fly"})", "/cmd"},
      {R"({"cmd": "play", "now": true})", "/now"},
      {R"({"cmd": "step", "frames": 0})", "/frames"},
      {R"({"cmd": "step", "frames": 1.5})", "/frames"},
      {R"({"cmd": "set"})", "expected substeps"},
      {R"({"cmd": "set", "substeps": 0})", "/substeps"},
      {R"({"cmd": "set", "substeps": 100001})", "/substeps"},
      {R"({"cmd": "set", "substeps": 20, "iterations": -1})", "/iterations"},  // nothing of it applied
      {R"({"cmd": "set", "solver": "jacobi"})", "/solver"},
      {R"({"cmd": "set", "rtf": 0})", "/rtf"},
      {R"({"cmd": "set", "rtf": 1e400})", "not JSON"},
      {R"({"cmd": "drive", "hinge": 1, "target": 0.5})", "/hinge"},
      {R"({"cmd": "drive", "hinge": 0, "target": "up"})", "/target"},
      {R"({"cmd": "winch", "cable": 0, "speed": 1})", "no cables"},
      {R"({"cmd": "drag", "body": 2, "point": [0, 0, 0], "target": [1, 0, 0]})", "not dynamic"},
      {R"({"cmd": "drag", "body": -1, "point": [0, 0, 0], "target": [1, 0, 0]})", "/body"},
      {R"({"cmd": "drag", "body": 0, "point": [0, 0], "target": [1, 0, 0]})", "/point"},
      {R"({"cmd": "drag", "body": 0, "point": [0, 0, 0], "target": [1, null, 0]})", "/target"},
      {R"({"cmd": "drag", "body": 0, "point": [0, 0, 0], "target": [1e7, 0, 0]})", "/target"},
      {std::string(kMaxCommandBytes + 1, ' '), "at most"},
  };
  for (const auto& [command, says] : refused) {
    const auto error = live.command(command);
    ASSERT_TRUE(error) << command;
    EXPECT_NE(error->find(says), std::string::npos) << command << " -> " << *error;
  }
  EXPECT_EQ(live.statusMessage(), status);
  EXPECT_EQ(live.frameMessage(), frame);
  live.stepFrame();  // and no drag was left on: the box floats still
  EXPECT_EQ(live.scene().world->body(0).x, Vec3::Zero());
}

TEST(LiveScene, DragPullsABodyOntoItsTargetAndReleaseGivesBackItsLoad) {
  LiveScene live(sceneFile("drag", kFloating), {});
  BodyState& box = const_cast<World&>(*live.scene().world).body(0);
  box.applied_force = Vec3(0, 0, 0.25);  // a user's own push, which the drag adds to
  ASSERT_FALSE(live.command(R"({"cmd": "drag", "body": 0, "point": [0, 0, 0], "target": [1, 0, 0]})"));
  const double start_balance = energyLedger(live.scene()).balance_J();
  double farthest = 0.0, most_kinetic = 0.0;
  for (int f = 0; f < 120; ++f) {  // 2 s: a critically damped 1.5 Hz spring settles in about 0.5 s
    live.stepFrame();
    farthest = std::max(farthest, box.x.x());
    // The ledger books the drag as an applied load's work: the box's
    // kinetic energy (up to about 1 J here) is not energy created.
    const EnergyLedger e = energyLedger(live.scene());
    most_kinetic = std::max(most_kinetic, e.kinetic_J);
    EXPECT_LE(e.balance_J() - start_balance, 1e-3 * std::max(e.kinetic_J, 1e-3)) << "frame " << f;
  }
  EXPECT_GT(most_kinetic, 0.1);  // it moved: a balance that could fail
  EXPECT_NEAR(box.x.x(), 1.0, 1e-3);
  EXPECT_LT(farthest, 1.02);  // no overshoot past 2 % of the pull
  EXPECT_NEAR(box.x.y(), 0.0, 1e-12);
  ASSERT_FALSE(live.command(R"({"cmd": "release"})"));
  EXPECT_EQ(box.applied_force, Vec3(0, 0, 0.25));
  EXPECT_EQ(box.applied_torque, Vec3::Zero());
}

TEST(LiveScene, DriveTargetAndBudgetApplyAndTheBudgetOutlivesAReset) {
  LiveScene live(sceneFile("drive", kFloating), {});
  ASSERT_FALSE(live.command(R"({"cmd": "drive", "hinge": 0, "target": 0.5})"));
  for (int f = 0; f < 5; ++f) live.stepFrame();
  EXPECT_NEAR(live.scene().world->hingeAngle(0), 0.5, 1e-9);  // a rigid drive meets its target
  ASSERT_FALSE(live.command(R"({"cmd": "set", "substeps": 7, "iterations": 3, "solver": "gauss-seidel", "rtf": 0.5})"));
  ASSERT_FALSE(live.command(R"({"cmd": "reset"})"));
  const SolverSettings& s = live.scene().world->settings();
  EXPECT_EQ(s.substeps, 7);
  EXPECT_EQ(s.iterations, 3);
  EXPECT_EQ(s.solver, SolverKind::GaussSeidel);
  EXPECT_EQ(live.realTimeFactor(), 0.5);
  EXPECT_EQ(live.scene().world->hinge(0).drive.target, 0.0);  // the scene's own again
}

TEST(LiveScene, AWinchCommandReelsAtItsSpeedInsteadOfItsSchedule) {
  // The crane's luffing winch: its schedule holds still until 3 s; told
  // 0.1 m/s (of at most 0.2), it reels in 0.1 m of rope a second. (A
  // winch starts at once: the jerk pulls the rope up to the winch's 30 kN
  // for a few substeps, in which it stalls and pays out, as the scene
  // says; timed after that.)
  LiveScene live(fs::path(REEVE_SCENES_DIR) / "crane.json", {});
  const int luff = test::cable(live.scene(), "luff");
  const auto stored = [&] { return live.scene().cables->cables()[luff].links.back().stored; };
  const auto refused = live.command(R"({"cmd": "winch", "cable": )" + std::to_string(luff) + R"(, "speed": 0.5})");
  ASSERT_TRUE(refused);
  EXPECT_NE(refused->find("/speed"), std::string::npos) << *refused;
  for (int f = 0; f < 5; ++f) live.stepFrame();
  const double still = stored();
  ASSERT_FALSE(live.command(R"({"cmd": "winch", "cable": )" + std::to_string(luff) + R"(, "speed": 0.1})"));
  for (int f = 0; f < 5; ++f) live.stepFrame();
  EXPECT_GT(stored(), still);  // the schedule would have held it
  const double before = stored();
  for (int f = 0; f < 60; ++f) live.stepFrame();
  EXPECT_NEAR(stored() - before, 0.1, 1e-9);
  const double pull = live.scene().cables->winchPull(luff);  // holding the boom, not stalled: the speed holds
  EXPECT_GT(pull, 0.0);
  EXPECT_LT(pull, 30000.0);
}

TEST(LiveScene, TellsWhereAFrictionWrapBeginsToSlipAndNotWhereItHolds) {
  // capstan.json: mu 0.3 over half a turn bounds the tension ratio at
  // exp(0.3 pi) = 2.57 < 3 kg / 1 kg, so 'slipping_rope' slides from the
  // start and on; the bollard's wrap (bound 16.9 > 15) and the hole's
  // (1.87 > 1.5) hold.
  LiveScene live(fs::path(REEVE_SCENES_DIR) / "capstan.json", {});
  std::vector<std::string> events;
  for (int f = 0; f < 60; ++f) {
    live.stepFrame();
    for (const std::string& m : live.takeEventMessages()) events.push_back(m.substr(5));
  }
  int slips = 0;
  for (const std::string& e : events) {
    EXPECT_EQ(e.find("sticks"), std::string::npos) << e;  // none stops, once sliding
    if (e.find(R"("event":"slips")") == std::string::npos) continue;
    ++slips;
    EXPECT_NE(e.find(R"("cable":"slipping_rope")"), std::string::npos) << e;
    EXPECT_NE(e.find(R"("link":1)"), std::string::npos) << e;
  }
  EXPECT_EQ(slips, 1);
}

TEST(LiveScene, PausesOnceAtTheScenesDurationAndStepsOnlyWhatIsAsked) {
  LiveScene live(sceneFile("duration", kFloating), {});
  ASSERT_TRUE(live.playing());
  for (int f = 0; f < 120; ++f) live.stepFrame();  // 2 s at 60 Hz
  EXPECT_FALSE(live.playing());
  ASSERT_FALSE(live.command(R"({"cmd": "play"})"));
  live.stepFrame();
  EXPECT_TRUE(live.playing());  // once only
  ASSERT_FALSE(live.command(R"({"cmd": "step", "frames": 3})"));
  EXPECT_FALSE(live.playing());
  EXPECT_EQ(live.stepsWanted(), 3);
  live.stepFrame();
  EXPECT_EQ(live.stepsWanted(), 2);
}

TEST(LiveScene, ABrokenBookkeepingPausesWithTheReasonAndResetStartsAgain) {
  // The gear whose spool holds no cable (tests/test_cli.cpp): its weight
  // pays out what the spool does not hold within a frame.
  LiveScene live(fs::path(REEVE_TEST_SCENES_DIR) / "gear_spool_runs_out.json", {});
  for (int f = 0; f < 30 && !live.failure(); ++f) live.stepFrame();
  ASSERT_TRUE(live.failure());
  EXPECT_NE(live.failure()->find("Its rolling end ran out of cable"), std::string::npos) << *live.failure();
  EXPECT_FALSE(live.playing());
  EXPECT_NE(live.statusMessage().find("ran out of cable"), std::string::npos);
  const double stopped = live.scene().world->time();
  ASSERT_FALSE(live.command(R"({"cmd": "step"})"));
  live.stepFrame();  // nothing: it stays where it failed
  EXPECT_EQ(live.scene().world->time(), stopped);
  ASSERT_FALSE(live.command(R"({"cmd": "play"})"));
  EXPECT_FALSE(live.playing());
  ASSERT_FALSE(live.command(R"({"cmd": "reset"})"));
  EXPECT_FALSE(live.failure());
  EXPECT_TRUE(live.playing());
  EXPECT_EQ(live.scene().world->time(), 0.0);
}

TEST(LiveScene, AnInvalidReloadIsRefusedAndTheOldSceneRunsOn) {
  LiveScene live(atwoodFile(), {});
  live.stepFrame();
  const std::string frame = live.frameMessage();
  try {
    live.reload(R"({"name": "x", "solver": {}, "bodies": [{"name": "b", "mass_kg": -1}]})");
    FAIL() << "a negative mass loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.jsonPath().rfind("/bodies/0", 0), 0u) << e.what();
  }
  EXPECT_EQ(live.sceneGeneration(), 1u);
  EXPECT_EQ(live.frameMessage(), frame);
}

}  // namespace
}  // namespace reeve::test_live_scene
