// Scenes stepped side by side (issue 30; tools/src/batch.h): the thread
// pool runs every index once, and a scene stepped in a batch on any number
// of threads ends on the same bits as stepped alone.
#include <gtest/gtest.h>
#include <sched.h>

#include <atomic>
#include <cfenv>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "batch.h"
#include "reeve/engine/thread_pool.h"
#include "scene_fixture.h"

namespace reeve::test_batch {
namespace {

TEST(ThreadPool, RunsEveryIndexOnceForAnyThreadCountAndSize) {
  for (const int threads : {1, 2, 3, 8}) {
    ThreadPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (const int n : {0, 1, 2, 7, 1000}) {
      std::vector<std::atomic<int>> runs(n);
      pool.run(n, [&](int i) { runs[i].fetch_add(1); });
      for (int i = 0; i < n; ++i) ASSERT_EQ(runs[i].load(), 1) << threads << " threads, " << n << " indices, " << i;
    }
    // Reused many times over (a learning loop steps one frame a call).
    std::atomic<long> sum{0};
    for (int call = 0; call < 2000; ++call) pool.run(3, [&](int i) { sum += i + 1; });
    EXPECT_EQ(sum.load(), 2000L * 6);
  }
}

TEST(ThreadPool, RethrowsATasksExceptionAfterTheOtherIndicesRan) {
  ThreadPool pool(3);
  std::atomic<int> ran{0};
  EXPECT_THROW(pool.run(50,
                        [&](int i) {
                          ran.fetch_add(1);
                          if (i == 17) throw std::runtime_error("index 17");
                        }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 50);
  pool.run(4, [&](int) { ran.fetch_add(1); });  // still usable
  EXPECT_EQ(ran.load(), 54);
  EXPECT_THROW(ThreadPool(0), std::invalid_argument);
}

TEST(ThreadPool, CountsTheCoresThisProcessMayRunOn) {
  // Its affinity (taskset, a container's cpuset), not the machine's cores:
  // two threads on one allowed core spin-wait against each other.
  cpu_set_t allowed;
  ASSERT_EQ(sched_getaffinity(0, sizeof allowed, &allowed), 0);
  EXPECT_EQ(ThreadPool::cores(), CPU_COUNT(&allowed));
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(sched_getcpu(), &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);
  EXPECT_EQ(ThreadPool::cores(), 1);
  ASSERT_EQ(sched_setaffinity(0, sizeof allowed, &allowed), 0);
  EXPECT_EQ(ThreadPool::cores(), CPU_COUNT(&allowed));
}

// Every double of the bodies' state.
std::vector<double> bodyState(const Scene& s) {
  std::vector<double> out;
  for (BodyId b = 0; b < s.world->bodyCount(); ++b) {
    const BodyState& x = s.world->body(b);
    for (const double v : {x.x.x(), x.x.y(), x.x.z(), x.q.w(), x.q.x(), x.q.y(), x.q.z(), x.v.x(), x.v.y(), x.v.z(),
                           x.omega.x(), x.omega.y(), x.omega.z()})
      out.push_back(v);
  }
  return out;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(Batch, EachSceneEndsOnTheBitsItReachesAloneOnAnyNumberOfThreads) {
  // Different machines (cables, joints, contacts, both solvers' scenes),
  // and copies of one with different loads on it.
  const std::vector<std::string> names = {"atwood", "hand", "hilbert2", "pulley", "contacts", "atwood", "atwood"};
  constexpr int kFrames = 30;
  const auto load = [&](std::size_t i) {
    Scene s = test::scene(names[i]);
    if (names[i] == "atwood")  // copies 0, 5, 6: pushed up by 0, 5 and 10 N
      s.world->body(test::body(s, "light")).applied_force = Vec3(0.0, 5.0 * (i == 0 ? 0 : i - 4), 0.0);
    return s;
  };
  std::vector<std::vector<double>> alone;
  for (std::size_t i = 0; i < names.size(); ++i) {
    Scene s = load(i);
    for (int f = 0; f < kFrames; ++f) test::frame(s);
    alone.push_back(bodyState(s));
  }
  for (const int threads : {1, 2, 3}) {
    std::vector<Scene> scenes;
    for (std::size_t i = 0; i < names.size(); ++i) scenes.push_back(load(i));
    std::vector<BatchItem> items;
    for (Scene& s : scenes) items.push_back({&s, nullptr});
    ThreadPool pool(threads);
    for (int f = 0; f < kFrames; f += 10) {  // several calls, as a controller makes them
      const std::vector<BatchOutcome> out = stepBatch(items, 10, pool);
      for (const BatchOutcome& o : out) ASSERT_EQ(o.frames_done, 10);
    }
    for (std::size_t i = 0; i < names.size(); ++i)
      EXPECT_TRUE(sameBits(bodyState(scenes[i]), alone[i])) << names[i] << " #" << i << ", " << threads << " threads";
  }
}

TEST(Batch, ALoadOnOneCopyChangesThatCopyByTheAtwoodClosedForm) {
  // The copies share nothing: copy k, its light box pushed up by F_k,
  // accelerates as a = ((m2 - m1) g + F) / (m1 + m2 + M / 2) (wheel a solid
  // disc of mass M), each by its own F. At 10 x 2 the direct solver meets
  // Atwood machines to rounding; 1e-6 leaves room for the wheel's turn.
  std::vector<Scene> scenes;
  const std::vector<double> push = {0.0, 2.0, 4.9, -3.0};
  for (const double f : push) {
    scenes.push_back(test::scene("atwood"));
    scenes.back().world->body(test::body(scenes.back(), "light")).applied_force = Vec3(0.0, f, 0.0);
  }
  std::vector<BatchItem> items;
  for (Scene& s : scenes) items.push_back({&s, nullptr});
  ThreadPool pool(2);
  stepBatch(items, 6, pool);
  std::vector<double> v0;
  for (Scene& s : scenes) v0.push_back(s.world->body(test::body(s, "heavy")).v.y());
  stepBatch(items, 12, pool);
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const Scene& s = scenes[k];
    const double m1 = s.world->bodyMass(test::body(s, "light")), m2 = s.world->bodyMass(test::body(s, "heavy"));
    const double M = s.world->bodyMass(test::body(s, "wheel"));
    const double a = ((m2 - m1) * 9.81 + push[k]) / (m1 + m2 + 0.5 * M);
    const double measured = -(s.world->body(test::body(s, "heavy")).v.y() - v0[k]) / (12.0 / s.frame_rate_hz);
    EXPECT_NEAR(measured, a, 1e-6 * std::abs(a) + 1e-9) << "push " << push[k] << " N";
  }
}

TEST(Batch, AStoppedSceneIsReportedAndTheOthersRunTheirFrames) {
  std::vector<Scene> scenes;
  for (int k = 0; k < 3; ++k) scenes.push_back(test::scene("atwood"));
  scenes[1].world->body(test::body(scenes[1], "heavy")).v.y() = std::numeric_limits<double>::quiet_NaN();
  std::vector<BatchItem> items;
  for (Scene& s : scenes) items.push_back({&s, nullptr});
  // The NaN is on purpose (fp_main.cpp traps it): traps off before the
  // pool starts, as its threads inherit the floating-point environment.
  const int traps = fedisableexcept(FE_ALL_EXCEPT);
  std::vector<BatchOutcome> out;
  {
    ThreadPool pool(2);
    out = stepBatch(items, 5, pool);
  }
  feenableexcept(traps);
  EXPECT_EQ(out[0].frames_done, 5);
  EXPECT_EQ(out[2].frames_done, 5);
  EXPECT_FALSE(out[0].stopped);
  ASSERT_TRUE(out[1].stopped);
  EXPECT_EQ(out[1].frames_done, 0);
  EXPECT_NE(out[1].stopped->find("non-finite"), std::string::npos) << *out[1].stopped;
  EXPECT_NEAR(scenes[0].world->time(), 5.0 / scenes[0].frame_rate_hz, 1e-12);
}

TEST(Batch, RefusesASceneListedTwiceAndNegativeFrames) {
  Scene s = test::scene("atwood");
  ThreadPool pool(2);
  EXPECT_THROW(stepBatch({{&s, nullptr}, {&s, nullptr}}, 1, pool), std::invalid_argument);
  EXPECT_THROW(stepBatch({{&s, nullptr}}, -1, pool), std::invalid_argument);
  EXPECT_THROW(stepBatch({{nullptr, nullptr}}, 1, pool), std::invalid_argument);
  EXPECT_EQ(s.world->time(), 0.0);
}

}  // namespace
}  // namespace reeve::test_batch
