// Joints in the JSON scene format (scenes/README.md, "Hinge" and "Joint"):
// every joint type and the hinge limit and drive load and map to the right
// values, defaults are the schema's, one error per kind of malformed joint.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "reeve/scene/scene.h"

namespace reeve::test_joint_scenes {
namespace {

// Five bodies, two hinges (a motor, a servo with a limit) and one joint of
// each other type.
constexpr const char* kJoints = R"({
  "name": "joints",
  "solver": {"gravity_m_per_s2": [0, -10, 0]},
  "bodies": [
    {"name": "wheel", "shape": {"type": "cylinder", "radius_m": 0.3, "half_length_m": 0.05},
     "mass_kg": 4, "position_m": [0, 0, 0]},
    {"name": "arm", "shape": {"type": "box", "half_extents_m": [0.5, 0.05, 0.05]},
     "mass_kg": 1, "position_m": [2.5, 0, 0]},
    {"name": "slider", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]},
     "mass_kg": 2, "position_m": [0, -2, 0]},
    {"name": "bob", "shape": {"type": "sphere", "radius_m": 0.1},
     "mass_kg": 1, "position_m": [3, -1, 0]},
    {"name": "weight", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]},
     "mass_kg": 3, "position_m": [3, -1.3, 0]}
  ],
  "hinges": [
    {"body": "wheel", "anchor_m": [0, 0, 0], "axis": [0, 0, 1],
     "drive": {"mode": "velocity", "target_rad_per_s": 10, "max_torque_N_m": 1.5}},
    {"body": "arm", "anchor_m": [2, 0, 0], "axis": [0, 0, 2],
     "limit": {"lower_rad": -0.5, "upper_rad": 1.0},
     "drive": {"mode": "angle", "target_rad": 0.25, "max_torque_N_m": 20}}
  ],
  "joints": [
    {"type": "prismatic", "body": "slider", "anchor_m": [0, -2, 0], "axis": [2, 0, 0],
     "limit": {"lower_m": -1, "upper_m": 1.5},
     "drive": {"mode": "velocity", "target_m_per_s": 0.5, "max_force_N": 30}},
    {"type": "spherical", "body": "bob", "anchor_m": [3, 0, 0], "axis": [0, -1, 0],
     "swing_limit_rad": 0.7, "twist_limit": {"lower_rad": -0.2, "upper_rad": 0.3}},
    {"type": "fixed", "body": "weight", "other": "bob", "anchor_m": [3, -1.2, 0],
     "compliance": 1e-6}
  ]
})";

std::string with(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "not in the scene: " << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "twice in the scene: " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string jointsWith(const std::string& from, const std::string& to) {
  return with(kJoints, from, to);
}

// Checks the SceneError of `text`: the pointer exactly, and that expected()
// and found() contain the given words, in the format of scenes/README.md.
void expectError(const std::string& text, const std::string& pointer,
                 const std::string& expected_words, const std::string& found_words) {
  try {
    parseScene(text, "test.json");
  } catch (const SceneError& e) {
    EXPECT_EQ(e.jsonPath(), pointer) << e.what();
    EXPECT_NE(e.expected().find(expected_words), std::string::npos) << e.what();
    EXPECT_NE(e.found().find(found_words), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()),
              "test.json: " + pointer + ": expected " + e.expected() + ", got " + e.found());
    return;
  }
  ADD_FAILURE() << "no SceneError for:\n" << text;
}

void expectVec(const Vec3& actual, const Vec3& expected) {
  EXPECT_LE((actual - expected).norm(), 1e-12) << actual.transpose() << " vs "
                                               << expected.transpose();
}

TEST(JointScenes, HingeLimitsAndDrivesMapToTheirValues) {
  const Scene s = parseScene(kJoints, "joints.json");
  const World& w = *s.world;
  ASSERT_EQ(w.hinges().size(), 2u);
  const HingeJoint& motor = w.hinge(0);
  EXPECT_FALSE(motor.limit.enabled);
  EXPECT_EQ(motor.drive.mode, HingeDrive::Mode::Velocity);
  EXPECT_EQ(motor.drive.target, 10.0);
  EXPECT_EQ(motor.drive.max_torque, 1.5);
  const HingeJoint& servo = w.hinge(1);
  EXPECT_EQ(servo.a, *w.findBody("arm"));
  EXPECT_EQ(servo.b, kWorldBody);
  expectVec(servo.frame.axis_b, Vec3::UnitZ());  // [0, 0, 2] normalized
  expectVec(servo.frame.anchor_a, Vec3(-0.5, 0, 0));
  EXPECT_TRUE(servo.limit.enabled);
  EXPECT_EQ(servo.limit.lower, -0.5);
  EXPECT_EQ(servo.limit.upper, 1.0);
  EXPECT_EQ(servo.drive.mode, HingeDrive::Mode::Angle);
  EXPECT_EQ(servo.drive.target, 0.25);
  EXPECT_EQ(servo.drive.max_torque, 20.0);
}

TEST(JointScenes, EachJointTypeMapsToItsValues) {
  const Scene s = parseScene(kJoints, "joints.json");
  const World& w = *s.world;
  ASSERT_EQ(w.prismatics().size(), 1u);
  const PrismaticJoint& p = w.prismatic(0);
  EXPECT_EQ(p.a, *w.findBody("slider"));
  EXPECT_EQ(p.b, kWorldBody);
  expectVec(p.axis_b, Vec3::UnitX());
  expectVec(p.anchor_a, Vec3::Zero());
  EXPECT_TRUE(p.limit.enabled);
  EXPECT_EQ(p.limit.lower, -1.0);
  EXPECT_EQ(p.limit.upper, 1.5);
  EXPECT_EQ(p.drive.mode, PrismaticDrive::Mode::Velocity);
  EXPECT_EQ(p.drive.target, 0.5);
  EXPECT_EQ(p.drive.max_force, 30.0);

  ASSERT_EQ(w.sphericals().size(), 1u);
  const SphericalJoint& ball = w.spherical(0);
  EXPECT_EQ(ball.a, *w.findBody("bob"));
  expectVec(ball.frame.anchor_a, Vec3(0, 1, 0));
  expectVec(ball.frame.anchor_b, Vec3(3, 0, 0));
  expectVec(ball.frame.axis_b, -Vec3::UnitY());
  EXPECT_TRUE(ball.swing_limit.enabled);
  EXPECT_EQ(ball.swing_limit.max, 0.7);
  EXPECT_TRUE(ball.twist_limit.enabled);
  EXPECT_EQ(ball.twist_limit.lower, -0.2);
  EXPECT_EQ(ball.twist_limit.upper, 0.3);

  ASSERT_EQ(w.fixedJoints().size(), 1u);
  const FixedJoint& weld = w.fixedJoint(0);
  EXPECT_EQ(weld.a, *w.findBody("weight"));
  EXPECT_EQ(weld.b, *w.findBody("bob"));
  expectVec(weld.anchor_a, Vec3(0, 0.1, 0));
  expectVec(weld.anchor_b, Vec3(0, -0.2, 0));
  EXPECT_EQ(weld.compliance, 1e-6);
}

TEST(JointScenes, DefaultsAreTheSchemasAndOmittedLimitsAndMaximaMeanNone) {
  const nlohmann::json defs = nlohmann::json::parse(sceneSchemaJson()).at("definitions");
  const Scene s = parseScene(R"({
    "name": "defaults", "solver": {},
    "bodies": [
      {"name": "a", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": 1,
       "position_m": [0, 0, 0]},
      {"name": "b", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]}, "mass_kg": 1,
       "position_m": [1, 0, 0]}],
    "hinges": [{"body": "a", "anchor_m": [0, 0, 0], "axis": [0, 0, 1],
                "drive": {"mode": "velocity", "target_rad_per_s": 1}}],
    "joints": [
      {"type": "prismatic", "body": "a", "anchor_m": [0, 0, 0], "axis": [1, 0, 0],
       "drive": {"mode": "position", "target_m": 0.1}},
      {"type": "spherical", "body": "b", "anchor_m": [1, 1, 0]},
      {"type": "fixed", "body": "b", "anchor_m": [1, 0, 0]}]})",
                             "defaults.json");
  const World& w = *s.world;
  for (const char* type : {"prismatic_joint", "spherical_joint", "fixed_joint"}) {
    const nlohmann::json& props = defs.at(type).at("properties");
    EXPECT_EQ(props.at("other").at("default"), "world") << type;
    EXPECT_EQ(props.at("compliance").at("default"), 0) << type;
  }
  EXPECT_EQ(w.prismatic(0).b, kWorldBody);
  EXPECT_EQ(w.spherical(0).b, kWorldBody);
  EXPECT_EQ(w.fixedJoint(0).b, kWorldBody);
  EXPECT_EQ(w.prismatic(0).compliance, 0.0);
  EXPECT_EQ(w.spherical(0).compliance, 0.0);
  EXPECT_EQ(w.fixedJoint(0).compliance, 0.0);
  // No limit unless given; a drive without a maximum is unlimited.
  EXPECT_FALSE(w.hinge(0).limit.enabled);
  EXPECT_TRUE(isUnlimited(w.hinge(0).drive.max_torque));
  EXPECT_FALSE(w.prismatic(0).limit.enabled);
  EXPECT_EQ(w.prismatic(0).drive.mode, PrismaticDrive::Mode::Position);
  EXPECT_EQ(w.prismatic(0).drive.target, 0.1);
  EXPECT_TRUE(isUnlimited(w.prismatic(0).drive.max_force));
  EXPECT_FALSE(w.spherical(0).swing_limit.enabled);
  EXPECT_FALSE(w.spherical(0).twist_limit.enabled);
  EXPECT_FALSE(defs.at("hinge_velocity_drive").at("properties").at("max_torque_N_m").contains("default"));
}

// The motor of kJoints through the whole loader: w(t) = tau t / I while
// below its target (I = m r^2 / 2 = 0.18 kg m^2, tau = 1.5 N m: 8.33 rad/s
// after 1 s, under the 10 rad/s target).
TEST(JointScenes, AMotorFromJsonSpinsUpAtTorqueOverInertia) {
  Scene s = parseScene(kJoints, "joints.json");
  for (int f = 0; f < 60; ++f) s.world->step(1.0 / s.frame_rate_hz);
  const double expected = 1.5 * s.world->time() / (0.5 * 4.0 * 0.3 * 0.3);
  EXPECT_NEAR(s.world->body(*s.world->findBody("wheel")).omega.z(), expected, 0.01 * expected);
}

// kJoints with the servo a torsional spring and the slider's drive a
// linear spring, each with the extra keys `hinge_extra` and
// `prismatic_extra` (JSON members, or "").
constexpr const char* kServo = R"("target_rad": 0.25, "max_torque_N_m": 20)";
constexpr const char* kSliderDrive = R"({"mode": "velocity", "target_m_per_s": 0.5, "max_force_N": 30})";

std::string springsWith(const std::string& hinge_extra, const std::string& prismatic_extra) {
  return with(jointsWith(kServo, std::string(kServo) + hinge_extra), kSliderDrive,
              R"({"mode": "position", "target_m": 0.2)" + prismatic_extra + "}");
}

TEST(JointScenes, SpringDrivesMapToTheirValues) {
  const nlohmann::json defs = nlohmann::json::parse(sceneSchemaJson()).at("definitions");
  const Scene s = parseScene(springsWith(R"(, "stiffness_N_m_per_rad": 30, "damping_N_m_s_per_rad": 1.5)",
                                         R"(, "stiffness_N_per_m": 400)"),
                             "springs.json");
  const World& w = *s.world;
  EXPECT_EQ(w.hinge(0).drive.stiffness, 0.0);  // the motor: no spring
  const HingeDrive& servo = w.hinge(1).drive;
  EXPECT_EQ(servo.mode, HingeDrive::Mode::Angle);
  EXPECT_EQ(servo.target, 0.25);
  EXPECT_EQ(servo.max_torque, 20.0);
  EXPECT_EQ(servo.stiffness, 30.0);
  EXPECT_EQ(servo.damping, 1.5);
  const PrismaticDrive& slider = w.prismatic(0).drive;
  EXPECT_EQ(slider.mode, PrismaticDrive::Mode::Position);
  EXPECT_EQ(slider.target, 0.2);
  EXPECT_TRUE(isUnlimited(slider.max_force));
  EXPECT_EQ(slider.stiffness, 400.0);
  EXPECT_EQ(slider.damping, defs.at("prismatic_position_drive").at("properties").at("damping_N_s_per_m").at("default"));
  EXPECT_EQ(defs.at("hinge_angle_drive").at("properties").at("damping_N_m_s_per_rad").at("default"), 0);
  EXPECT_FALSE(defs.at("hinge_angle_drive").at("properties").at("stiffness_N_m_per_rad").contains("default"));
}

TEST(JointScenes, SpringIntegrationAndDriveEndTimesMapToTheirValues) {
  const nlohmann::json defs = nlohmann::json::parse(sceneSchemaJson()).at("definitions");
  const Scene s = parseScene(
      with(springsWith(R"(, "stiffness_N_m_per_rad": 30, "integration": "trapezoidal", "until_s": 2.5)",
                       R"(, "stiffness_N_per_m": 400, "integration": "trapezoidal")"),
           R"("max_torque_N_m": 1.5})", R"("max_torque_N_m": 1.5, "until_s": 0.5})"),
      "springs.json");
  const World& w = *s.world;
  EXPECT_EQ(w.hinge(0).drive.until, 0.5);
  EXPECT_EQ(w.hinge(0).drive.integration, HingeDrive::Integration::Implicit);
  EXPECT_EQ(w.hinge(1).drive.integration, HingeDrive::Integration::Trapezoidal);
  EXPECT_TRUE(w.hinge(1).drive.isTrapezoidalSpring());
  EXPECT_EQ(w.hinge(1).drive.until, 2.5);
  EXPECT_EQ(w.prismatic(0).drive.integration, PrismaticDrive::Integration::Trapezoidal);
  EXPECT_TRUE(std::isinf(w.prismatic(0).drive.until));  // omitted: always
  EXPECT_EQ(defs.at("hinge_angle_drive").at("properties").at("integration").at("default"), "implicit");
  EXPECT_EQ(defs.at("prismatic_position_drive").at("properties").at("integration").at("default"), "implicit");
  const Scene plain = parseScene(springsWith(R"(, "stiffness_N_m_per_rad": 30)", ""), "springs.json");
  EXPECT_EQ(plain.world->hinge(1).drive.integration, HingeDrive::Integration::Implicit);
  EXPECT_FALSE(plain.world->hinge(1).drive.isTrapezoidalSpring());
}

// kJoints' motor with "until_s": 0.5 spins up at torque / inertia until
// then and coasts on at tau 0.5 s / I (no drive, no friction); its drive is
// gone (mode None) from then on.
TEST(JointScenes, ADriveLetsGoAtItsEndTime) {
  Scene s = parseScene(jointsWith(R"("max_torque_N_m": 1.5})", R"("max_torque_N_m": 1.5, "until_s": 0.5})"),
                       "joints.json");
  const BodyId wheel = *s.world->findBody("wheel");
  const double inertia = 0.5 * 4.0 * 0.3 * 0.3;
  for (int f = 0; f < 30; ++f) s.world->step(1.0 / s.frame_rate_hz);
  EXPECT_EQ(s.world->hinge(0).drive.mode, HingeDrive::Mode::Velocity);
  EXPECT_NEAR(s.world->body(wheel).omega.z(), 1.5 * 0.5 / inertia, 1e-9);
  for (int f = 0; f < 30; ++f) s.world->step(1.0 / s.frame_rate_hz);
  EXPECT_EQ(s.world->hinge(0).drive.mode, HingeDrive::Mode::None);
  EXPECT_NEAR(s.world->body(wheel).omega.z(), 1.5 * 0.5 / inertia, 1e-9);
}

TEST(JointErrors, HingeStiffnessNotPositive) {
  expectError(springsWith(R"(, "stiffness_N_m_per_rad": 0)", ""), "/hinges/1/drive/stiffness_N_m_per_rad",
              "a number > 0", "0");
}

TEST(JointErrors, HingeStiffnessNotANumber) {
  expectError(springsWith(R"(, "stiffness_N_m_per_rad": "stiff")", ""), "/hinges/1/drive/stiffness_N_m_per_rad",
              "a number", "\"stiff\"");
}

TEST(JointErrors, NegativeHingeDamping) {
  expectError(springsWith(R"(, "stiffness_N_m_per_rad": 30, "damping_N_m_s_per_rad": -1.5)", ""),
              "/hinges/1/drive/damping_N_m_s_per_rad", "a number >= 0", "-1.5");
}

TEST(JointErrors, HingeDampingWithoutStiffness) {
  expectError(springsWith(R"(, "damping_N_m_s_per_rad": 1.5)", ""), "/hinges/1/drive/damping_N_m_s_per_rad",
              "no damping_N_m_s_per_rad without stiffness_N_m_per_rad", "1.5");
}

TEST(JointErrors, StiffnessOnAHingeVelocityDrive) {
  expectError(jointsWith(R"("max_torque_N_m": 1.5)", R"("max_torque_N_m": 1.5, "stiffness_N_m_per_rad": 30)"),
              "/hinges/0/drive/stiffness_N_m_per_rad",
              "no property \"stiffness_N_m_per_rad\" (allowed: mode, target_rad_per_s, schedule, max_torque_N_m, until_s, damping_N_m_s_per_rad)",
              "\"stiffness_N_m_per_rad\"");
}

TEST(JointErrors, PrismaticStiffnessNotPositive) {
  expectError(springsWith("", R"(, "stiffness_N_per_m": -400)"), "/joints/0/drive/stiffness_N_per_m",
              "a number > 0", "-400");
}

TEST(JointErrors, NegativePrismaticDamping) {
  expectError(springsWith("", R"(, "stiffness_N_per_m": 400, "damping_N_s_per_m": -2)"),
              "/joints/0/drive/damping_N_s_per_m", "a number >= 0", "-2");
}

TEST(JointErrors, PrismaticDampingWithoutStiffness) {
  expectError(springsWith("", R"(, "damping_N_s_per_m": 2)"), "/joints/0/drive/damping_N_s_per_m",
              "no damping_N_s_per_m without stiffness_N_per_m", "2");
}

TEST(JointErrors, StiffnessOnAPrismaticVelocityDrive) {
  expectError(jointsWith(R"("max_force_N": 30)", R"("max_force_N": 30, "stiffness_N_per_m": 400)"),
              "/joints/0/drive/stiffness_N_per_m",
              "no property \"stiffness_N_per_m\" (allowed: mode, target_m_per_s, schedule, max_force_N, until_s, damping_N_s_per_m)",
              "\"stiffness_N_per_m\"");
}

TEST(JointErrors, HingeIntegrationWithoutStiffness) {
  expectError(springsWith(R"(, "integration": "trapezoidal")", ""), "/hinges/1/drive/integration",
              "no integration without stiffness_N_m_per_rad", "\"trapezoidal\"");
}

TEST(JointErrors, PrismaticIntegrationWithoutStiffness) {
  expectError(springsWith("", R"(, "integration": "implicit")"), "/joints/0/drive/integration",
              "no integration without stiffness_N_per_m", "\"implicit\"");
}

TEST(JointErrors, UnknownSpringIntegration) {
  expectError(springsWith(R"(, "stiffness_N_m_per_rad": 30, "integration": "explicit")", ""),
              "/hinges/1/drive/integration", R"(one of "implicit", "trapezoidal")", "\"explicit\"");
}

TEST(JointErrors, IntegrationOnAHingeVelocityDrive) {
  expectError(jointsWith(R"("max_torque_N_m": 1.5})", R"("max_torque_N_m": 1.5, "integration": "trapezoidal"})"),
              "/hinges/0/drive/integration",
              "no property \"integration\" (allowed: mode, target_rad_per_s, schedule, max_torque_N_m, until_s, damping_N_m_s_per_rad)",
              "\"integration\"");
}

TEST(JointErrors, DriveEndTimeNotPositive) {
  expectError(jointsWith(R"("max_force_N": 30)", R"("max_force_N": 30, "until_s": 0)"),
              "/joints/0/drive/until_s", "a number > 0", "0");
}

TEST(JointErrors, UnknownJointType) {
  expectError(jointsWith(R"("type": "fixed")", R"("type": "weld")"), "/joints/2/type",
              R"(one of "prismatic", "spherical", "fixed")", "\"weld\"");
}

TEST(JointErrors, HingeLimitLowerAboveUpper) {
  expectError(jointsWith(R"({"lower_rad": -0.5, "upper_rad": 1.0})",
                         R"({"lower_rad": 0.5, "upper_rad": -0.5})"),
              "/hinges/1/limit/upper_rad", "an angle >= lower_rad 0.5", "-0.5");
}

TEST(JointErrors, SlideLimitLowerAboveUpper) {
  expectError(jointsWith(R"({"lower_m": -1, "upper_m": 1.5})", R"({"lower_m": 2, "upper_m": 1.5})"),
              "/joints/0/limit/upper_m", "a number >= lower_m 2", "1.5");
}

TEST(JointErrors, TwistLimitLowerAboveUpper) {
  expectError(jointsWith(R"({"lower_rad": -0.2, "upper_rad": 0.3})",
                         R"({"lower_rad": 0.2, "upper_rad": 0.1})"),
              "/joints/1/twist_limit/upper_rad", "an angle >= lower_rad 0.2", "0.1");
}

TEST(JointErrors, ATwistLimitNeedsASwingLimitOfAtMostAQuarterTurn) {
  // The twist about the two axes' mean is undefined as the swing nears pi:
  // a body on a ball joint with a twist limit alone, swung over its axis,
  // gained 1e5 J (kMaxSwingWithTwist).
  expectError(jointsWith(R"("swing_limit_rad": 0.7, )", ""), "/joints/1",
              "swing_limit_rad of at most pi/2 with a twist_limit (the twist is ill-defined as the swing nears pi)",
              "a twist_limit alone");
  expectError(jointsWith(R"("swing_limit_rad": 0.7)", R"("swing_limit_rad": 1.6)"), "/joints/1/swing_limit_rad",
              "at most pi/2 rad with a twist_limit (the twist is ill-defined as the swing nears pi)", "1.6");
  EXPECT_NO_THROW(parseScene(jointsWith(R"("swing_limit_rad": 0.7)", R"("swing_limit_rad": 1.57)"), "test.json"));
}

TEST(JointErrors, HingeLimitOutsideAHalfTurn) {
  expectError(jointsWith(R"({"lower_rad": -0.5, "upper_rad": 1.0})",
                         R"({"lower_rad": -4, "upper_rad": 1.0})"),
              "/hinges/1/limit/lower_rad", "an angle in [-pi, pi] rad", "-4");
}

TEST(JointScene, AnAngleTargetMayBeManyTurns) {
  // Counted through whole turns (issue 28): 8 rad is past a whole turn.
  const Scene scene = parseScene(jointsWith(R"("target_rad": 0.25)", R"("target_rad": 8)"), "test.json");
  EXPECT_EQ(scene.world->hinge(1).drive.target, 8.0);
}

TEST(JointScene, ADriveScheduleLoads) {
  const Scene scene = parseScene(
      jointsWith(R"("target_rad": 0.25)", R"("schedule": [{"t_s": 0, "target_rad": 0}, {"t_s": 2, "target_rad": 8}])"),
      "test.json");
  const HingeDrive& d = scene.world->hinge(1).drive;
  ASSERT_EQ(d.schedule.size(), 2u);
  EXPECT_EQ(d.schedule[1].time, 2.0);
  EXPECT_EQ(d.schedule[1].target, 8.0);
  EXPECT_EQ(d.target, 0.0);  // the schedule's value at t = 0
}

TEST(JointErrors, DriveTargetAndSchedule) {
  expectError(jointsWith(R"("target_rad": 0.25)", R"("target_rad": 0.25, "schedule": [{"t_s": 0, "target_rad": 1}])"),
              "/hinges/1/drive", "exactly one of \"target_rad\" (a constant target) and \"schedule\"", "both");
}

TEST(JointErrors, DriveWithoutTarget) {
  expectError(jointsWith(R"("target_m_per_s": 0.5, )", ""), "/joints/0/drive",
              "exactly one of \"target_m_per_s\"", "neither");
}

TEST(JointErrors, DriveScheduleTimesGoBack) {
  expectError(jointsWith(R"("target_rad_per_s": 10)",
                         R"("schedule": [{"t_s": 0, "target_rad_per_s": 0}, {"t_s": 1, "target_rad_per_s": 5}, )"
                         R"({"t_s": 1, "target_rad_per_s": 6}])"),
              "/hinges/0/drive/schedule/2/t_s", "a time after the previous keyframe's 1 s", "1");
}

TEST(JointErrors, DriveScheduleKeyframeOfAnotherMode) {
  // A velocity drive's keyframe names target_rad_per_s: the schema says so.
  expectError(jointsWith(R"("target_rad_per_s": 10)", R"("schedule": [{"t_s": 0, "target_rad": 1}])"),
              "/hinges/0/drive/schedule/0/target_rad", "(allowed: t_s, target_rad_per_s)", "target_rad");
}

TEST(JointErrors, SwingLimitAboveAHalfTurn) {
  expectError(jointsWith(R"("swing_limit_rad": 0.7)", R"("swing_limit_rad": 3.5)"),
              "/joints/1/swing_limit_rad", "an angle in [0, pi] rad", "3.5");
}

TEST(JointErrors, NegativeMaxTorque) {
  expectError(jointsWith(R"("max_torque_N_m": 1.5)", R"("max_torque_N_m": -1.5)"),
              "/hinges/0/drive/max_torque_N_m", "a number > 0", "-1.5");
}

TEST(JointErrors, NegativeMaxForce) {
  expectError(jointsWith(R"("max_force_N": 30)", R"("max_force_N": -30)"),
              "/joints/0/drive/max_force_N", "a number > 0", "-30");
}

TEST(JointErrors, UnknownBody) {
  expectError(jointsWith(R"("body": "slider")", R"("body": "slidr")"), "/joints/0/body",
              "the name of a body (wheel, arm, slider, bob, weight)", "\"slidr\"");
}

TEST(JointErrors, UnknownOtherBody) {
  expectError(jointsWith(R"("other": "bob")", R"("other": "bobb")"), "/joints/2/other",
              "\"world\" or the name of a body (wheel, arm, slider, bob, weight)", "\"bobb\"");
}

TEST(JointErrors, JointToItself) {
  expectError(jointsWith(R"("other": "bob")", R"("other": "weight")"), "/joints/2/other",
              "a body other than the joint's body \"weight\"", "\"weight\"");
}

TEST(JointErrors, ZeroPrismaticAxis) {
  expectError(jointsWith(R"("axis": [2, 0, 0])", R"("axis": [0, 0, 0])"), "/joints/0/axis",
              "a non-zero prismatic axis", "[0,0,0]");
}

TEST(JointErrors, SphericalLimitsNeedAnAxis) {
  expectError(jointsWith(R"("axis": [0, -1, 0],)", ""), "/joints/1",
              "required property \"axis\"", "nothing");
}

TEST(JointErrors, PrismaticWithoutAxis) {
  expectError(jointsWith(R"("axis": [2, 0, 0],)", ""), "/joints/0",
              "required property \"axis\"", "nothing");
}

TEST(JointErrors, VelocityDriveWithAnAngleTarget) {
  expectError(jointsWith(R"("target_rad_per_s": 10,)", R"("target_rad": 1,)"),
              "/hinges/0/drive/target_rad",
              "no property \"target_rad\" (allowed: mode, target_rad_per_s, schedule, max_torque_N_m, until_s, damping_N_m_s_per_rad)",
              "\"target_rad\"");
}

TEST(JointErrors, UnknownDriveMode) {
  expectError(jointsWith(R"("mode": "angle")", R"("mode": "torque")"), "/hinges/1/drive/mode",
              R"(one of "velocity", "angle")", "\"torque\"");
}

TEST(JointErrors, SwingLimitOnAFixedJointIsUnknown) {
  expectError(jointsWith(R"("compliance": 1e-6)", R"("compliance": 1e-6, "swing_limit_rad": 1)"),
              "/joints/2/swing_limit_rad",
              "no property \"swing_limit_rad\" (allowed: type, body, other, anchor_m, compliance)",
              "\"swing_limit_rad\"");
}

}  // namespace
}  // namespace reeve::test_joint_scenes
