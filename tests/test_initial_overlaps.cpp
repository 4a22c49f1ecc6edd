// Bodies a scene places overlapping, by the rounding of their poses, start
// at rest: the overlaps are pushed out before the first step as poses, not
// as speeds (initial_overlaps.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "contact_fixture.h"
#include "solver_budgets.h"

namespace reeve::test_initial_overlaps {
namespace {

TEST(InitialOverlaps, AStackPlacedIntoTheGroundAndIntoItselfStartsAtRestAtAnySubstep) {
  // A 2 kg box placed 0.1 mm into the ground, and two 1 kg cubes on it,
  // each 0.1 mm into the one below. The first substep's contacts pushed
  // the overlaps out, and v = dx / h made that a speed of 0.1 mm / h: the
  // stack jumped at 0.14 m/s at 20 x 4, 0.28 m/s at 100 x 1, and at 1000 x
  // 1 was thrown up at 4.3 m/s, its top cube 1 m above where it began half
  // a second later. Now each body moves at most 1 mm/s over the first half
  // second (measured: 2e-5 m/s at 20 x 4, 9e-7 at 100 x 1, 5e-10 at 1000 x
  // 1), and the stack stands where its faces touch, to the resting
  // contacts' own sag (2e-6 m at 20 x 4).
  const ContactMaterial m = test::material(0.5, 0.3, 0.0);
  for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel}) {
    for (const auto& [substeps, iterations] : {std::pair{20, 4}, {100, 1}, {1000, 1}}) {
      SCOPED_TRACE(test::name({solver, substeps, iterations}));
      World world = test::makeWorld(substeps, iterations);
      world.settings().solver = solver;
      world.setGround(test::ground(Vec3::UnitY(), m));
      const BodyId box = test::add(world, Shape::box(Vec3(0.2, 0.1, 0.2)), 2.0, Vec3(0.0, 0.1 - 1e-4, 0.0), m, true);
      const BodyId lower = test::add(world, Shape::box(Vec3(0.1, 0.1, 0.1)), 1.0, Vec3(0.0, 0.3 - 2e-4, 0.0), m, true);
      const BodyId upper = test::add(world, Shape::box(Vec3(0.1, 0.1, 0.1)), 1.0, Vec3(0.0, 0.5 - 3e-4, 0.0), m, true);
      double fastest = 0.0;
      for (int f = 0; f < 30; ++f) {
        world.step(test::kFrame);
        for (const BodyId b : {box, lower, upper}) {
          fastest = std::max(fastest, world.body(b).v.norm());
          fastest = std::max(fastest, world.body(b).omega.norm() * 0.2);  // the speed of a corner
        }
      }
      EXPECT_LT(fastest, 1e-3);
      EXPECT_NEAR(world.body(box).x.y(), 0.1, 1e-5);
      EXPECT_NEAR(world.body(lower).x.y(), 0.3, 1e-5);
      EXPECT_NEAR(world.body(upper).x.y(), 0.5, 1e-5);
    }
  }
}

}  // namespace
}  // namespace reeve::test_initial_overlaps
