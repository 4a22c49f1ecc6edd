// Determinism, a guarantee (README): the same build on the same machine
// with the same inputs gives the same numbers, bit for bit. Here: every
// shipped scene loaded twice in one process and stepped 20 frames; its
// CSV from two processes is in tests/test_cli_outputs.cpp.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "reeve/scene/scene.h"

namespace reeve::test_determinism {
namespace {

// Every double of the state a run reports: bodies' position, orientation,
// velocities; cables' tension, rest length, length and stored cable.
std::vector<double> state(const Scene& s) {
  std::vector<double> out;
  const World& w = *s.world;
  for (BodyId b = 0; b < w.bodyCount(); ++b) {
    const BodyState& x = w.body(b);
    for (const double v : {x.x.x(), x.x.y(), x.x.z(), x.q.w(), x.q.x(), x.q.y(), x.q.z(), x.v.x(), x.v.y(),
                           x.v.z(), x.omega.x(), x.omega.y(), x.omega.z()})
      out.push_back(v);
  }
  for (int c = 0; c < static_cast<int>(s.cables->cables().size()); ++c) {
    const Cable& cable = s.cables->cables()[c];
    for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j)
      for (const double v : {s.cables->tension(c, j), s.cables->restLength(c, j), s.cables->length(c, j)})
        out.push_back(v);
    for (const Link& l : cable.links) out.push_back(l.stored);
  }
  return out;
}

TEST(Determinism, EveryShippedSceneStepsToTheSameBitsTwiceInOneProcess) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(REEVE_SCENES_DIR)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "scene.schema.json") continue;
    SCOPED_TRACE(entry.path().filename().string());
    Scene a = loadScene(entry.path()), b = loadScene(entry.path());
    for (int f = 0; f < 20; ++f) {
      a.world->step(1.0 / a.frame_rate_hz);
      b.world->step(1.0 / b.frame_rate_hz);
    }
    const std::vector<double> sa = state(a), sb = state(b);
    ASSERT_EQ(sa.size(), sb.size());
    EXPECT_EQ(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(double)), 0);
    ++scenes;
  }
  EXPECT_GE(scenes, 17);
}

// A solve done again (World::ResolveCheck: cable/ asks when a friction
// link's stick or slip turns out wrong) starts from exactly what the first
// one started from: the poses, the contacts and their anchors, the springs'
// previous errors. Asked to solve every substep twice, every shipped scene
// ends on the same bits as solved once.
TEST(Determinism, ASolveDoneAgainStartsFromWhatTheFirstStartedFrom) {
  for (const auto& entry : std::filesystem::directory_iterator(REEVE_SCENES_DIR)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "scene.schema.json") continue;
    SCOPED_TRACE(entry.path().filename().string());
    Scene once = loadScene(entry.path()), twice = loadScene(entry.path());
    long calls = 0;
    twice.world->addResolveCheck([&](World&, double) { return calls++ % 2 == 0; });
    for (int f = 0; f < 20; ++f) {
      once.world->step(1.0 / once.frame_rate_hz);
      twice.world->step(1.0 / twice.frame_rate_hz);
    }
    EXPECT_GE(calls, 40);
    const std::vector<double> a = state(once), b = state(twice);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
  }
}

}  // namespace
}  // namespace reeve::test_determinism
