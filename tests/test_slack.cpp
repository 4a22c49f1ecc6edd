// A loose cable exerts nothing (paper sec. 3.1): a body on a slack cable
// over a wheel falls freely, the wheel does not turn, until the cable is taut.
#include <gtest/gtest.h>

#include "reeve/cable/cable.h"

namespace reeve::test_slack {
namespace {

TEST(Slack, BodyFallsFreelyUntilTheCableIsTaut) {
  const double g = 10.0, slack = 0.8;
  World world;
  world.settings().gravity = Vec3(0, -g, 0);
  // The jerk must travel through the wheel to the anchored span within one
  // substep: Gauss-Seidel needs iterations for that, not substeps.
  world.settings().substeps = 10;
  world.settings().iterations = 10;
  CableSystem cables(world);
  BodyDef post;
  post.is_static = true;
  post.position = Vec3(-1.0, 0.0, 0.0);
  const BodyId anchor = world.addBody(post);
  BodyDef w;
  w.shape = Shape::cylinder(0.3, 0.05);
  w.mass = 1.0;
  w.position = Vec3(0.0, 1.0, 0.0);
  const BodyId wheel = world.addBody(w);
  world.addHinge({wheel, kWorldBody, w.position, Vec3::UnitZ(), 0.0});
  BodyDef box;
  box.shape = Shape::box(Vec3(0.1, 0.1, 0.1));
  box.mass = 1.0;
  box.position = Vec3(0.3, -1.0, 0.0);
  const BodyId body = world.addBody(box);
  CableDef def;
  def.links = {LinkDef::attachment(anchor, Vec3::Zero()),
               LinkDef::rolling(wheel, -1),
               LinkDef::attachment(body, Vec3(0, 0.1, 0))};
  const int c = cables.addCable(def);
  // Give the hanging span `slack` m more cable than its length.
  cables.setRestLength(c, 1, cables.restLength(c, 1) + slack);
  const double y0 = world.body(body).x.y();

  const double taut_y = y0 - slack;
  bool caught = false;
  for (int f = 1; f <= 60; ++f) {
    world.step(1.0 / 60.0);
    const double t = world.time();
    const double drop = 0.5 * g * t * t;
    const double y = world.body(body).x.y();
    if (drop < slack - 0.05) {
      // Free fall: XPBD's symplectic Euler differs from 1/2 g t^2 by
      // g t h / 2 at most, h = 1/600 s.
      EXPECT_NEAR(y, y0 - drop, 0.5 * g * t / 600.0 + 1e-12);
      EXPECT_EQ(cables.tension(c, 1), 0.0);
      EXPECT_EQ(world.body(wheel).omega.norm(), 0.0);
    }
    // Once taut, the inextensible cable holds the body at the taut length.
    EXPECT_GT(y, taut_y - 1e-3) << "t = " << t;
    if (!caught && y < taut_y + 0.01) {
      caught = true;  // the frame of the jerk: a large tension stops the fall
      EXPECT_GT(cables.tension(c, 1), 10.0 * g) << "t = " << t;
    }
  }
  EXPECT_TRUE(caught);
}

}  // namespace
}  // namespace reeve::test_slack
