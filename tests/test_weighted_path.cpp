// A weighted path (PathConstraint::weights): the forces of its segments in
// fixed ratios, its length unweighted. Two boxes hung over a fixed point
// with weights 1 and k slide as over a hole whose friction holds the
// capstan ratio: T_2 = k T_1 while box 2 falls, and
//   a = g (m2 - k m1) / (m2 + k m1),
// with both solvers, any substep budget, and compliant cables.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "reeve/engine/world.h"

namespace reeve::test_weighted_path {
namespace {

struct Hang {
  World world;
  BodyId box1 = 0, box2 = 0;
  PathId path = 0;
};

// Box m1 hangs 1 m below the point (0, 0, 0) at x = -0.5, box m2 at
// x = +0.5; the path runs box 1 -> a fixed point -> a fixed point -> box 2
// (the two fixed points 1 m apart: the wrap), weights {1, w_mid, k}.
void build(Hang& h, double m1, double m2, double k, SolverKind solver, int substeps, int iterations,
           double compliance = 0.0) {
  h.world.settings().solver = solver;
  h.world.settings().substeps = substeps;
  h.world.settings().iterations = iterations;
  BodyDef def;
  def.shape = Shape::box(Vec3::Constant(0.05));
  def.mass = m1;
  def.position = Vec3(-0.5, -1.0, 0.0);
  h.box1 = h.world.addBody(def);
  def.mass = m2;
  def.position = Vec3(0.5, -1.0, 0.0);
  h.box2 = h.world.addBody(def);
  PathConstraint p;
  p.points = {{h.box1, Vec3::Zero()}, {kWorldBody, Vec3(-0.5, 0.0, 0.0)}, {kWorldBody, Vec3(0.5, 0.0, 0.0)},
              {h.box2, Vec3::Zero()}};
  p.weights = {1.0, std::sqrt(k), k};  // the middle segment joins two fixed points: its weight acts on nothing
  p.rest_length = 3.0;
  p.compliance = compliance;
  h.path = h.world.addPath(p);
}

TEST(WeightedPath, SlidesWithTheTensionsInTheWeightsRatioAndTheCapstanAcceleration) {
  constexpr double g = 9.81;
  struct Budget {
    int substeps, iterations;
  };
  struct Case {
    double m1, m2, k;
  } cases[] = {
      {1.0, 3.0, 2.0},       // a = g / 5
      {1.0, 1.0, 1.0},       // no friction, balanced: at rest
      {1.0, 100.0, 20.0},    // a = 80/120 g
      {1e-3, 1e3, 1e3},      // extreme masses: a = g (1e3 - 1) / (1e3 + 1)
      {100.0, 1e5, 535.49},  // kilonewton loads and the ratio of mu = 0.5 over 4 pi
  };
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel})
    for (const Budget b : {Budget{20, 1}, Budget{1, 10}})
      for (const Case& c : cases) {
        SCOPED_TRACE(std::string(solver == SolverKind::Direct ? "direct " : "gauss-seidel ") +
                     std::to_string(b.substeps) + " x " + std::to_string(b.iterations) + " m1 " +
                     std::to_string(c.m1) + " m2 " + std::to_string(c.m2) + " k " + std::to_string(c.k));
        Hang h;
        build(h, c.m1, c.m2, c.k, solver, b.substeps, b.iterations);
        const double a = g * (c.m2 - c.k * c.m1) / (c.m2 + c.k * c.m1);
        for (int f = 0; f < 20; ++f) h.world.step(1.0 / 60.0);
        const double t = h.world.time();
        // Velocities follow from positions: exact for constant acceleration.
        EXPECT_NEAR(h.world.body(h.box2).v.y(), -a * t, 1e-3 * std::abs(a) * t + 1e-9);
        EXPECT_NEAR(h.world.body(h.box1).v.y(), a * t, 1e-3 * std::abs(a) * t + 1e-9);
        const double t1 = h.world.pathTension(h.path);
        EXPECT_NEAR(t1, c.m1 * (g + a), 1e-3 * c.m1 * (g + a));
        // The length is kept: it is the constraint, not the weighted sum.
        EXPECT_NEAR(h.world.pathLength(h.path), 3.0, 1e-6);
      }
}

TEST(WeightedPath, AnElasticCableStretchesByTheWeightedComplianceAtRest) {
  // Held at rest (k = m2 / m1 exactly): T1 = m1 g, T2 = m2 g, and the whole
  // path stretches by compliance x T1 (compliance = sum w_i c_i).
  constexpr double g = 9.81, c = 1e-4;  // m/N
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel}) {
    SCOPED_TRACE(solver == SolverKind::Direct ? "direct" : "gauss-seidel");
    Hang h;
    build(h, 2.0, 6.0, 3.0, solver, 20, 4, c);
    // Start the boxes where the stretched cable holds them: each segment
    // stretches by its share, so start at the end position (split evenly).
    const double stretch = c * 2.0 * g;
    h.world.body(h.box1).x.y() -= stretch / 2.0;
    h.world.body(h.box2).x.y() -= stretch / 2.0;
    for (int f = 0; f < 60; ++f) h.world.step(1.0 / 60.0);
    EXPECT_NEAR(h.world.pathTension(h.path), 2.0 * g, 1e-3 * 2.0 * g);
    EXPECT_NEAR(h.world.pathLength(h.path) - 3.0, stretch, 1e-3 * stretch);
    EXPECT_LT(h.world.body(h.box2).v.norm(), 1e-6);
  }
}

}  // namespace
}  // namespace reeve::test_weighted_path
