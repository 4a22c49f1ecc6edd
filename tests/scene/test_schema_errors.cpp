// Errors the schema finds, phrased with the JSON pointer, what the schema
// expects and what the scene has.
#include "scene_test_util.h"

namespace reeve::test {
namespace {

TEST(SchemaErrors, MissingRequiredField) {
  expectError(baseWith(R"("radius_m": 0.5, "half_length_m": 0.1)", R"("half_length_m": 0.1)"),
              "/bodies/0/shape", "required property \"radius_m\"", "nothing");
}

TEST(SchemaErrors, MissingRequiredTopLevelFieldIsAtTheRoot) {
  expectError(R"({"name": "x", "solver": {}})", "", "required property \"bodies\"", "nothing");
}

TEST(SchemaErrors, UnknownFieldListsTheAllowedOnes) {
  expectError(baseWith(R"("mass_kg": 2,)", R"("mass_kg": 2, "colour": "red",)"), "/bodies/1/colour",
              "no property \"colour\" (allowed: name, shape, density_kg_per_m3, mass_kg, inertia_kg_m2, "
              "position_m, orientation, static, linear_velocity_m_per_s, "
              "angular_velocity_rad_per_s, linear_damping_per_s, angular_damping_per_s, "
              "static_friction, dynamic_friction, restitution, collides, contact_type, contact_affinity, motion)",
              "\"colour\"");
}

TEST(SchemaErrors, FieldOfAnotherShapeIsUnknown) {
  expectError(baseWith(R"("half_extents_m": [0.2, 0.2, 0.2]})",
                       R"("half_extents_m": [0.2, 0.2, 0.2], "radius_m": 0.2})"),
              "/bodies/1/shape/radius_m",
              "no property \"radius_m\" (allowed: type, half_extents_m)", "\"radius_m\"");
}

TEST(SchemaErrors, PointOnARollingLinkIsUnknown) {
  expectError(baseWith(R"("orientation": "cw"})", R"("orientation": "cw", "point_m": [0, 0, 0]})"),
              "/cables/0/links/1/point_m",
              "no property \"point_m\" (allowed: body, type, orientation, stored_m, section, "
              "plane_offset_m, active, mu)",
              "\"point_m\"");
}

TEST(SchemaErrors, AttachmentWithoutPoint) {
  expectError(baseWith(R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]})",
                       R"({"body": "ball", "type": "attachment"})"),
              "/cables/0/links/2", "required property \"point_m\"", "nothing");
}

TEST(SchemaErrors, UnknownFieldNameIsEscapedInThePointer) {
  expectError(baseWith(R"("solver": {})", R"("solver": {"a/b~c": 1})"), "/solver/a~1b~0c",
              "no property \"a/b~c\" (allowed: frame_rate_hz, substeps, iterations, method, projection, "
              "max_linear_speed_m_per_s, max_angular_speed_rad_per_s, gravity_m_per_s2)",
              "\"a/b~c\"");
}

// "$schema" is for editors: any string is accepted and changes nothing;
// another kind of value is an error like any other.
TEST(SchemaErrors, SchemaKeyIsAStringForEditorsAndOtherwiseIgnored) {
  const Scene plain = parseScene(kBase, "test.json");
  const Scene named = parseScene(baseWith(R"("name": "base",)", R"("$schema": "elsewhere/any.json", "name": "base",)"),
                                 "test.json");
  ASSERT_EQ(named.world->bodyCount(), plain.world->bodyCount());
  for (BodyId b = 0; b < plain.world->bodyCount(); ++b) {
    EXPECT_EQ(named.world->body(b).x, plain.world->body(b).x);
    EXPECT_EQ(named.world->body(b).inv_mass, plain.world->body(b).inv_mass);
  }
  EXPECT_EQ(named.cables->restLength(0, 0), plain.cables->restLength(0, 0));
  expectError(baseWith(R"("name": "base",)", R"("$schema": 7, "name": "base",)"), "/$schema", "a string",
              "7");
}

TEST(SchemaErrors, WrongType) {
  expectError(baseWith(R"("solver": {})", R"("solver": {"substeps": "ten"})"), "/solver/substeps",
              "an integer", "a string (\"ten\")");
}

TEST(SchemaErrors, WrongTypeForAVector) {
  expectError(baseWith(R"("position_m": [0.5, -2, 0])", R"("position_m": "0.5, -2, 0")"),
              "/bodies/2/position_m", "an array of 3 numbers", "a string (\"0.5, -2, 0\")");
}

TEST(SchemaErrors, WrongTypeInAVector) {
  expectError(baseWith(R"("position_m": [0.5, -2, 0])", R"("position_m": [0.5, "-2", 0])"),
              "/bodies/2/position_m/1", "a number", "a string (\"-2\")");
}

TEST(SchemaErrors, VectorOfTwoNumbers) {
  expectError(baseWith(R"("axis": [0, 0, 1])", R"("axis": [0, 1])"), "/hinges/0/axis",
              "an array of 3 numbers", "an array of 2 items");
}

TEST(SchemaErrors, RootMustBeAnObject) {
  const std::optional<SceneError> e = errorOf("[]");
  ASSERT_TRUE(e);
  EXPECT_EQ(std::string(e->what()),
            "test.json: (root): expected an object, got an array of 0 items");
}

TEST(SchemaErrors, NegativeMass) {
  expectError(baseWith(R"("mass_kg": 2,)", R"("mass_kg": -2,)"), "/bodies/1/mass_kg",
              "a number > 0", "-2");
}

TEST(SchemaErrors, NegativeRadius) {
  const std::string text = baseWith(R"("radius_m": 0.5)", R"("radius_m": -0.5)");
  expectError(text, "/bodies/0/shape/radius_m", "a number > 0", "-0.5");
  EXPECT_STREQ(errorOf(text)->what(),
               "test.json: /bodies/0/shape/radius_m: expected a number > 0, got -0.5");
}

TEST(SchemaErrors, ZeroHalfExtent) {
  expectError(
      baseWith(R"("half_extents_m": [0.2, 0.2, 0.2])", R"("half_extents_m": [0.2, 0, 0.2])"),
      "/bodies/1/shape/half_extents_m/1", "a number > 0", "0");
}

TEST(SchemaErrors, ZeroSubsteps) {
  expectError(baseWith(R"("solver": {})", R"("solver": {"substeps": 0})"), "/solver/substeps",
              "an integer >= 1 and <= 100000", "0");
}

// JSON Schema counts 10.0 as an integer (draft 6 on); 10.5 is not one.
TEST(SchemaErrors, IntegerSettingsAcceptAWholeNumberWithAFraction) {
  const Scene s = parseScene(baseWith(R"("solver": {})", R"("solver": {"substeps": 10.0, "iterations": 3e0})"),
                             "test.json");
  EXPECT_EQ(s.world->settings().substeps, 10);
  EXPECT_EQ(s.world->settings().iterations, 3);
  expectError(baseWith(R"("solver": {})", R"("solver": {"substeps": 10.5})"), "/solver/substeps",
              "an integer", "10.5");
}

TEST(SchemaErrors, FieldOfViewOutOfRange) {
  expectError(
      baseWith(
          R"("name": "base",)",
          R"("name": "base",
              "camera": {"eye_m": [0, 0, 5], "target_m": [0, 0, 0], "fov_y_deg": 200},)"),
      "/camera/fov_y_deg", "a number > 0 and < 180", "200");
}

TEST(SchemaErrors, UnknownShapeType) {
  expectError(baseWith(R"("type": "sphere")", R"("type": "cone")"), "/bodies/2/shape/type",
              "one of \"box\", \"cylinder\", \"sphere\"", "\"cone\"");
}

TEST(SchemaErrors, UnknownSolverMethod) {
  expectError(baseWith(R"("solver": {})", R"("solver": {"method": "jacobi"})"), "/solver/method",
              "one of \"direct\", \"gauss-seidel\"", "\"jacobi\"");
}

TEST(SchemaErrors, UnknownLinkOrientation) {
  expectError(baseWith(R"("orientation": "cw")", R"("orientation": "clockwise")"),
              "/cables/0/links/1/orientation", "one of \"ccw\", \"cw\"", "\"clockwise\"");
}

TEST(SchemaErrors, EmptyName) {
  expectError(baseWith(R"("name": "base")", R"("name": "")"), "/name", "a non-empty string",
              "\"\"");
}

TEST(SchemaErrors, CableWithOneLink) {
  expectError(R"({"name": "x", "solver": {},
    "bodies": [{"name": "b", "shape": {"type": "sphere", "radius_m": 1}, "mass_kg": 1,
                "position_m": [0, 0, 0]}],
    "cables": [{"name": "c", "links": [
      {"body": "b", "type": "attachment", "point_m": [0, 0, 0]}]}]})",
              "/cables/0/links", "an array of at least 2 items", "an array of 1 item");
}

TEST(SchemaErrors, UnknownLinkType) {
  expectError(baseWith(R"("type": "rolling")", R"("type": "sliding")"),
              "/cables/0/links/1/type",
              "one of \"attachment\", \"rolling\", \"pinhole\", \"hybrid\"", "\"sliding\"");
}

TEST(SchemaErrors, PinholeWithoutPoint) {
  expectError(baseWith(R"({"body": "wheel", "type": "rolling", "orientation": "cw"})",
                       R"({"body": "wheel", "type": "pinhole"})"),
              "/cables/0/links/1", "required property \"point_m\"", "nothing");
}

TEST(SchemaErrors, OrientationOnAPinholeIsUnknown) {
  expectError(baseWith(R"({"body": "wheel", "type": "rolling", "orientation": "cw"})",
                       R"({"body": "wheel", "type": "pinhole", "point_m": [0, 1, 0],
                           "orientation": "cw"})"),
              "/cables/0/links/1/orientation",
              "no property \"orientation\" (allowed: body, type, point_m, mu)", "\"orientation\"");
}

TEST(SchemaErrors, ActiveOnAHybridLinkIsUnknown) {
  expectError(baseWith(R"({"body": "ball", "type": "attachment", "point_m": [0, 0.2, 0]})",
                       R"({"body": "ball", "type": "hybrid", "orientation": "cw", "active": true})"),
              "/cables/0/links/2/active",
              "no property \"active\" (allowed: body, type, orientation, stored_m, section, "
              "plane_offset_m)",
              "\"active\"");
}

TEST(SchemaErrors, NegativeStoredCable) {
  expectError(baseWith(R"("orientation": "cw"})", R"("orientation": "cw", "stored_m": -1})"),
              "/cables/0/links/1/stored_m", "a number >= 0", "-1");
}

TEST(SchemaErrors, ActiveMustBeABoolean) {
  expectError(baseWith(R"("orientation": "cw"})", R"("orientation": "cw", "active": "no"})"),
              "/cables/0/links/1/active", "true or false", "a string (\"no\")");
}

TEST(SchemaErrors, ClosedMustBeABoolean) {
  expectError(baseWith(R"({"name": "rope",)", R"({"name": "rope", "closed": 1,)"),
              "/cables/0/closed", "true or false", "an integer (1)");
}

TEST(SchemaErrors, SectionWithRadiusAndPolygon) {
  expectError(baseWith(R"("orientation": "cw"})",
                       R"("orientation": "cw",
                           "section": {"radius_m": 0.2, "polygon_m": [[0, 0], [1, 0], [0, 1]]}})"),
              "/cables/0/links/1/section/radius_m",
              "no property \"radius_m\" (allowed: polygon_m)", "\"radius_m\"");
}

TEST(SchemaErrors, EmptySectionNeedsARadius) {
  expectError(baseWith(R"("orientation": "cw"})", R"("orientation": "cw", "section": {}})"),
              "/cables/0/links/1/section", "required property \"radius_m\"", "nothing");
}

TEST(SchemaErrors, ZeroSectionRadius) {
  expectError(baseWith(R"("orientation": "cw"})",
                       R"("orientation": "cw", "section": {"radius_m": 0}})"),
              "/cables/0/links/1/section/radius_m", "a number > 0", "0");
}

TEST(SchemaErrors, PolygonOfTwoPoints) {
  expectError(baseWith(R"("orientation": "cw"})",
                       R"("orientation": "cw", "section": {"polygon_m": [[0, 0], [1, 0]]}})"),
              "/cables/0/links/1/section/polygon_m", "an array of at least 3 items",
              "an array of 2 items");
}

TEST(SchemaErrors, PolygonPointOfThreeNumbers) {
  expectError(
      baseWith(R"("orientation": "cw"})",
               R"("orientation": "cw", "section": {"polygon_m": [[0, 0], [1, 0], [0, 1, 0]]}})"),
      "/cables/0/links/1/section/polygon_m/2", "an array of 2 numbers", "an array of 3 items");
}

TEST(SchemaErrors, CircleCentreOfThreeNumbers) {
  expectError(baseWith(R"("orientation": "cw"})",
                       R"("orientation": "cw", "section": {"radius_m": 0.2, "centre_m": [0, 0.1, 0]}})"),
              "/cables/0/links/1/section/centre_m", "an array of 2 numbers", "an array of 3 items");
}

TEST(SchemaErrors, APolygonHasNoCentre) {
  // Its vertices are where it is.
  expectError(baseWith(R"("orientation": "cw"})",
                       R"("orientation": "cw",
                           "section": {"polygon_m": [[0, 0], [1, 0], [0, 1]], "centre_m": [1, 0]}})"),
              "/cables/0/links/1/section/centre_m", "no property \"centre_m\" (allowed: polygon_m)",
              "\"centre_m\"");
}

TEST(SchemaErrors, PlaneOffsetMustBeANumber) {
  expectError(baseWith(R"("orientation": "cw"})",
                       R"("orientation": "cw", "plane_offset_m": "0.1"})"),
              "/cables/0/links/1/plane_offset_m", "a number", "a string (\"0.1\")");
}

TEST(SchemaErrors, NegativeDamping) {
  expectError(baseWith(R"("mass_kg": 2,)", R"("mass_kg": 2, "angular_damping_per_s": -0.1,)"),
              "/bodies/1/angular_damping_per_s", "a number >= 0", "-0.1");
}

}  // namespace
}  // namespace reeve::test
