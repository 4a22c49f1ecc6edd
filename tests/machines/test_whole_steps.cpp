// Whole steps (issue 30): where nothing joins the islands within a step
// (World::runsWholeSteps), each island runs all the substeps of a step in
// one run, and the threads join once a step instead of twice a substep. An
// island whose cables have news (an event, a jam, a broken invariant)
// stops before that substep's solve and goes on substep by substep with
// the World. None of it may change a bit: each scene is stepped here both
// ways, on one thread and two, a frame a step and a whole second in one
// step (where the islands' events fall on different substeps of it).
#include <fenv.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "reeve/machines/machines.h"
#include "reeve/scene/scene.h"
#include "state_bytes.h"

namespace reeve::test_whole_steps {
namespace {

using machines::StaticMachine;
using test::eventBytes;
using test::stateBytes;

// A substep hook that does nothing and does not run whole steps
// (IslandHook::whole_steps false): the World then steps substep by substep.
void stepSubstepBySubstep(World& world) {
  world.addSubstepHook([](World&, double) {});
}

struct SceneRun {
  std::vector<unsigned char> bytes;
  bool whole = false;  // runsWholeSteps() at the start
  std::vector<CableEvent> events;
};

// `frames` of the scene, `per_step` frames a step (with as many times the
// substeps, so the same substep h), under the scene's solver or `solver`.
SceneRun runScene(const std::filesystem::path& path, bool whole, int threads, int frames, int per_step,
                  std::optional<SolverKind> solver = std::nullopt) {
  Scene scene = loadScene(path);
  World& world = *scene.world;
  if (solver) world.settings().solver = *solver;
  world.setThreads(threads, 0.0);
  if (!whole) stepSubstepBySubstep(world);
  world.settings().substeps *= per_step;
  world.islandCount();
  SceneRun run;
  run.whole = world.runsWholeSteps();
  for (int f = 0; f < frames; f += per_step) {
    world.step(per_step / scene.frame_rate_hz);
    const std::vector<unsigned char> now = stateBytes(scene);
    run.bytes.insert(run.bytes.end(), now.begin(), now.end());
    const std::vector<CableEvent> events = scene.cables->takeEvents();
    run.events.insert(run.events.end(), events.begin(), events.end());
    const std::vector<unsigned char> listed = eventBytes(events);
    run.bytes.insert(run.bytes.end(), listed.begin(), listed.end());
  }
  return run;
}

TEST(WholeSteps, EveryShippedSceneEndsOnTheSameBitsAsSubstepBySubstep) {
  std::set<std::string> whole;
  for (const auto& entry : std::filesystem::directory_iterator(REEVE_SCENES_DIR)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "scene.schema.json") continue;
    const std::string name = entry.path().stem().string();
    SCOPED_TRACE(name);
    for (const int per_step : {1, 60}) {
      const SceneRun by_substep = runScene(entry.path(), false, 1, 60, per_step);
      ASSERT_FALSE(by_substep.whole);
      for (const int threads : {1, 2}) {
        const SceneRun run = runScene(entry.path(), true, threads, 60, per_step);
        if (!run.whole) break;  // the same stepping as by_substep
        whole.insert(name);
        EXPECT_TRUE(run.bytes == by_substep.bytes) << threads << " threads, " << per_step << " frames a step";
      }
    }
  }
  std::string listed;
  for (const std::string& name : whole) listed += name + " ";
  std::printf("[ measured ] scenes run in whole steps: %s\n", listed.c_str());
  // A spool that runs out and jams (a joint added within a step), hybrid
  // links running out on several islands, elastic cables, drives, springs.
  for (const char* name : {"atwood", "spool", "hybrid", "elastic", "gym", "hilbert3", "springs"})
    EXPECT_TRUE(whole.count(name)) << name;
}

// The same under Gauss-Seidel, whose island solve (sweeps, each span's
// ends read from the cable update) is not the direct solver's: the scenes
// that run whole under their own solver, each switched to Gauss-Seidel.
TEST(WholeSteps, EveryShippedSceneUnderGaussSeidelEndsOnTheSameBitsAsSubstepBySubstep) {
  for (const char* name : {"atwood", "spool", "hybrid", "elastic", "gym", "hilbert2_loose", "hilbert3", "springs",
                           "motor_belt", "square_wheel", "wheels_3d"}) {
    SCOPED_TRACE(name);
    const std::filesystem::path path = std::string(REEVE_SCENES_DIR) + "/" + name + ".json";
    for (const int per_step : {1, 60}) {
      const SceneRun by_substep = runScene(path, false, 1, 60, per_step, SolverKind::GaussSeidel);
      for (const int threads : {1, 2}) {
        const SceneRun run = runScene(path, true, threads, 60, per_step, SolverKind::GaussSeidel);
        ASSERT_TRUE(run.whole);
        EXPECT_TRUE(run.bytes == by_substep.bytes) << threads << " threads, " << per_step << " frames a step";
      }
    }
  }
}

// The scene with events on several islands: stepped a second at a time,
// islands stop for their news at different substeps of one step, and
// every event keeps its time and its place in the list.
TEST(WholeSteps, IslandsWithNewsAtDifferentSubstepsOfOneStepKeepEveryEvent) {
  const std::filesystem::path path = std::string(REEVE_SCENES_DIR) + "/hybrid.json";
  const SceneRun by_substep = runScene(path, false, 1, 120, 60), whole = runScene(path, true, 2, 120, 60);
  ASSERT_TRUE(whole.whole);
  EXPECT_TRUE(whole.bytes == by_substep.bytes);
  // Two cables on different islands with events at different times of
  // one step (a second): the case the test is for.
  Scene scene = loadScene(path);
  scene.world->islandCount();
  const auto island = [&](int cable) {
    for (const Link& link : scene.cables->cables()[cable].links)
      if (const int i = scene.world->islandOfBody(link.body); i >= 0) return i;
    return -1;
  };
  std::map<int, std::set<double>> times;  // per step, the event times
  std::map<int, std::set<int>> islands;   // per step, the islands with events
  for (const CableEvent& e : whole.events) {
    const int step = static_cast<int>(std::floor(e.time_s - 1e-9));
    times[step].insert(e.time_s);
    islands[step].insert(island(e.cable));
  }
  bool met = false;
  for (const auto& [step, in] : islands) met |= in.size() >= 2 && times[step].size() >= 2;
  EXPECT_TRUE(met) << whole.events.size() << " events";
}

// K Atwood machines side by side (machines::islands), 1 kg and 1 to 2.5 kg
// on a 2 kg solid wheel of 0.3 m: a = (m2 - m1) g / (m1 + m2 + M / 2).
StaticMachine atwoods(int count, int substeps, int threads) {
  machines::ScalingSpec spec;
  spec.count = count;
  spec.load_kg = 1.0;
  spec.gravity = 10.0;
  spec.budget = {substeps, 2, SolverKind::Direct};
  StaticMachine m = machines::islands(spec);
  World& world = *m.scene.world;
  for (int k = 0; k < count; ++k)
    world.setMass(*world.findBody("right" + std::to_string(k)), 1.0 + 0.5 * (k % 4));
  world.setThreads(threads, 0.0);
  return m;
}

// The interrupt flag raised while the islands run their substeps, each on
// its own: those behind are stepped up to the one furthest on, so all end
// at one time; stepped on with the flag lowered, every machine still
// meets its closed form at the World's time (an island a substep behind
// or ahead would be h a off). The flag is raised from the progress the
// step's own thread reports: on two threads, under load, the other
// thread's islands may all have run to the frame's end by then (once in
// 25 runs beside two busy cores), and the frame then ends there, every
// island with it; the cut itself is asserted on one thread.
TEST(WholeSteps, AnInterruptedStepEndsEveryIslandAtOneTime) {
  for (const int threads : {1, 2}) {
    SCOPED_TRACE(threads);
    StaticMachine m = atwoods(16, 40, threads);
    World& world = *m.scene.world;
    std::atomic<int> flag{0};
    world.setInterruptFlag(&flag);
    world.setSubstepProgress([&](int done, int) {
      if (done >= 3) flag = 1;
    });
    const double dt = 1.0 / 60.0, h = dt / 40;
    world.step(dt);
    ASSERT_TRUE(world.runsWholeSteps());
    const double cut_at = world.time() / h;  // substeps run
    EXPECT_NEAR(cut_at, std::round(cut_at), 1e-9);
    EXPECT_GE(std::round(cut_at), 3.0);
    EXPECT_LE(std::round(cut_at), 40.0);
    if (threads == 1) {
      EXPECT_TRUE(world.stepInterrupted());
      EXPECT_LT(std::round(cut_at), 40.0);
    }
    flag = 0;
    world.setSubstepProgress({});
    for (int f = 0; f < 30; ++f) world.step(dt);
    EXPECT_FALSE(world.stepInterrupted());
    const double t = world.time();
    for (int k = 0; k < 16; ++k) {
      const double m2 = 1.0 + 0.5 * (k % 4), a = (m2 - 1.0) * 10.0 / (1.0 + m2 + 1.0);
      const BodyId left = *world.findBody("left" + std::to_string(k));
      EXPECT_NEAR(world.body(left).v.y(), a * t, 1e-9 * (1.0 + a * t)) << "machine " << k;
    }
    world.setInterruptFlag(nullptr);
  }
}

// The first non-finite value is the one a scan of the whole World after
// each pass finds: the lowest body at the earliest pass, whichever island
// found its own first.
TEST(WholeSteps, TheFirstNonFiniteValueIsTheSameAsSubstepBySubstep) {
  struct TrapsOff {  // the NaNs here are on purpose (fp_main.cpp traps them)
    int traps = fedisableexcept(FE_ALL_EXCEPT);
    ~TrapsOff() { feenableexcept(traps); }
  } traps_off;
  // Both made non-finite between frames: the first substep's integration
  // spreads each to its body's pose (x += h v, the turn by h omega), so the
  // first found is the lower of the two ids, at the end of that substep,
  // its position (left6) or orientation (right5) first.
  std::vector<NonFiniteState> found;
  for (const bool whole : {false, true}) {
    StaticMachine m = atwoods(8, 10, 2);
    World& world = *m.scene.world;
    if (!whole) stepSubstepBySubstep(world);
    world.step(1.0 / 60.0);
    EXPECT_EQ(world.runsWholeSteps(), whole);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const BodyId right5 = *world.findBody("right5"), left6 = *world.findBody("left6");
    world.body(right5).omega.z() = nan;
    world.body(left6).v.y() = nan;
    world.step(1.0 / 60.0);
    ASSERT_TRUE(world.firstNonFinite().has_value());
    const NonFiniteState& first = *world.firstNonFinite();
    EXPECT_EQ(first.body, std::min(right5, left6));
    EXPECT_EQ(first.quantity,
              right5 < left6 ? NonFiniteState::Quantity::Orientation : NonFiniteState::Quantity::Position);
    EXPECT_NEAR(first.time_s, 1.0 / 60.0 + 1.0 / 600.0, 1e-12);
    found.push_back(first);
  }
  EXPECT_EQ(found[0].time_s, found[1].time_s);
}

// Whole steps only where nothing joins the islands within a step.
TEST(WholeSteps, RunOnlyWhereNothingJoinsTheIslandsWithinAStep) {
  const auto whole = [](const std::function<void(World&)>& change) {
    StaticMachine m = atwoods(4, 10, 1);
    change(*m.scene.world);
    m.scene.world->step(1.0 / 60.0);
    return m.scene.world->runsWholeSteps();
  };
  EXPECT_TRUE(whole([](World&) {}));
  EXPECT_FALSE(whole([](World& w) { stepSubstepBySubstep(w); }));
  EXPECT_FALSE(whole([](World& w) { w.setGround(GroundPlane{}); }));  // contacts are found each substep
  EXPECT_FALSE(whole([](World& w) { w.addResolveCheck([](World&, double) { return false; }); }));
  EXPECT_FALSE(whole([](World& w) {  // a braked drive's assembly is found with the World's scratch
    HingeDrive& d = w.hinge(0).drive;
    d.mode = HingeDrive::Mode::Angle;
    d.max_torque = 100.0;
  }));
}

}  // namespace
}  // namespace reeve::test_whole_steps
