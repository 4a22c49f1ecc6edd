// Pinhole links (paper sec. 3.3): the cable slides freely through a fixed
// point, so the tension is the same on both sides.
#include <gtest/gtest.h>

#include <cmath>

#include "reeve/cable/cable.h"
#include "scene_fixture.h"
#include "solver_budgets.h"

namespace reeve::test_pinhole {
namespace {

TEST(Pinhole, ARingOnACableComesToRestWithEqualAnglesAndTensions) {
  // A ring of mass m on a cable of length S between posts a horizontal
  // distance D apart rests where both sides make the same angle a with
  // the horizontal, cos a = D / S, with tension m g / (2 sin a) on each.
  Scene s = test::scene("pinhole");
  const Vec3 left = s.world->body(test::body(s, "post_left")).x;
  const Vec3 right = s.world->body(test::body(s, "post_right")).x;
  const double S = s.cables->totalLength(0), D = right.x() - left.x(), g = 9.81;
  const double a = std::acos(D / S);
  // Left span l1, right span l2: l1 + l2 = S, (l2 - l1) sin a = rise.
  const double l1 = 0.5 * (S - (right.y() - left.y()) / std::sin(a));
  const Vec3 rest = left + l1 * Vec3(std::cos(a), -std::sin(a), 0.0);
  for (int f = 0; f < s.frameCount(); ++f) test::frame(s);
  const BodyState& ring = s.world->body(test::body(s, "ring"));
  EXPECT_LT(ring.v.norm(), 1e-3);
  EXPECT_NEAR((ring.x - rest).norm(), 0.0, 0.005) << ring.x.transpose() << " vs " << rest.transpose();
  const double T = 1.0 * g / (2.0 * std::sin(a));
  EXPECT_NEAR(s.cables->tension(0, 0), T, 0.01 * T);
  EXPECT_NEAR(s.cables->tension(0, 1), T, 0.01 * T);
  EXPECT_NEAR(s.cables->totalLength(0), S, 1e-9 * S);
  // Equal strain: both spans at their rest lengths (to the gravity step
  // g h^2 of the substep in which the rest lengths were shared).
  for (int j = 0; j < 2; ++j)
    EXPECT_NEAR(s.cables->length(0, j), s.cables->restLength(0, j), 1e-5);
}

// m1 and m2 (kg) hang 2 m below a fixed bar from one cable through two
// holes in it, 1 m apart (settings: gravity along -y).
struct TwoHoleAtwood {
  World world;
  CableSystem cables{world};
  BodyId light = 0, heavy = 0;
  int cable = 0;
  double total = 0.0;
  TwoHoleAtwood(const SolverSettings& settings, double m1, double m2) : world(settings) {
    BodyDef bar;
    bar.is_static = true;
    const BodyId b = world.addBody(bar);
    BodyDef box;
    box.shape = Shape::box(Vec3(0.1, 0.1, 0.1));
    box.mass = m1;
    box.position = Vec3(-0.5, -2.0, 0);
    light = world.addBody(box);
    box.mass = m2;
    box.position = Vec3(0.5, -2.0, 0);
    heavy = world.addBody(box);
    CableDef def;
    def.links = {LinkDef::attachment(light, Vec3(0, 0.1, 0)), LinkDef::pinhole(b, Vec3(-0.5, 0, 0)),
                 LinkDef::pinhole(b, Vec3(0.5, 0, 0)), LinkDef::attachment(heavy, Vec3(0, 0.1, 0))};
    cable = cables.addCable(def);
    total = cables.totalLength(cable);
  }
};

TEST(Pinhole, CableSlidesThroughTwoHolesLikeAMasslessPulley) {
  // An Atwood machine with a massless, frictionless pulley:
  // a = (m2 - m1) g / (m1 + m2), T = 2 m1 m2 g / (m1 + m2) on every span.
  const double m1 = 1.0, m2 = 3.0, g = 10.0;
  SolverSettings settings;
  settings.gravity = Vec3(0, -g, 0);
  TwoHoleAtwood m(settings, m1, m2);
  World& world = m.world;
  CableSystem& cables = m.cables;
  const BodyId light = m.light, heavy = m.heavy;
  const int c = m.cable;
  const double total = m.total;
  for (int f = 0; f < 30; ++f) world.step(1.0 / 60.0);
  const double t = world.time(), a = (m2 - m1) * g / (m1 + m2), T = 2.0 * m1 * m2 * g / (m1 + m2);
  EXPECT_NEAR(-world.body(heavy).v.y() / t, a, 0.01 * a);
  EXPECT_NEAR(world.body(light).v.y() / t, a, 0.01 * a);
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(cables.tension(c, j), T, 0.01 * T) << "span " << j;
  // Cable moved from the light side to the heavy side through both holes.
  const double moved = 0.5 * a * t * t;
  EXPECT_NEAR(cables.restLength(c, 2) - cables.restLength(c, 0), 2.0 * moved, 0.01 * moved);
  EXPECT_NEAR(cables.totalLength(c), total, 1e-9 * total);
}

TEST(Pinhole, ATiePointHauledIntoItsPinholeJamsThere) {
  // The two-hole Atwood machine run on: the light box's tie point rises
  // into its hole (0.1 m up: 1.9 m at a = (m2 - m1) g / (m1 + m2)) and
  // jams there, a ball joint holding it to the bar (event span_runs_out),
  // the hole holding the cable from then on: the heavy box hangs still from
  // the other hole with T = m2 g, and no energy is made by the catch. (A
  // tie point at a hole had nothing to stop it: it went through, and the
  // cable pulled it back from the other side; the start projection made
  // 29 kJ of it in one frame, the end projection let the box rise 2 m past
  // the bar.) At every budget, both projections, and 1 to 1000 kg below.
  for (const test::Budget& budget : test::fourBudgetsBothProjections())
    for (const double m2 : {3.0, 1000.0}) {
      SCOPED_TRACE(test::name(budget) + ", " + std::to_string(m2) + " kg");
      const double m1 = 1.0, g = 9.81;
      TwoHoleAtwood m(test::settings(budget), m1, m2);
      World& world = m.world;
      CableSystem& cables = m.cables;
      const BodyId light = m.light, heavy = m.heavy;
      const int c = m.cable;
      const double total = m.total;
      const auto energy = [&] {
        const WorldEnergy e = world.energy();
        return e.kinetic + e.gravity;
      };
      const double start = energy();
      bool jammed = false;
      for (int f = 0; f < 120; ++f) {
        world.step(1.0 / 60.0);
        for (const CableEvent& e : cables.takeEvents()) jammed |= e.kind == CableEvent::Kind::SpanRunsOut && e.link == 0;
        EXPECT_LE(energy(), start + 1e-9 * m2 * g) << "t = " << world.time();
      }
      EXPECT_TRUE(jammed);
      EXPECT_TRUE(cables.cables()[c].joints[0].jammed);
      const Vec3 tie = world.body(light).toWorld(Vec3(0, 0.1, 0));
      EXPECT_LT((tie - Vec3(-0.5, 0, 0)).norm(), 0.1) << tie.transpose();
      EXPECT_LT(world.body(heavy).v.norm(), 1e-6);
      EXPECT_NEAR(cables.tension(c, 2), m2 * g, 1e-6 * m2 * g);
      EXPECT_NEAR(cables.totalLength(c), total, 1e-9 * total);
      EXPECT_FALSE(cables.firstBreach().has_value());
    }
}

}  // namespace
}  // namespace reeve::test_pinhole
