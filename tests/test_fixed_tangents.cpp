// A span between two wheels that turn on axles that stay put keeps its
// tangent points in the world from one update to the next
// (CableSystem::keepsTangents): they must stay tangent points, in a plane
// (a belt) and between planes (paper Fig. 6), and a wheel moved by hand
// between steps must have them found afresh; the direct solver keeps such
// a span's evaluation only while it lies where it lay.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "reeve/cable/cable.h"
#include "scene_fixture.h"

namespace reeve::test_fixed_tangents {
namespace {

// The largest misfit, over every span of `s` between two rolling links,
// of its ends as tangent points: |distance from the circle's centre - r|
// and |cos| of the angle between the radius and the span (m, 1). After an
// update by hand: a step's solve turns the wheels on past the tangent
// points its substep's update found.
double worstTangentMisfit(Scene& s) {
  s.cables->update();
  double worst = 0.0;
  for (const Cable& cable : s.cables->cables()) {
    for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
      const CableJoint& joint = cable.joints[j];
      const Link &from = cable.links[j], &to = cable.links[joint.to];
      if (!from.active || !from.rolls() || !to.rolls() || joint.parted) continue;
      const BodyState &a = s.world->body(from.body), &b = s.world->body(to.body);
      const Vec3 p_a = a.toWorld(joint.local_a), p_b = b.toWorld(joint.local_b);
      const Vec3 span = (p_b - p_a).normalized();
      for (const auto& [link, body, p] : {std::tuple{&from, &a, p_a}, std::tuple{&to, &b, p_b}}) {
        const Vec3 centre = body->toWorld(Vec3(0.0, 0.0, link->plane_offset));
        const Vec3 radius = p - centre;
        worst = std::max({worst, std::abs(radius.norm() - link->section.radius),
                          std::abs(radius.normalized().dot(span))});
      }
    }
  }
  return worst;
}

TEST(FixedTangents, SpansBetweenTurningWheelsStayTangent) {
  // gear_1_to_4: a belt in one plane over two hinged wheels; wheels_3d: a
  // cable over three wheels in three planes. Every frame for 1.5 s, under
  // both solvers.
  for (const std::string name : {"gear_1_to_4", "wheels_3d"}) {
    for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel}) {
      SCOPED_TRACE(name + (solver == SolverKind::Direct ? " direct" : " gauss-seidel"));
      Scene s = test::scene(name);
      s.world->settings().solver = solver;
      double worst = 0.0;
      for (int f = 0; f < 90; ++f) {
        test::frame(s);
        worst = std::max(worst, worstTangentMisfit(s));
      }
      EXPECT_LT(worst, 1e-12);
    }
  }
}

TEST(FixedTangents, AWheelMovedByHandHasItsTangentsFoundAfresh) {
  // wheels_3d's last wheel moved 5 cm sideways, and turned a quarter turn
  // about its diameter, between two steps: its spans' tangent points move
  // with it (the last update's, kept, would be 5 cm off).
  for (const bool turn : {false, true}) {
    SCOPED_TRACE(turn ? "moved and turned" : "moved");
    Scene s = test::scene("wheels_3d");
    for (int f = 0; f < 30; ++f) test::frame(s);
    BodyState& wheel = s.world->body(test::body(s, "wheel_c"));
    wheel.x += Vec3(0.05, 0.0, 0.0);
    if (turn) wheel.q = (Quat(Eigen::AngleAxisd(0.1, Vec3::UnitX())) * wheel.q).normalized();
    test::frame(s);
    EXPECT_LT(worstTangentMisfit(s), 1e-12);
  }
}

// The largest difference between two runs' body poses: positions (m)
// and orientations (rad).
double worstPoseGap(const Scene& a, const Scene& b) {
  double worst = 0.0;
  for (BodyId id = 0; id < a.world->bodyCount(); ++id) {
    const BodyState &p = a.world->body(id), &q = b.world->body(id);
    worst = std::max({worst, (p.x - q.x).norm(), p.q.angularDistance(q.q)});
  }
  return worst;
}

// Sets every path's placement to `placement` after the cable update, each
// substep: 0 has the direct solver evaluate every span afresh; 1 says that
// every path lies where it lay, whatever the bodies did.
void forcePlacement(Scene& s, long long placement) {
  World::IslandHook hook;
  hook.after = [placement](World& w, double) {
    for (int i = 0; i < w.pathCount(); ++i) w.path(i).placement = placement;
  };
  s.world->addSubstepHook(std::move(hook));
}

TEST(FixedTangents, TheDirectSolverKeepsASpanOnlyWhileItLiesWhereItLay) {
  // A span between rotors whose tangent points were kept keeps the direct
  // solver's last evaluation (PathConstraint::placement): the same motion
  // as one evaluated afresh every substep, to rounding (8e-12 m or rad at
  // most), over 2 s with a wheel moved and turned by hand at 0.5 s. A
  // placement that claims every span stays put changes nothing either: the
  // solver sees the moved wheel itself (BodyFrame::still). Kept across the
  // move, the spans turn the wheels 0.17 to 2.5 rad otherwise. (Not
  // motor_belt: its motor reaches its target speed at a substep's end,
  // which rounding puts on one side or the other.)
  for (const auto& [name, wheel] : {std::pair{"gear_1_to_4", "large"}, std::pair{"wheels_3d", "wheel_c"},
                                     std::pair{"hilbert2", "wheel62"}}) {
    SCOPED_TRACE(name);
    Scene kept = test::scene(name), afresh = test::scene(name), claimed = test::scene(name);
    forcePlacement(afresh, 0);
    forcePlacement(claimed, 1);
    const BodyId moved = test::body(kept, wheel);
    double worst = 0.0;
    for (int f = 0; f < 120; ++f) {
      if (f == 30)
        for (Scene* s : {&kept, &afresh, &claimed}) {
          BodyState& body = s->world->body(moved);
          body.x += Vec3(0.05, 0.0, 0.0);
          body.q = (Quat(Eigen::AngleAxisd(0.1, Vec3::UnitX())) * body.q).normalized();
        }
      for (Scene* s : {&kept, &afresh, &claimed}) test::frame(*s);
      worst = std::max({worst, worstPoseGap(kept, afresh), worstPoseGap(claimed, afresh)});
    }
    EXPECT_LT(worst, 1e-9);
  }
}

TEST(FixedTangents, ASpanWhoseHybridRunsOutIsEvaluatedAfresh) {
  // hilbert2 with 5 cm on each end spool: the braked spool (wheel63) runs
  // out in its first frame, and its arriving span, kept between two rotors
  // by updateJoint, is tied where the cable ends (switchHybrids) later in
  // the same update, on the same bodies: the update says so (an event) and
  // the span's placement is 0. The motion is the one evaluated afresh every
  // substep, to rounding (7e-13 measured); taken as kept, the wheels turn
  // 0.067 rad away.
  std::ifstream in(std::string(REEVE_SCENES_DIR) + "/hilbert2.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string stored = "\"stored_m\":128.0";
  for (std::size_t at = text.find(stored); at != std::string::npos; at = text.find(stored))
    text.replace(at, stored.size(), "\"stored_m\":0.05");
  Scene kept = parseScene(text, "hilbert2, 5 cm stored"), afresh = parseScene(text, "hilbert2, 5 cm stored");
  forcePlacement(afresh, 0);
  int run_outs = 0;
  double worst = 0.0;
  for (int f = 0; f < 60; ++f) {
    for (Scene* s : {&kept, &afresh}) test::frame(*s);
    worst = std::max(worst, worstPoseGap(kept, afresh));
    for (const CableEvent& e : kept.cables->takeEvents()) run_outs += e.kind == CableEvent::Kind::HybridRunsOut;
  }
  EXPECT_EQ(run_outs, 1);
  EXPECT_LT(worst, 1e-9);
}

}  // namespace
}  // namespace reeve::test_fixed_tangents
