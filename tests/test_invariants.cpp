// The cable bookkeeping's invariants (CableSystem::invariantViolation)
// after every substep of every shipped scene, with both solvers: no rest
// length or stored cable below zero but through the events that end there,
// and each cable's total length conserved (the first second of each under
// the sanitizers).
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "reeve/scene/scene.h"
#include "scene_fixture.h"

namespace reeve::test_invariants {
namespace {

// One test per scene and solver, so that ctest runs them in parallel.
struct Case {
  std::filesystem::path file;
  SolverKind method;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.file.filename().string() << ", " << solverMethodName(c.method);
}

std::vector<Case> cases() {
  std::vector<Case> all;
  for (const SolverKind method : {SolverKind::Direct, SolverKind::GaussSeidel})
    for (const auto& file : test::shippedSceneFiles()) all.push_back({file, method});
  return all;
}

class EveryShippedScene : public testing::TestWithParam<Case> {};

TEST(Invariants, EveryShippedSceneIsCovered) { EXPECT_GE(test::shippedSceneFiles().size(), 17u); }

TEST_P(EveryShippedScene, InvariantsHoldAfterEverySubstep) {
  const auto& [file, method] = GetParam();
  Scene s = loadScene(file);
  s.world->settings().solver = method;
  // The whole run, under the sanitizers too (issue 27): a code path that a
  // scene reaches late (a cable that merges, a load set down) is checked.
  const int frames = s.frameCount();
  // The cable system checks its invariants after each of its updates, that
  // is after every substep, and keeps the first break.
  for (int f = 0; f < frames && !s.cables->firstBreach(); ++f) {
    s.world->step(1.0 / s.frame_rate_hz);
    ASSERT_FALSE(s.world->firstNonFiniteBody()) << "frame " << f;
  }
  EXPECT_FALSE(s.cables->firstBreach()) << s.cables->firstBreach()->what;
}

INSTANTIATE_TEST_SUITE_P(Invariants, EveryShippedScene, testing::ValuesIn(cases()),
                         [](const testing::TestParamInfo<Case>& info) {
                           std::string name = info.param.file.stem().string() + "_" +
                                              solverMethodName(info.param.method);
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

TEST(Invariants, ANegativeRestLengthOrStoredCableIsReported) {
  // A post, a wheel and a post: a cable that could not exist.
  World world;
  CableSystem cables(world);
  BodyDef post;
  post.is_static = true;
  post.position = Vec3(-1.0, -1.0, 0.0);
  const BodyId a = world.addBody(post);
  post.position = Vec3(1.0, -1.0, 0.0);
  const BodyId b = world.addBody(post);
  BodyDef w;
  w.is_static = true;
  w.shape = Shape::cylinder(0.3, 0.1);
  const BodyId wheel = world.addBody(w);
  CableDef def;
  def.name = "rope";
  def.links = {LinkDef::attachment(a, Vec3::Zero()), LinkDef::rolling(wheel, -1), LinkDef::attachment(b, Vec3::Zero())};
  cables.addCable(def);
  EXPECT_FALSE(cables.invariantViolation());
  // Lengths to 10 digits: std::to_string's 6 decimals showed -1e-8 m as
  // -0.000000 m, and a cable's total length changed by 1e-7 m as the
  // same number twice.
  cables.setRestLength(0, 1, -1e-8);
  const auto tiny = cables.invariantViolation();
  ASSERT_TRUE(tiny);
  EXPECT_NE(tiny->find("joint 1 has a negative rest length (-1e-08 m)"), std::string::npos) << *tiny;
  cables.setRestLength(0, 1, -0.25);
  const auto rest = cables.invariantViolation();
  ASSERT_TRUE(rest);
  EXPECT_NE(rest->find("cable 'rope': joint 1 has a negative rest length (-0.25"), std::string::npos) << *rest;

  // A spool end with nothing stored that pays cable out: its store goes
  // below zero, with no event to end it (that is what hybrid links are for).
  World world2;
  CableSystem spool(world2);
  post.position = Vec3(2.0, -1.0, 0.0);
  const BodyId p = world2.addBody(post);
  const BodyId drum = world2.addBody(w);
  def.links = {LinkDef::rolling(drum, 1), LinkDef::attachment(p, Vec3::Zero())};
  spool.addCable(def);
  rotateExactly(world2.body(drum).q, Vec3(0.0, 0.0, 0.5));  // ccw: pays out
  EXPECT_FALSE(spool.firstBreach());
  spool.update(0.25);
  const auto stored = spool.invariantViolation();
  ASSERT_TRUE(stored);
  EXPECT_NE(stored->find("link 0 stores a negative length of cable"), std::string::npos) << *stored;
  // Every build keeps the first break, with the wheel that turned furthest
  // (what a runner blames); later updates do not replace it.
  ASSERT_TRUE(spool.firstBreach());
  EXPECT_EQ(spool.firstBreach()->what, *stored);
  EXPECT_EQ(spool.firstBreach()->time_s, 0.25);
  EXPECT_EQ(spool.firstBreach()->fastest, drum);
  EXPECT_TRUE(spool.firstBreach()->spool_ran_out) << "a rolling end paid out what it did not store";
  EXPECT_EQ(spool.firstBreach()->cable, 0);
  EXPECT_NEAR(spool.firstBreach()->fastest_turn, 0.5, 1e-12);
  rotateExactly(world2.body(drum).q, Vec3(0.0, 0.0, 0.5));
  spool.update(0.5);
  EXPECT_EQ(spool.firstBreach()->time_s, 0.25);
}

}  // namespace
}  // namespace reeve::test_invariants
