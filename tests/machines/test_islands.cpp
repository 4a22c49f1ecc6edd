// Islands (issue 30): which bodies the constraints join into one, each
// island moving as mechanics says when solved on its own, and the same
// bits on any number of threads (World::setThreads).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "reeve/machines/machines.h"
#include "reeve/scene/scene.h"
#include "state_bytes.h"

namespace reeve::test_islands {
namespace {

using test::eventBytes;
using test::stateBytes;

using machines::ScalingSpec;
using machines::StaticMachine;

constexpr double kG = 10.0;

// Machine k's right box (kg): 1 to 2.5, so that the islands differ.
double rightMass(int k) { return 1.0 + 0.5 * (k % 4); }

// K Atwood machines side by side (machines::islands): 1 kg on the left,
// rightMass(k) on the right of a 2 kg solid wheel of 0.3 m on a hinge.
StaticMachine atwoods(int count, SolverKind solver, int iterations, int threads) {
  ScalingSpec spec;
  spec.count = count;
  spec.load_kg = 1.0;
  spec.gravity = kG;
  spec.budget = {10, iterations, solver};
  StaticMachine m = machines::islands(spec);
  World& world = *m.scene.world;
  for (int k = 0; k < count; ++k) world.setMass(*world.findBody("right" + std::to_string(k)), rightMass(k));
  world.setThreads(threads, 0.0);  // shared however short the runs
  return m;
}

TEST(Islands, MachinesHungFromOneAnchorAreIslandsOfTheirOwn) {
  StaticMachine m = atwoods(64, SolverKind::Direct, 2, 1);
  World& world = *m.scene.world;
  ASSERT_EQ(world.islandCount(), 64);
  for (int k = 0; k < 64; ++k) {
    // Each island: its wheel and its two boxes (the static world joins none).
    const std::vector<BodyId> expected{*world.findBody("wheel" + std::to_string(k)),
                                       *world.findBody("left" + std::to_string(k)),
                                       *world.findBody("right" + std::to_string(k))};
    std::vector<BodyId> sorted = expected;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(world.islandBodies(k), sorted) << "machine " << k;
  }
}

TEST(Islands, JointsCablesContactsAndKinematicBodiesJoinIslandsStaticOnesDoNot) {
  World world;
  BodyDef box;
  box.shape = Shape::box(Vec3::Constant(0.1));
  box.mass = 1.0;
  std::vector<BodyId> ids;
  for (int i = 0; i < 8; ++i) {
    box.position = Vec3(2.0 * i, 0.0, 0.0);
    box.collides = i == 4 || i == 6;  // far apart, but they may meet within a step
    ids.push_back(world.addBody(box));
  }
  BodyDef anchor = box;
  anchor.is_static = true;
  anchor.collides = false;
  const BodyId fixed = world.addBody(anchor);
  const auto distance = [&](BodyId a, BodyId b) {
    DistanceConstraint c;
    c.a = a, c.b = b, c.rest_length = 2.0;
    world.addDistance(c);
  };
  distance(ids[0], ids[1]);
  distance(fixed, ids[2]);  // a static anchor joins nothing
  distance(fixed, ids[3]);
  world.addHinge({ids[5], kWorldBody, Vec3(10.0, 0.0, 0.0), Vec3::UnitZ()});
  world.coupleBodies({ids[2], kWorldBody, ids[7]});
  EXPECT_EQ(world.islandCount(), 5);  // {0 1} {2 7} {3} {4 6} {5}
  EXPECT_EQ(world.islandBodies(0), (std::vector<BodyId>{0, 1}));
  EXPECT_EQ(world.islandBodies(1), (std::vector<BodyId>{2, 7}));
  EXPECT_EQ(world.islandBodies(3), (std::vector<BodyId>{4, 6}));
  // A kinematic body joins what it touches: the constraints write its
  // impulses (the work it does).
  BodyDef carrier = box;
  carrier.collides = false;
  carrier.motion = {MotionKeyframe{0.0, Vec3(1.0, 0.0, 0.0), Vec3::Zero()}};
  const BodyId moved = world.addBody(carrier);
  distance(moved, ids[3]);
  distance(moved, ids[5]);
  EXPECT_EQ(world.islandCount(), 4);
  EXPECT_EQ(world.islandBodies(2), (std::vector<BodyId>{3, 5, moved}));
  // A span moved in place onto another body (as a cable's does) is found.
  world.distance(0).b = ids[4];
  EXPECT_EQ(world.islandCount(), 4);
  EXPECT_EQ(world.islandBodies(0), (std::vector<BodyId>{0, 4, 6}));
  EXPECT_EQ(world.islandBodies(1), (std::vector<BodyId>{1}));
  EXPECT_THROW(world.coupleBodies({ids[0], 99}), std::invalid_argument);
  EXPECT_THROW(world.setThreads(0), std::invalid_argument);
}

// Threads share the runs only while the islands' work a run reaches the
// minimum. A run here is a whole step (World::runsWholeSteps): 64
// machines' (about 1 ms on one thread) pass 1 us, 2 machines' (about 30 us,
// a few ms under the sanitizers) never reach 100 ms, and a minimum of 0
// always shares.
TEST(Islands, RunsAreSharedOnlyWhereTheyPay) {
  const auto shared = [](int machines, double min_us) {
    StaticMachine m = atwoods(machines, SolverKind::Direct, 2, 2);
    m.scene.world->setThreads(2, min_us);
    for (int f = 0; f < 3; ++f) m.scene.world->step(1.0 / 60.0);
    return m.scene.world->runsShared();
  };
  EXPECT_TRUE(shared(64, 1.0));
  EXPECT_FALSE(shared(2, 1e5));
  EXPECT_TRUE(shared(2, 0.0));
  World world;
  EXPECT_THROW(world.setThreads(2, -1.0), std::invalid_argument);
  EXPECT_THROW(world.setThreads(2, std::nan("")), std::invalid_argument);
}

// Each island solved on its own still moves as the closed form says: a =
// (m2 - m1) g / (m1 + m2 + M / 2), and semi-implicit Euler gives v = a t
// exactly under constant acceleration.
TEST(Islands, EachAtwoodMachineMeetsItsClosedFormOnTwoThreads) {
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel}) {
    StaticMachine m = atwoods(16, solver, solver == SolverKind::Direct ? 2 : 40, 2);
    World& world = *m.scene.world;
    const int frames = 30;
    for (int f = 0; f < frames; ++f) world.step(1.0 / 60.0);
    const double t = frames / 60.0;
    for (int k = 0; k < 16; ++k) {
      const double m1 = 1.0, m2 = rightMass(k), a = (m2 - m1) * kG / (m1 + m2 + 1.0);
      const double v = world.body(*world.findBody("right" + std::to_string(k))).v.y();
      const double tolerance = solver == SolverKind::Direct ? 1e-9 : 1e-4;
      EXPECT_NEAR(v, -a * t, tolerance * (1.0 + a * t)) << (solver == SolverKind::Direct ? "direct" : "gauss-seidel")
                                                        << ", machine " << k;
    }
  }
}

// More threads than this machine's cores: a thread the OS holds back
// leaves its run's islands to the others (World::forEachIsland), each
// island still stepped once a pass.
TEST(Islands, AnyNumberOfThreadsGivesTheSameBits) {
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel}) {
    std::vector<std::vector<unsigned char>> runs;
    for (const int threads : {1, 2, 3, 8, 1}) {
      StaticMachine m = atwoods(24, solver, 4, threads);
      std::vector<unsigned char> all;
      for (int f = 0; f < 40; ++f) {
        m.scene.world->step(1.0 / 60.0);
        const std::vector<unsigned char> now = stateBytes(m.scene);
        all.insert(all.end(), now.begin(), now.end());
      }
      runs.push_back(std::move(all));
    }
    for (std::size_t r = 1; r < runs.size(); ++r)
      EXPECT_TRUE(runs[r] == runs[0]) << (solver == SolverKind::Direct ? "direct" : "gauss-seidel") << ", run " << r;
  }
}

// Where an island's bodies lie among the world's ids changes none of its
// bits. The direct solver finds a body's slot in a window over its
// island's ids, or by search where they lie far apart
// (DirectSolver::slotOf): here every wheel listed first, then every left
// box, then every right one, so that machine k's ids are k, 100 + k and
// 200 + k, against the machines listed one after another.
TEST(Islands, AMachineEndsOnTheSameBitsWhereverItsBodiesIdsLie) {
  constexpr int kMachines = 100;
  const auto sceneText = [&](bool grouped) {
    std::vector<std::string> wheels, lefts, rights, hinges, cables;
    for (int k = 0; k < kMachines; ++k) {
      const std::string n = std::to_string(k), x = std::to_string(1.0 * k);
      const std::string xl = std::to_string(1.0 * k - 0.3), xr = std::to_string(1.0 * k + 0.3);
      wheels.push_back(R"({"name": "wheel)" + n + R"(", "shape": {"type": "cylinder", "radius_m": 0.3, "half_length_m": 0.05}, "mass_kg": 2, "position_m": [)" + x + ", 0, 0]}");
      lefts.push_back(R"({"name": "left)" + n + R"(", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": 1, "position_m": [)" + xl + ", -2, 0]}");
      rights.push_back(R"({"name": "right)" + n + R"(", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": )" + std::to_string(rightMass(k)) + R"(, "position_m": [)" + xr + ", -2, 0]}");
      hinges.push_back(R"({"body": "wheel)" + n + R"(", "other": "world", "anchor_m": [)" + x + R"(, 0, 0], "axis": [0, 0, 1]})");
      cables.push_back(R"({"name": "rope)" + n + R"(", "links": [{"body": "left)" + n + R"(", "type": "attachment", "point_m": [0, 0.1, 0]}, {"body": "wheel)" + n + R"(", "type": "rolling", "orientation": "cw"}, {"body": "right)" + n + R"(", "type": "attachment", "point_m": [0, 0.1, 0]}]})");
    }
    std::vector<std::string> bodies;
    if (grouped) {
      for (const auto* list : {&wheels, &lefts, &rights}) bodies.insert(bodies.end(), list->begin(), list->end());
    } else {
      for (int k = 0; k < kMachines; ++k) bodies.insert(bodies.end(), {wheels[k], lefts[k], rights[k]});
    }
    const auto joined = [](const std::vector<std::string>& items) {
      std::string out;
      for (const std::string& item : items) out += (out.empty() ? "" : ",\n") + item;
      return out;
    };
    return R"({"name": "atwoods", "solver": {"frame_rate_hz": 60, "substeps": 10, "iterations": 4, "gravity_m_per_s2": [0, -10, 0]},
               "duration_s": 1, "bodies": [)" + joined(bodies) + R"(], "hinges": [)" + joined(hinges) +
           R"(], "cables": [)" + joined(cables) + "]}";
  };
  Scene listed = parseScene(sceneText(false), "machines one after another");
  Scene grouped = parseScene(sceneText(true), "wheels, then left boxes, then right boxes");
  ASSERT_EQ(grouped.world->islandCount(), kMachines);
  for (int f = 0; f < 30; ++f) {
    listed.world->step(1.0 / 60.0);
    grouped.world->step(1.0 / 60.0);
  }
  const auto same = [](const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (int k = 0; k < kMachines; ++k) {
    for (const std::string body : {"wheel", "left", "right"}) {
      const BodyState& a = listed.world->body(*listed.world->findBody(body + std::to_string(k)));
      const BodyState& b = grouped.world->body(*grouped.world->findBody(body + std::to_string(k)));
      EXPECT_TRUE(same(a.x, b.x) && same(a.q.coeffs(), b.q.coeffs()) && same(a.v, b.v) && same(a.omega, b.omega))
          << body << k;
    }
    const auto tension = [&](const Scene& s) {
      return s.world->pathTension(s.cables->cables()[k].joints.front().path);
    };
    EXPECT_TRUE(same(tension(listed), tension(grouped))) << "rope" << k;
    // And each moves as mechanics says: a = (m2 - m1) g / (m1 + m2 + M / 2)
    // from rest, v = a t exactly under constant acceleration (as in
    // EachAtwoodMachineMeetsItsClosedFormOnTwoThreads); m2 = m1 stays put.
    const double a = (rightMass(k) - 1.0) * kG / (1.0 + rightMass(k) + 1.0), t = 0.5;
    EXPECT_NEAR(grouped.world->body(*grouped.world->findBody("right" + std::to_string(k))).v.y(), -a * t,
                1e-9 * (1.0 + a * t))
        << "machine " << k;
  }
}

// Scenes with events in their islands: a spool that runs out and jams (a
// joint added within a step), cables that merge and split, friction that
// asks for a solve again, contacts, winches, elastic cables, hybrid links
// running out, spring hinges; hybrid and elastic have several islands.
TEST(Islands, ShippedScenesGiveTheSameBitsOnOneAndTwoThreads) {
  for (const char* name : {"merge_split", "capstan", "contacts", "crane", "gym", "hand", "spool", "hybrid", "elastic",
                           "servin", "bow"}) {
    std::vector<std::vector<unsigned char>> runs;
    for (const int threads : {1, 2}) {
      Scene scene = loadScene(std::string(REEVE_SCENES_DIR) + "/" + name + ".json");
      scene.world->setThreads(threads, 0.0);
      if (std::string(name) == "hybrid" || std::string(name) == "elastic") {
        EXPECT_GE(scene.world->islandCount(), 2) << name;
      }
      std::vector<unsigned char> all;
      for (int f = 0; f < 60; ++f) {
        scene.world->step(1.0 / scene.frame_rate_hz);
        const std::vector<unsigned char> now = stateBytes(scene);
        all.insert(all.end(), now.begin(), now.end());
        const std::vector<unsigned char> events = eventBytes(scene.cables->takeEvents());
        all.insert(all.end(), events.begin(), events.end());
      }
      runs.push_back(std::move(all));
    }
    EXPECT_TRUE(runs[1] == runs[0]) << name;
  }
}

}  // namespace
}  // namespace reeve::test_islands
