// The test models stepped by MuJoCo itself (Debian's libmujoco-dev) and by
// Reeve after import, at MuJoCo's timestep: the same statics to 1e-4, the
// same motion to 1e-3 (MuJoCo's constraints are soft, Reeve's rigid; both
// step with semi-implicit Euler). Built only where MuJoCo is installed.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <utility>
#include <vector>

#include "mjcf_fixture.h"
#include "reeve/engine/fp_exceptions.h"

namespace reeve::test {
namespace {

struct MuJoCo {
  mjModel* model = nullptr;
  mjData* data = nullptr;
  explicit MuJoCo(const std::string& path) {
    const FloatingPointExceptionsMasked theirs;  // MuJoCo's own arithmetic is not under test
    char error[1000] = "";
    model = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
    if (!model) throw std::runtime_error(path + ": " + error);
    data = mj_makeData(model);
  }
  ~MuJoCo() {
    mj_deleteData(data);
    mj_deleteModel(model);
  }
  void step(int n) {
    const FloatingPointExceptionsMasked theirs;
    for (int i = 0; i < n; ++i) mj_step(model, data);
  }
  // A free body's height (m, world) as its joint has it now (xipos is the
  // pose the last step started from).
  double freeHeight(const char* name) const {
    const int id = mj_name2id(model, mjOBJ_BODY, name);
    return data->qpos[model->jnt_qposadr[model->body_jntadr[id]] + 2];
  }
  // A slide joint's position (m).
  double slide(const char* joint) const {
    return data->qpos[model->jnt_qposadr[mj_name2id(model, mjOBJ_JOINT, joint)]];
  }
  // The force (N) the tendon's limit pulls with.
  double tendonLimitForce(int tendon) const {
    double f = 0.0;
    for (int i = 0; i < data->nefc; ++i)
      if (data->efc_type[i] == mjCNSTR_LIMIT_TENDON && data->efc_id[i] == tendon) f += data->efc_force[i];
    return f;
  }
};

// Steps Reeve frame by frame: its substep is MuJoCo's timestep.
void stepReeve(Scene& s, int frames) {
  for (int f = 0; f < frames; ++f) s.world->step(1.0 / s.frame_rate_hz);
}

// MuJoCo's limit is soft (it takes 0.9 of the tension in its first step),
// Reeve's rigid; over 0.48 s the drops agree to 1e-3 and the tensions at
// the end to 1e-4, over a cylinder and over a sphere. MuJoCo 2.2.2's
// sphere wrap turns NaN within 8 ms where the ropes leave the sphere
// exactly vertical (models/atwood_sphere.xml, whose closed form Reeve
// meets): both boxes hang 1 mm further in here.
TEST(MjcfVsMuJoCo, AtwoodFallsAsMuJoCoLetsIt) {
  for (const char* name : {"atwood", "atwood_sphere"}) {
    std::string path = mjcfModel(name);
    if (std::string(name) == "atwood_sphere") {
      std::ifstream in(path);
      std::string xml((std::istreambuf_iterator<char>(in)), {});
      for (const auto& [from, to] : {std::pair{"pos=\"-0.1 0 1\"", "pos=\"-0.099 0 1\""}, {"pos=\"0.1 0 1\"", "pos=\"0.099 0 1\""}})
        xml.replace(xml.find(from), std::string(from).size(), to);
      path = writeModel("atwood_sphere_inside", xml).string();
    }
    MuJoCo mj(path);
    Scene s = parseScene(importMjcf(path).scene_json, path);
    const int substeps = s.world->settings().substeps;
    ASSERT_NEAR(1.0 / (s.frame_rate_hz * substeps), mj.model->opt.timestep, 1e-15);
    const int frames = 30;
    mj.step(frames * substeps);
    stepReeve(s, frames);
    const double drop_mj = 1.0 - mj.freeHeight("heavy"), drop = 1.0 - s.world->body(bodyNamed(s, "heavy")).x.z();
    EXPECT_GT(drop, 0.3);
    EXPECT_NEAR(drop, drop_mj, 1e-3 * drop) << name << ": MuJoCo " << drop_mj << " m, Reeve " << drop << " m";
    const double T_mj = mj.tendonLimitForce(0), T = s.cables->tension(0, 0);
    EXPECT_NEAR(T, T_mj, 1e-4 * T) << "MuJoCo " << T_mj << " N, Reeve " << T << " N";
  }
}

// Statics: the lever on its tendon over the joint cylinder, the rod on a
// ball joint hung from its tendon, the two-link arm on its two tendons;
// after 2 s (MuJoCo's soft limits settle) the tendons pull alike to 1e-4.
TEST(MjcfVsMuJoCo, TendonsHoldWithMuJoCosTension) {
  for (const char* name : {"lever", "ball", "arm"}) {
    MuJoCo mj(mjcfModel(name));
    Scene s = importedScene(name);
    const int substeps = s.world->settings().substeps;
    const int frames = 120;
    mj.step(frames * substeps);
    stepReeve(s, frames);
    for (int t = 0; t < mj.model->ntendon; ++t) {
      const double T_mj = mj.tendonLimitForce(t), T = s.cables->tension(t, 0);
      EXPECT_NEAR(T, T_mj, 1e-4 * T_mj) << name << " tendon " << t << ": MuJoCo " << T_mj << " N, Reeve " << T << " N";
    }
  }
}

// models/pulley.xml: MuJoCo's three pulley branches, Reeve's junction of
// three cables. With a 4 kg counterweight (T = 26.16 N) it sinks 1.5 m in
// 0.96 s, the loads rising as far: within 1e-3 of MuJoCo's, whose soft
// limit lets the tendon stretch (its counterweight sinks 0.3 mm further
// than its loads rise); the lift branch's pull within 1e-4 (MuJoCo's
// limit force is the tendon's T). Balanced (2 kg against two 1 kg loads)
// after 2 s: the pull within 1e-4, and MuJoCo's soft limit sags 0.28 mm
// where Reeve's cable holds.
TEST(MjcfVsMuJoCo, PulleyBranchesMoveAsInMuJoCo) {
  std::ifstream in(mjcfModel("pulley"));
  const std::string xml((std::istreambuf_iterator<char>(in)), {});
  for (const std::string mass : {"4", "2"}) {
    std::string model = xml;
    const std::string from = "mass=\"2.2\"";
    model.replace(model.find(from), from.size(), "mass=\"" + mass + "\"");
    const std::string path = writeModel("pulley_vs", model).string();
    MuJoCo mj(path);
    Scene s = parseScene(importMjcf(path).scene_json, path);
    const int substeps = s.world->settings().substeps;
    const bool moving = mass == "4";
    const int frames = moving ? 60 : 120;
    mj.step(frames * substeps);
    stepReeve(s, frames);
    const double T_mj = mj.tendonLimitForce(0), T = s.cables->tension(0, 0);
    EXPECT_NEAR(T, T_mj, 1e-4 * T) << mass << " kg: MuJoCo " << T_mj << " N, Reeve " << T << " N";
    const double sink_mj = -mj.slide("counterweight_slide"), sink = -s.world->body(bodyNamed(s, "counterweight")).x.z();
    const double rise_mj = mj.slide("left_slide"), rise = s.world->body(bodyNamed(s, "load_left")).x.z() + 1.0;
    if (moving) {
      EXPECT_GT(sink, 1.0);
      EXPECT_NEAR(sink, sink_mj, 1e-3 * sink) << "MuJoCo " << sink_mj << " m, Reeve " << sink << " m";
      EXPECT_NEAR(rise, rise_mj, 1e-3 * rise) << "MuJoCo " << rise_mj << " m, Reeve " << rise << " m";
    } else {
      EXPECT_NEAR(sink, 0.0, 1e-12);
      EXPECT_NEAR(sink_mj, 0.0, 5e-4) << "MuJoCo's soft limit's sag";
    }
  }
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

// models/gimbal.xml: the bob on its universal joint swings as in MuJoCo,
// generalized coordinates there, bodies and joint rows here. With the
// start projection (SHAKE, which keeps a swing's energy) its pitch after
// 0.96 s, near the end of a swing, is within 1e-3 of its 0.3 rad
// amplitude of MuJoCo's; the default end projection loses (w h)^2 of the
// swing's energy a substep (README, "projection"): 1.9 % in these 480, so
// it lags by 0.9 % of the amplitude. The box on its two slides falls alike.
TEST(MjcfVsMuJoCo, GimbalSwingsAsInMuJoCo) {
  const double w = std::sqrt(9.81 / 1.0);
  for (const Projection projection : {Projection::Start, Projection::End}) {
    MuJoCo mj(mjcfModel("gimbal"));
    Scene s = importedScene("gimbal");
    s.world->settings().projection = projection;
    const int substeps = s.world->settings().substeps, frames = 60;
    mj.step(frames * substeps);
    stepReeve(s, frames);
    const double pitch_mj = 0.3 + mj.data->qpos[mj.model->jnt_qposadr[mj_name2id(mj.model, mjOBJ_JOINT, "pitch")]];
    const Vec3 bob = s.world->body(bodyNamed(s, "bob")).x;
    const double pitch = std::atan2(bob.y(), -bob.z());
    const double h = mj.model->opt.timestep, lost = 0.5 * w * w * h * h * frames * substeps;  // of the amplitude
    EXPECT_NEAR(pitch, pitch_mj, projection == Projection::Start ? 1e-3 * 0.3 : (lost + 1e-3) * 0.3)
        << "MuJoCo " << pitch_mj << " rad, Reeve " << pitch << " rad";
    const double down_mj = mj.data->qpos[mj.model->jnt_qposadr[mj_name2id(mj.model, mjOBJ_JOINT, "down")]];
    EXPECT_NEAR(s.world->body(bodyNamed(s, "box")).x.z(), down_mj, 1e-3 * std::abs(down_mj));
  }
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

// MuJoCo 2.2.2's mass of a mesh geom of 1000 kg/m^3 whose principal
// moments per kilogram are `per_kg`: that of the box with those moments,
// of sides sqrt(6 (I_j + I_k - I_i)) (the import weighs the mesh's solid).
double boxMass(const Vec3& per_kg) {
  const Vec3 sides(std::sqrt(6.0 * (per_kg[1] + per_kg[2] - per_kg[0])), std::sqrt(6.0 * (per_kg[0] + per_kg[2] - per_kg[1])),
                   std::sqrt(6.0 * (per_kg[0] + per_kg[1] - per_kg[2])));
  return 1000.0 * sides.prod();
}

// Mass properties against MuJoCo's own compiler (mj_loadXML's body_mass,
// body_inertia, xipos) on the test models and Debian's sample models: each
// jointed body that nothing is welded to and whose joints have no armature
// (the importer adds it to the body; MuJoCo keeps it in joint space) has
// the same mass, centre of mass and principal moments, to 1e-9. Meshes
// (models/meshes.xml): to 1e-6, as MuJoCo keeps their vertices in single
// precision, and their moments per kilogram: MuJoCo 2.2.2 weighs a mesh
// geom as the box of its principal moments (density x that box's volume:
// the corner tetrahedron at 1.394 times its volume; the cube is its box),
// where the import weighs the solid, as later MuJoCo does.
TEST(MjcfVsMuJoCo, MassPropertiesAreMuJoCosCompilers) {
  std::vector<std::string> models;
  for (const char* name : {"atwood", "lever", "ball", "gimbal", "actuators", "meshes", "arm"}) models.push_back(mjcfModel(name));
  for (const char* sample : {"tendon_arm/arm26.xml", "humanoid/humanoid.xml", "slider_crank/slider_crank.xml"})
    if (const std::string path = std::string("/usr/share/mujoco/model/") + sample; std::filesystem::exists(path))
      models.push_back(path);
  int compared = 0;
  for (const std::string& path : models) {
    MuJoCo mj(path);
    {
      const FloatingPointExceptionsMasked theirs;
      mj_forward(mj.model, mj.data);
    }
    Scene s = parseScene(importMjcf(path).scene_json, path);
    const mjModel* m = mj.model;
    for (int b = 1; b < m->nbody; ++b) {
      const char* name = mj_id2name(m, mjOBJ_BODY, b);
      if (!name || m->body_jntnum[b] == 0) continue;
      bool welded_to = false, armature = false;
      for (int c = 1; c < m->nbody; ++c) welded_to |= c != b && m->body_weldid[c] == b;
      for (int j = m->body_jntadr[b]; j < m->body_jntadr[b] + m->body_jntnum[b]; ++j)
        armature |= m->dof_armature[m->jnt_dofadr[j]] > 0.0;
      const auto id = s.world->findBody(name);
      if (welded_to || armature || !id) continue;
      const BodyState& body = s.world->body(*id);
      const bool mesh = path.find("meshes") != std::string::npos;
      const double tol = mesh ? 1e-6 : 1e-9, mass = 1.0 / body.inv_mass;
      Vec3 ours = body.inertia.diagonal(), theirs(m->body_inertia[3 * b], m->body_inertia[3 * b + 1], m->body_inertia[3 * b + 2]);
      std::sort(ours.data(), ours.data() + 3);
      std::sort(theirs.data(), theirs.data() + 3);
      if (mesh) {  // per kilogram, and MuJoCo 2.2.2's mass the box's
        ours /= mass;
        theirs /= m->body_mass[b];
        EXPECT_NEAR(boxMass(ours), m->body_mass[b], tol * m->body_mass[b]) << path << ": " << name;
      } else {
        EXPECT_NEAR(mass, m->body_mass[b], tol * m->body_mass[b]) << path << ": " << name;
      }
      const Vec3 com(mj.data->xipos[3 * b], mj.data->xipos[3 * b + 1], mj.data->xipos[3 * b + 2]);
      EXPECT_LT((body.x - com).norm(), tol) << path << ": " << name;
      EXPECT_LT((ours - theirs).norm(), tol * theirs.norm()) << path << ": " << name << ": " << ours.transpose()
                                                                << " vs " << theirs.transpose();
      ++compared;
    }
  }
  EXPECT_GE(compared, 10);
}

// Debian's mug.xml: a mesh of 12,676 vertices (mug.obj, scaled to cm; not
// closed: 800 edges have one triangle), alone on its body here (the boxes
// about it and the welded handle taken out). MuJoCo's default compiler
// counts each triangle's pyramid from the centre as positive, and so does
// the import: the centre of mass and the moments per kilogram agree to
// 1e-6, and MuJoCo 2.2.2's mass is that of the moments' box (above).
TEST(MjcfVsMuJoCo, TheMugsOpenMeshIsCentredAndShapedAsInMuJoCo) {
  const std::string dir = "/usr/share/mujoco/model/mug/";
  if (!std::filesystem::exists(dir + "mug.xml")) GTEST_SKIP() << "libmujoco-samples is not installed";
  const auto path = writeModel("mug_mesh", R"(<mujoco>
  <compiler meshdir=")" + dir + R"("/>
  <asset><mesh file="mug.obj" scale=".01 .01 .01"/></asset>
  <worldbody><body name="mug"><freejoint/><geom type="mesh" mesh="mug" euler="90 0 0"/></body></worldbody>
</mujoco>)").string();
  MuJoCo mj(path);
  {
    const FloatingPointExceptionsMasked theirs;
    mj_forward(mj.model, mj.data);
  }
  Scene s = parseScene(importMjcf(path).scene_json, path);
  const mjModel* m = mj.model;
  const int b = mj_name2id(m, mjOBJ_BODY, "mug");
  const BodyState& mug = s.world->body(bodyNamed(s, "mug"));
  const Vec3 com(mj.data->xipos[3 * b], mj.data->xipos[3 * b + 1], mj.data->xipos[3 * b + 2]);
  EXPECT_LT((mug.x - com).norm(), 1e-6 * 0.05) << mug.x.transpose() << " vs " << com.transpose();
  Vec3 ours = mug.inertia.diagonal() * mug.inv_mass, theirs(m->body_inertia[3 * b], m->body_inertia[3 * b + 1], m->body_inertia[3 * b + 2]);
  theirs /= m->body_mass[b];
  std::sort(ours.data(), ours.data() + 3);
  std::sort(theirs.data(), theirs.data() + 3);
  EXPECT_LT((ours - theirs).norm(), 1e-6 * theirs.norm()) << ours.transpose() << " vs " << theirs.transpose();
  EXPECT_NEAR(boxMass(ours), m->body_mass[b], 1e-6 * m->body_mass[b]);
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

// Debian's arm26.xml (libmujoco-samples): two links on hinges in the
// horizontal plane, six muscles on spatial tendons over the joints'
// cylinders. It imports and runs; its muscles and their tendons (which
// pull on nothing else) are listed, one line each. At rest (controls 0)
// the difference from MuJoCo is the muscles' passive force: MuJoCo's pull
// on their own (SF 1.7 N, BF 0.6 N after 1 s) and turn both joints 0.19
// and 0.34 rad in 1 s; Reeve's arm, without them, stays where it is
// (gravity lies along its axles).
TEST(MjcfVsMuJoCo, Arm26ImportsAndRestsWhereMuJoCosMusclesPullItOnTheirOwn) {
  const std::string path = "/usr/share/mujoco/model/tendon_arm/arm26.xml";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "libmujoco-samples is not installed";
  MjcfImport model = importMjcf(path);
  const auto listed = [&](const std::string& what) {
    return std::count_if(model.unmapped.begin(), model.unmapped.end(),
                         [&](const std::string& u) { return u.find(what) != std::string::npos; });
  };
  EXPECT_EQ(listed("<muscle name="), 6);
  EXPECT_EQ(listed("<spatial name="), 6);
  Scene s = parseScene(model.scene_json, path);
  MuJoCo mj(path);
  const int frames = static_cast<int>(std::lround(s.frame_rate_hz));  // 1 s
  mj.step(frames * s.world->settings().substeps);
  stepReeve(s, frames);
  EXPECT_GT(mj.data->qpos[0], 0.1);
  EXPECT_GT(mj.data->qpos[1], 0.1);
  for (const HingeJoint& h : s.world->hinges()) {
    const BodyState& b = s.world->body(h.a);
    EXPECT_LT(b.omega.norm(), 1e-12);
  }
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

// arm26.xml driven, each muscle's control at 1 in turn: a muscle becomes a
// winch pulling with its control times MuJoCo's peak force F0 = scale /
// acc0 (acc0: the joint accelerations a unit tendon force gives at load,
// which the import measures on the scene it built), equal to MuJoCo's own
// (200 / actuator_acc0) to 1e-6. BF's muscle (over both joints) replaced
// in MuJoCo by a motor of that constant force (and the others by motors at
// 0, which a muscle at 0 is not: it pulls by its passive force): after
// 0.2 s at MuJoCo's 5 ms step the elbow at 1.7500 rad against MuJoCo's
// 1.7723, the shoulder at 0.10099 against 0.09848, within 3 %. The
// difference is MuJoCo's soft joint limits: both joints start on their
// lower limits, the pull presses the shoulder into its own, and MuJoCo's
// limit holds at most its impedance (0.9 to 0.95) of what it should
// (0.5 mrad in, within 17 ms). With the limits made near rigid
// (solreflimit 1 ms, solimplimit 0.9999) and a 0.5 ms step, both engines
// agree within 2e-3 (elbow 1.77678 in MuJoCo, 1.77437 here; shoulder
// 0.10675, 0.10695). Against MuJoCo's
// muscle itself Reeve's arm is far ahead: MuJoCo's builds its activation
// over ~10 ms and pulls with F0 x FL(length) x FV(speed), 55 N of 213 N
// after 0.2 s, its elbow shortening it fast.
TEST(MjcfVsMuJoCo, Arm26sMusclesPullWithMuJoCosPeakForce) {
  const std::string path = "/usr/share/mujoco/model/tendon_arm/arm26.xml";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "libmujoco-samples is not installed";
  MuJoCo mj(path);
  double f0_bf = 0.0;
  for (int i = 0; i < mj.model->nu; ++i) {
    const std::string name = mj_id2name(mj.model, mjOBJ_ACTUATOR, i);
    MjcfOptions options;
    options.controls[name] = 1.0;
    Scene s = parseScene(importMjcf(path, options).scene_json, path);
    ASSERT_EQ(s.cables->cables().size(), 1u) << name;
    const double f0 = 200.0 / mj.model->actuator_acc0[i];
    EXPECT_NEAR(s.cables->cables()[0].winch->max_pull, f0, 1e-6 * f0) << name;
    if (name == "BF") f0_bf = f0;
  }
  std::ifstream in(path);
  const std::string arm26((std::istreambuf_iterator<char>(in)), {});
  const auto edited = [&](const std::vector<std::pair<std::string, std::string>>& edits) {
    std::string xml = arm26;
    for (const auto& [from, to] : edits) xml.replace(xml.find(from), from.size(), to);
    return xml;
  };
  // In MuJoCo every muscle a motor (at control 0 a muscle still pulls by
  // its passive force), BF's of constant force F0; Reeve's import of the
  // muscles, BF's at control 1.
  char gear[32];
  std::snprintf(gear, sizeof gear, "%.17g", -f0_bf);
  std::vector<std::pair<std::string, std::string>> to_motors;
  for (const char* m : {"SF", "SE", "EF", "EE", "BF", "BE"})
    to_motors.push_back({"<muscle name=\"" + std::string(m) + "\" tendon=\"" + m + "\"/>",
                         "<motor name=\"" + std::string(m) + "\" tendon=\"" + m + "\" gear=\"" +
                             (std::string(m) == "BF" ? std::string(gear) : std::string("-1")) + "\"/>"});
  const std::pair<std::string, std::string> fine{"timestep=\"0.005\"", "timestep=\"0.0005\""};
  const std::pair<std::string, std::string> rigid{
      "damping=\"0.1\"", "damping=\"0.1\" solreflimit=\"0.001 1\" solimplimit=\"0.9999 0.9999 0.001\""};
  struct Case {
    std::string name;
    std::vector<std::pair<std::string, std::string>> muscle, motor;
    double tolerance;
  };
  std::vector<std::pair<std::string, std::string>> stiff_motors = to_motors;
  stiff_motors.push_back(fine);
  stiff_motors.push_back(rigid);
  for (const Case& c : {Case{"at MuJoCo's step, its soft limits", {}, to_motors, 0.03},
                        Case{"at 0.5 ms, limits near rigid", {fine}, stiff_motors, 2e-3}}) {
    SCOPED_TRACE(c.name);
    const std::string muscle_path = writeModel("arm26_muscle", edited(c.muscle)).string();
    MuJoCo motor(writeModel("arm26_motor", edited(c.motor)).string());
    MjcfOptions options;
    options.controls["BF"] = 1.0;
    Scene s = parseScene(importMjcf(muscle_path, options).scene_json, muscle_path);
    const int frames = static_cast<int>(std::lround(0.2 * s.frame_rate_hz));
    const int steps = frames * s.world->settings().substeps;
    motor.data->ctrl[mj_name2id(motor.model, mjOBJ_ACTUATOR, "BF")] = 1.0;
    motor.step(steps);
    stepReeve(s, frames);
    const double shoulder = s.world->hingeAngle(0), elbow = s.world->hingeAngle(1);
    EXPECT_GT(shoulder, 0.05);
    EXPECT_GT(elbow, 1.0);
    EXPECT_NEAR(shoulder, motor.data->qpos[0], c.tolerance * shoulder) << "MuJoCo " << motor.data->qpos[0] << " rad";
    EXPECT_NEAR(elbow, motor.data->qpos[1], c.tolerance * elbow) << "MuJoCo " << motor.data->qpos[1] << " rad";
    EXPECT_FALSE(s.cables->firstBreach());
    if (c.muscle.empty()) {  // MuJoCo's muscle itself, at its own step
      MuJoCo muscle(path);
      const int bf = mj_name2id(muscle.model, mjOBJ_ACTUATOR, "BF");
      muscle.data->ctrl[bf] = 1.0;
      muscle.step(steps);
      EXPECT_LT(muscle.data->qpos[0], shoulder) << "MuJoCo's muscle";
      EXPECT_LT(muscle.data->qpos[1], elbow) << "MuJoCo's muscle";
      EXPECT_LT(-muscle.data->actuator_force[bf], 0.5 * f0_bf) << "MuJoCo's muscle, shortening fast";
    }
  }
}

}  // namespace
}  // namespace reeve::test
