// Errors a schema cannot find: names, mass, cross-sections, counts, axes,
// cables the solver cannot build.
#include "scene_test_util.h"

namespace reeve::test {
namespace {

TEST(SemanticErrors, UnknownBodyInALink) {
  expectError(
      baseWith(R"({"body": "wheel", "type": "rolling")", R"({"body": "wheell", "type": "rolling")"),
      "/cables/0/links/1/body", "the name of a body (wheel, crate, ball)", "\"wheell\"");
}

// kBase with a second cable, "tie", and `junctions`.
std::string withJunction(const std::string& junctions) {
  return baseWith(R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]}]}])",
                  R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]}]},
    {"name": "tie", "links": [{"body": "wheel", "type": "attachment", "point_m": [0, -0.5, 0]},
      {"body": "crate", "type": "attachment", "point_m": [0, 0.2, 0]}]}],
  "junctions": )" + junctions);
}

TEST(SemanticErrors, JunctionOfAnUnknownCable) {
  expectError(withJunction(R"([{"name": "j", "branches": [{"cable": "tie"}, {"cable": "tye", "divisor": 2}]}])"),
              "/junctions/0/branches/1/cable", "the name of a cable", "\"tye\"");
}

TEST(SemanticErrors, JunctionOfACableTwice) {
  expectError(withJunction(R"([{"name": "j", "branches": [{"cable": "tie"}, {"cable": "tie", "divisor": 2}]}])"),
              "/junctions/0/branches/1/cable", "a cable in no other branch", "already at /junctions/0/branches/0");
}

TEST(SemanticErrors, JunctionOfACableThatHoldsOnAWheel) {
  // The rope rolls on the wheel without slipping: two runs, not one.
  expectError(withJunction(R"([{"name": "j", "branches": [{"cable": "tie"}, {"cable": "rope", "divisor": 2}]}])"),
              "/junctions/0/branches/1/cable", "a cable that can be a junction's branch", "holds the cable");
}

TEST(SemanticErrors, JunctionOfACableWithAWinch) {
  const std::string text = with(withJunction(R"([{"name": "j", "branches": [{"cable": "tie"}, {"cable": "rope"}]}])"),
                                R"("name": "tie", )",
                                R"("name": "tie", "winch": {"end": "first", "commands": [{"from_s": 0, "speed_m_per_s": 0.1}]}, )");
  expectError(text, "/junctions/0/branches/0/cable", "a cable that can be a junction's branch", "has a winch");
}

// kBase's rope made frictionless over its wheel: one run, a branch.
std::string sliding(const std::string& text) {
  return with(text, R"({"body": "wheel", "type": "rolling", "orientation": "cw"})",
              R"({"body": "wheel", "type": "rolling", "orientation": "cw", "mu": 0})");
}

TEST(SemanticErrors, CableInTwoJunctions) {
  expectError(sliding(withJunction(R"([{"name": "j", "branches": [{"cable": "tie"}, {"cable": "rope"}]},
                                      {"name": "k", "branches": [{"cable": "tie"}, {"cable": "rope"}]}])")),
              "/junctions/1/branches/0/cable", "a cable in no other branch", "already at /junctions/0/branches/0");
}

TEST(SemanticErrors, DuplicateJunctionName) {
  expectError(sliding(withJunction(R"([{"name": "j", "branches": [{"cable": "tie"}, {"cable": "rope"}]},
                                      {"name": "j", "branches": [{"cable": "tie"}, {"cable": "rope"}]}])")),
              "/junctions/1/name", "a junction name not already used", "\"j\"");
}

TEST(SemanticErrors, ASlidingRopeAndATieMakeAJunction) {
  // The same two cables, once: loads (the error tests' counterpart).
  Scene scene = parseScene(sliding(withJunction(R"([{"name": "j", "branches": [{"cable": "tie"}, {"cable": "rope", "divisor": 3}]}])")),
                           "test.json");
  ASSERT_EQ(scene.cables->junctions().size(), 1u);
  EXPECT_EQ(scene.cables->junctions()[0].scales, (std::vector<double>{1.0, 1.0 / 3.0}));
}

// kBase with `pairs` as its contact_exclusions.
std::string withExclusions(const std::string& pairs) {
  return baseWith(R"("name": "base",)", R"("name": "base", "contact_exclusions": )" + pairs + ",");
}

TEST(SemanticErrors, ContactExclusionOfAnUnknownBody) {
  expectError(withExclusions(R"([["crate", "ball"], ["crate", "bal"]])"), "/contact_exclusions/1/1",
              "the name of a body (wheel, crate, ball)", "\"bal\"");
  expectError(withExclusions(R"([["world", "ball"]])"), "/contact_exclusions/0/0", "the name of a body", "\"world\"");
}

TEST(SemanticErrors, ContactExclusionOfABodyWithItself) {
  expectError(withExclusions(R"([["crate", "crate"]])"), "/contact_exclusions/0/1", "a body other than the first",
              "\"crate\"");
}

TEST(SemanticErrors, ContactBitsAndExclusionsLoad) {
  Scene scene = parseScene(
      with(withExclusions(R"([["ball", "crate"]])"), R"("mass_kg": 2,)", R"("mass_kg": 2, "collides": true, "contact_type": 6, "contact_affinity": 4294967295,)"),
      "test.json");
  const BodyId crate = *scene.world->findBody("crate"), ball = *scene.world->findBody("ball"), wheel = *scene.world->findBody("wheel");
  EXPECT_EQ(scene.world->bodyDef(crate).contact_type, 6u);
  EXPECT_EQ(scene.world->bodyDef(crate).contact_affinity, 4294967295u);
  EXPECT_FALSE(scene.world->contactAllowed(crate, ball));
  EXPECT_TRUE(scene.world->contactAllowed(crate, wheel));
}

TEST(SemanticErrors, UnknownBodyInAHinge) {
  expectError(baseWith(R"({"body": "wheel", "anchor_m")", R"({"body": "whel", "anchor_m")"),
              "/hinges/0/body", "the name of a body (wheel, crate, ball)", "\"whel\"");
}

TEST(SemanticErrors, UnknownOtherBodyInAHinge) {
  expectError(baseWith(R"("anchor_m": [0, 0, 0])", R"("other": "grond", "anchor_m": [0, 0, 0])"),
              "/hinges/0/other", "\"world\" or the name of a body (wheel, crate, ball)",
              "\"grond\"");
}

TEST(SemanticErrors, HingeToItself) {
  expectError(baseWith(R"("anchor_m": [0, 0, 0])", R"("other": "wheel", "anchor_m": [0, 0, 0])"),
              "/hinges/0/other", "a body other than the hinge's body \"wheel\"", "\"wheel\"");
}

TEST(SemanticErrors, TheStartProjectionIsTheDirectSolvers) {
  expectError(baseWith(R"("solver": {})", R"("solver": {"method": "gauss-seidel", "projection": "start"})"),
              "/solver/projection",
              "\"end\" with method \"gauss-seidel\" (the start projection is the direct solver's)", "\"start\"");
}

TEST(SemanticErrors, ZeroHingeAxis) {
  expectError(baseWith(R"("axis": [0, 0, 1])", R"("axis": [0, 0, 0])"), "/hinges/0/axis",
              "a non-zero hinge axis", "[0,0,0]");
}

TEST(SemanticErrors, ZeroOrientationAxis) {
  expectError(baseWith(R"("mass_kg": 1,)",
                       R"("mass_kg": 1, "orientation": {"axis": [0, 0, 0], "angle_rad": 1},)"),
              "/bodies/2/orientation/axis", "a non-zero rotation axis", "[0,0,0]");
}

TEST(SemanticErrors, DuplicateBodyName) {
  expectError(baseWith(R"("name": "ball")", R"("name": "crate")"), "/bodies/2/name",
              "a body name not already used by /bodies/1", "\"crate\"");
}

TEST(SemanticErrors, BodyNamedWorld) {
  expectError(baseWith(R"("name": "ball")", R"("name": "world")"), "/bodies/2/name",
              "other than \"world\"", "\"world\"");
}

TEST(SemanticErrors, DynamicBodyWithDensityAndMass) {
  expectError(baseWith(R"("mass_kg": 2,)", R"("mass_kg": 2, "density_kg_per_m3": 500,)"),
              "/bodies/1", "exactly one of density_kg_per_m3 or mass_kg for a dynamic body",
              "both");
}

TEST(SemanticErrors, DynamicBodyWithoutDensityOrMass) {
  expectError(baseWith(R"("mass_kg": 2,)", ""), "/bodies/1",
              "exactly one of density_kg_per_m3 or mass_kg for a dynamic body", "neither");
}

TEST(SemanticErrors, StaticBodyWithMass) {
  expectError(baseWith(R"("mass_kg": 2,)", R"("mass_kg": 2, "static": true,)"), "/bodies/1/mass_kg",
              "no density or mass for a static body", "2");
}

TEST(SemanticErrors, KinematicBodyWithMass) {
  expectError(baseWith(R"("mass_kg": 2,)", R"("mass_kg": 2, "motion": [{"t_s": 0}],)"), "/bodies/1/mass_kg",
              "no density or mass for a kinematic body (its motion moves it)", "2");
}

TEST(SemanticErrors, StaticBodyWithAMotion) {
  expectError(baseWith(R"("density_kg_per_m3": 1000,)", R"("static": true, "motion": [{"t_s": 0}],)"),
              "/bodies/0/motion", "no motion for a static body", "[{\"t_s\":0}]");
}

TEST(SemanticErrors, MotionTimesGoBack) {
  expectError(baseWith(R"("density_kg_per_m3": 1000,)",
                       R"("motion": [{"t_s": 1}, {"t_s": 2, "angular_velocity_rad_per_s": [0, 0, 1]}, {"t_s": 2}],)"),
              "/bodies/0/motion/2/t_s", "a time after the previous keyframe's 2 s", "2");
}

TEST(SceneKinematic, AWheelTurnedAtOneRadianASecondHaulsOneSideAndPaysOutTheOther) {
  // kBase's wheel (r = 0.5 m) made kinematic, turning counter-clockwise at
  // 1 rad/s: the rope over it, which cannot slip, hauls the ball up on the
  // right at r omega = 0.5 m/s and pays the crate out on the left as fast
  // (the crate falls free at first and is caught).
  Scene scene = parseScene(baseWith(R"("density_kg_per_m3": 1000,)",
                                    R"("motion": [{"t_s": 0, "angular_velocity_rad_per_s": [0, 0, 1]}],)"),
                           "test.json");
  World& world = *scene.world;
  ASSERT_TRUE(world.body(0).kinematic);
  for (int f = 0; f < 60; ++f) world.step(1.0 / 60.0);
  EXPECT_NEAR(world.body(2).x.y(), -2.0 + 0.5, 1e-9);
  EXPECT_NEAR(world.body(1).x.y(), -2.0 - 0.5, 1e-9);
  EXPECT_NEAR(world.body(0).omega.z(), 1.0, 1e-15);
  EXPECT_NEAR(world.hingeAngle(0), 1.0, 1e-12);
}

TEST(SemanticErrors, StaticBodyWithVelocity) {
  expectError(baseWith(R"("density_kg_per_m3": 1000,)",
                       R"("static": true, "angular_velocity_rad_per_s": [0, 0, 1],)"),
              "/bodies/0/angular_velocity_rad_per_s", "no velocity for a static body", "[0,0,1]");
}

TEST(SemanticErrors, PolygonSectionWithZeroArea) {
  expectError(baseWith(R"("orientation": "cw"})",
                       R"("orientation": "cw", "section": {"polygon_m": [[0, 0], [1, 1], [2, 2]]}})"),
              "/cables/0/links/1/section/polygon_m", "a polygon with non-zero area",
              "[[0,0],[1,1],[2,2]] (its convex hull has zero area");
}

TEST(SemanticErrors, PolygonSectionOfOnePointRepeated) {
  expectError(baseWith(R"("orientation": "cw"})",
                       R"("orientation": "cw", "section": {"polygon_m": [[1, 1], [1, 1], [1, 1]]}})"),
              "/cables/0/links/1/section/polygon_m", "a polygon with non-zero area",
              "[[1,1],[1,1],[1,1]]");
}

TEST(SemanticErrors, PinholeStartsAnOpenCable) {
  expectError(baseWith(R"({"body": "crate", "type": "attachment", "point_m": [0, 0.2, 0]},)",
                       R"({"body": "crate", "type": "pinhole", "point_m": [0, 0.2, 0]},)"),
              "/cables/0/links/0/type",
              "\"attachment\", \"rolling\" or \"hybrid\" as the first link of an open cable",
              "\"pinhole\"");
}

TEST(SemanticErrors, PinholeEndsAnOpenCable) {
  expectError(baseWith(R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]})",
                       R"({"body": "ball", "type": "pinhole", "point_m": [0, 0.2, 0]})"),
              "/cables/0/links/2/type",
              "\"attachment\", \"rolling\" or \"hybrid\" as the last link of an open cable",
              "\"pinhole\"");
}

TEST(SemanticErrors, HybridInsideAnOpenCable) {
  expectError(baseWith(R"({"body": "wheel", "type": "rolling")", R"({"body": "wheel", "type": "hybrid")"),
              "/cables/0/links/1/type",
              "\"attachment\", \"rolling\" or \"pinhole\" for an interior link (hybrid links "
              "are only the first or last link of an open cable)",
              "\"hybrid\"");
}

TEST(SemanticErrors, HybridInAClosedCable) {
  // A belt around the wheel and the ball; link 0 is an end only if open.
  expectError(baseWith(R"({"name": "rope", "links": [
    {"body": "crate", "type": "attachment", "point_m": [0, 0.2, 0]},)",
                       R"({"name": "rope", "closed": true, "links": [
    {"body": "crate", "type": "hybrid", "orientation": "cw"},)"),
              "/cables/0/links/0/type", "\"attachment\", \"rolling\" or \"pinhole\" in a closed cable",
              "\"hybrid\"");
}

TEST(SemanticErrors, InactiveEndLink) {
  expectError(baseWith(R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]})",
                       R"({"body": "ball", "type": "rolling", "orientation": "cw", "active": false})"),
              "/cables/0/links/2/active",
              "true for the last link of an open cable (only interior rolling links can start "
              "inactive)",
              "false");
}

TEST(SemanticErrors, FrictionOnAnEndLink) {
  // The cable is fixed to its ends; it can slide only over interior links.
  expectError(baseWith(R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]})",
                       R"({"body": "ball", "type": "rolling", "orientation": "cw", "mu": 0.3})"),
              "/cables/0/links/2/mu", "no mu on the last link of an open cable", "0.3");
}

TEST(SemanticErrors, NegativeMuAndMuOnAnAttachmentAreRefusedByTheSchema) {
  expectError(baseWith(R"("orientation": "cw"})", R"("orientation": "cw", "mu": -0.1})"),
              "/cables/0/links/1/mu", "a number >= 0", "-0.1");
  expectError(baseWith(R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]})",
                       R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0], "mu": 0.3})"),
              "/cables/0/links/2/mu", "no property \"mu\"", "\"mu\"");
}

TEST(SemanticErrors, StoredCableOnAnInactiveLink) {
  expectError(baseWith(R"("orientation": "cw"})",
                       R"("orientation": "cw", "active": false, "stored_m": 0.5})"),
              "/cables/0/links/1/stored_m", "no stored_m on an inactive link", "0.5");
}

TEST(SemanticErrors, RestLengthOfAJointLeavingAnInactiveLink) {
  // Joint 1 leaves the inactive wheel: the crate's span runs to the ball.
  expectError(with(baseWith(R"({"name": "rope", "links": [)",
                            R"({"name": "rope", "rest_length_m": [3, 1], "links": [)"),
                   R"("orientation": "cw"})", R"("orientation": "cw", "active": false})"),
              "/cables/0/rest_length_m/1",
              "0 for the joint leaving inactive link 1 (it has no span until the link is split in)",
              "1");
}

TEST(SemanticErrors, WrongRestLengthCountOfAClosedCable) {
  expectError(baseWith(R"({"name": "rope",)",
                       R"({"name": "rope", "closed": true, "rest_length_m": [1, 2],)"),
              "/cables/0/rest_length_m",
              "an array of 3 numbers (one rest length per cable joint: links, for a closed cable)",
              "an array of 2 items");
}

TEST(SemanticErrors, ClosedCableOfPinholesOnly) {
  expectError(baseWith(R"({"name": "rope", "links": [
    {"body": "crate", "type": "attachment", "point_m": [0, 0.2, 0]},
    {"body": "wheel", "type": "rolling", "orientation": "cw"},
    {"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]}]})",
                       R"({"name": "rope", "closed": true, "links": [
    {"body": "crate", "type": "pinhole", "point_m": [0, 0.2, 0]},
    {"body": "wheel", "type": "pinhole", "point_m": [0, 0.5, 0]},
    {"body": "ball", "type": "pinhole", "point_m": [0, 0.2, 0]}]})"),
              "/cables/0/links", "a link other than a pinhole in a closed cable",
              "only pinhole links (3)");
}

TEST(SemanticErrors, StaticBodyWithDamping) {
  expectError(baseWith(R"("density_kg_per_m3": 1000,)",
                       R"("static": true, "linear_damping_per_s": 0.5,)"),
              "/bodies/0/linear_damping_per_s", "no damping for a static body", "0.5");
}

TEST(SemanticErrors, WrongRestLengthCount) {
  expectError(baseWith(R"({"name": "rope",)", R"({"name": "rope", "rest_length_m": [1, 2, 3],)"),
              "/cables/0/rest_length_m",
              "an array of 2 numbers (one rest length per cable joint: links - 1, for an open "
              "cable)",
              "an array of 3 items");
}

TEST(SemanticErrors, DuplicateCableName) {
  expectError(baseWith(R"("cables": [)", R"("cables": [{"name": "rope", "links": [
    {"body": "crate", "type": "attachment", "point_m": [0, 0, 0]},
    {"body": "ball", "type": "attachment", "point_m": [0, 0, 0]}]},)"),
              "/cables/1/name", "a cable name not already used", "\"rope\"");
}

TEST(SemanticErrors, CableTheSolverCannotBuildIsReportedAtTheCable) {
  // The attachment point lies inside the wheel: no tangent from it exists.
  expectError(baseWith(R"({"body": "crate", "type": "attachment", "point_m": [0, 0.2, 0]})",
                       R"({"body": "crate", "type": "attachment", "point_m": [0.5, 2.0, 0]})"),
              "/cables/0", "a cable the solver can build", "no tangent");
}

TEST(SemanticErrors, CameraLookingAtItsEye) {
  expectError(baseWith(R"("name": "base",)",
                       R"("name": "base", "camera": {"eye_m": [0, 0, 5], "target_m": [0, 0, 5]},)"),
              "/camera/target_m", "a point other than eye_m", "[0,0,5]");
}

TEST(SemanticErrors, CameraUpAlongTheView) {
  expectError(baseWith(R"("name": "base",)",
                       R"("name": "base", "camera": {"eye_m": [0, 5, 0], "target_m": [0, 0, 0]},)"),
              "/camera/up", "not parallel to the view direction", "the default [0,1,0]");
}

TEST(SemanticErrors, DurationShorterThanAFrame) {
  expectError(baseWith(R"("solver": {})", R"("solver": {}, "duration_s": 0.001)"), "/duration_s",
              "a duration of 1 to", "0.001 s (0 frames)");
}

// Sizes and densities whose mass or inertia leave double precision: the
// same clean error from validate and run (they both load), never an abort.
TEST(SemanticErrors, ABoxTooSmallForItsVolumeHasNoMass) {
  // (1e-200 m)^3 underflows to 0: 1000 kg/m^3 x 0 m^3.
  expectError(baseWith(R"("half_extents_m": [0.2, 0.2, 0.2]},
     "mass_kg": 2)", R"("half_extents_m": [1e-200, 1e-200, 1e-200]},
     "density_kg_per_m3": 1000)"),
              "/bodies/1/density_kg_per_m3",
              "a mass between 1e-100 and 1e100 kg (its cube finite and non-zero in double precision)",
              "1000 kg/m^3 x 0 m^3 = 0 kg");
}

TEST(SemanticErrors, ABoxTooSmallGivenAMassHasNoInertia) {
  // 2 kg x ((1e-200)^2 + (1e-200)^2) / 3 underflows to 0 about every axis.
  expectError(baseWith(R"("half_extents_m": [0.2, 0.2, 0.2]})", R"("half_extents_m": [1e-200, 1e-200, 1e-200]})"),
              "/bodies/1/shape", "a size whose moments of inertia are between 1e-100 and 1e100 kg m^2",
              "moments 0, 0, 0 kg m^2 for 2 kg");
}

TEST(SemanticErrors, ADensityAndSizeWhoseMassSquareOverflows) {
  // Each number is allowed, their product is not: 1e150 kg/m^3 over
  // (1000 m)^3 is 1e159 kg, whose square (in energies) is infinite.
  expectError(baseWith(R"("half_extents_m": [0.2, 0.2, 0.2]},
     "mass_kg": 2)", R"("half_extents_m": [500, 500, 500]},
     "density_kg_per_m3": 1e150)"),
              "/bodies/1/density_kg_per_m3",
              "a mass between 1e-100 and 1e100 kg (its cube finite and non-zero in double precision)",
              "1e+150 kg/m^3 x 1e+09 m^3 = 1e+159 kg");
}

TEST(SemanticErrors, ANumberWhoseSquareOverflowsIsRefusedWhereverItIs) {
  // Positions, velocities, gravity: their squares (kinetic energy,
  // distances) must be finite, for a vector of three too.
  expectError(baseWith(R"("mass_kg": 1,)", R"("mass_kg": 1, "linear_velocity_m_per_s": [1e300, 0, 0],)"),
              "/bodies/2/linear_velocity_m_per_s/0", "a number of magnitude at most 1e153 (its square must be finite)",
              "1e+300");
  expectError(baseWith(R"("position_m": [0.5, -2, 0])", R"("position_m": [0.5, -2e154, 0])"),
              "/bodies/2/position_m/1", "a number of magnitude at most 1e153 (its square must be finite)",
              "-2e+154");
}

// A winch on the rope's last link (the ball), with `commands`.
std::string winchWith(const std::string& winch) {
  return baseWith(R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]}]}])",
                  R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]}], "winch": )" + winch + "}]");
}

TEST(SemanticErrors, WinchesAreRefusedWhereTheyCannotReel) {
  // A valid winch loads, at either end (both are attachments).
  EXPECT_NO_THROW(parseScene(winchWith(R"({"end": "first", "commands": [{"from_s": 0, "speed_m_per_s": 0.5}]})"),
                             "test.json"));
  EXPECT_NO_THROW(parseScene(
      winchWith(R"({"end": "last", "max_speed_m_per_s": 1, "commands": [{"from_s": 0, "speed_m_per_s": 0.5},
                {"from_s": 2, "stored_m": 0.3}]})"),
      "test.json"));
  expectError(baseWith(R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]}]}])",
                       R"({"body": "ball", "type": "rolling", "orientation": "cw"}], "winch": {"end": "last", "commands": [{"from_s": 0, "speed_m_per_s": 1}]}}])"),
              "/cables/0/links/2/type", "\"attachment\" for the winch's end link", "\"rolling\"");
  expectError(winchWith(R"({"end": "last", "commands": [{"from_s": 1, "speed_m_per_s": 0.5},
              {"from_s": 1, "speed_m_per_s": 0}]})"),
              "/cables/0/winch/commands/1/from_s", "a time after the command before's (1 s)", "1");
  expectError(winchWith(R"({"end": "last", "commands": [{"from_s": 0, "speed_m_per_s": 0.5, "stored_m": 1}]})"),
              "/cables/0/winch/commands/0", "exactly one of \"speed_m_per_s\"", "both");
  expectError(winchWith(R"({"end": "last", "commands": [{"from_s": 0}]})"), "/cables/0/winch/commands/0",
              "exactly one of \"speed_m_per_s\"", "neither");
  expectError(winchWith(R"({"end": "last", "max_speed_m_per_s": 0.2, "commands": [{"from_s": 0, "speed_m_per_s": -0.5}]})"),
              "/cables/0/winch/commands/0/speed_m_per_s", "a speed within max_speed_m_per_s (0.2)", "-0.5");
  // The schema: bounds and keys.
  expectError(winchWith(R"({"end": "last", "max_pull_N": 0, "commands": [{"from_s": 0, "speed_m_per_s": 1}]})"),
              "/cables/0/winch/max_pull_N", "a number > 0", "0");
  expectError(winchWith(R"({"end": "last", "commands": [{"from_s": 0, "stored_m": -1}]})"),
              "/cables/0/winch/commands/0/stored_m", "a number >= 0", "-1");
  expectError(winchWith(R"({"end": "middle", "commands": [{"from_s": 0, "stored_m": 1}]})"),
              "/cables/0/winch/end", "\"first\"", "\"middle\"");
}

TEST(SemanticErrors, CableDampingMustBeANumberAtLeastZeroOnAnElasticCable) {
  const auto damped = [](const std::string& properties) {
    return baseWith(R"("name": "rope", "links")", R"("name": "rope", )" + properties + R"(, "links")");
  };
  expectError(damped(R"("compliance_m_per_N": 0.01, "damping_N_s_per_m": -2)"), "/cables/0/damping_N_s_per_m",
              "a number >= 0", "-2");
  expectError(damped(R"("compliance_m_per_N": 0.01, "damping_N_s_per_m": "2")"), "/cables/0/damping_N_s_per_m",
              "a number", "\"2\"");
  expectError(damped(R"("compliance_m_per_N": 0.01, "damping_N_s_per_m": 1e300)"), "/cables/0/damping_N_s_per_m",
              "a number of magnitude at most 1e153", "1e+300");
  // JSON has no infinity: too large for a double is a syntax error there.
  const std::optional<SceneError> e = errorOf(damped(R"("compliance_m_per_N": 0.01, "damping_N_s_per_m": 1e400)"));
  ASSERT_TRUE(e);
  EXPECT_NE(e->found().find("number overflow parsing '1e400'"), std::string::npos) << e->what();
  // A rigid cable does not stretch: nothing to damp.
  expectError(damped(R"("damping_N_s_per_m": 2)"), "/cables/0/damping_N_s_per_m",
              "no damping without compliance_m_per_N > 0", "2");
  expectError(damped(R"("compliance_m_per_N": 0, "damping_N_s_per_m": 0.5)"), "/cables/0/damping_N_s_per_m",
              "no damping without compliance_m_per_N > 0", "0.5");
}

TEST(SemanticErrors, AWinchOnABeltAndABreakingTensionOfZeroAreRefused) {
  expectError(baseWith(R"("name": "rope", "links")", R"("name": "rope", "closed": true, "winch": {"end": "last", "commands": [{"from_s": 0, "speed_m_per_s": 1}]}, "links")"),
              "/cables/0/winch", "no winch on a closed cable", "");
  expectError(baseWith(R"("name": "rope", "links")", R"("name": "rope", "breaking_tension_N": 0, "links")"),
              "/cables/0/breaking_tension_N", "a number > 0", "0");
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

TEST(SemanticErrors, MomentsOfInertiaNeedAMass) {
  expectError(baseWith(R"("density_kg_per_m3": 1000,)", R"("density_kg_per_m3": 1000, "inertia_kg_m2": [1, 1, 1],)"),
              "/bodies/0/inertia_kg_m2", "mass_kg with moments of inertia", "density_kg_per_m3");
}

}  // namespace
}  // namespace reeve::test
