// `reeve bench peers`: Reeve's cable machines next to the same machines as
// MuJoCo spatial tendons (Debian's libmujoco-dev), in the same run.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "reeve/bench/bench.h"
#include "reeve/bench/timing.h"
#include "reeve/machines/closed_forms.h"
#include "reeve/machines/machines.h"

namespace reeve::bench {
namespace {

constexpr double kFrameHz = 60.0;
constexpr int kFrames = 60;         // 1 s
constexpr int kStepsPerFrame = 10;  // MuJoCo's steps: Reeve's default 10 substeps
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A machine of boxes hanging from one cable over K wheels on fixed axles,
// with the closed forms of its motion: the real machine's (turning wheels)
// and the one with massless wheels, which is MuJoCo's model of it (its
// tendons slide without friction over cylinders that never turn).
struct Case {
  std::string name;
  int K = 1;
  std::function<Scene()> make;
  BodyId heavy = 0;
  int cable = 0;
  double a_turning = 0, tension_turning = 0;  // heavy box's acceleration, light side's tension
  double a_fixed = 0, tension_fixed = 0;
};

std::vector<Case> cases() {
  std::vector<Case> all;
  const machines::AtwoodSpec atwood;
  const machines::Atwood machine = machines::atwood(atwood);
  const auto turning = machines::atwoodMotion(atwood.light_kg, atwood.heavy_kg, atwood.wheel_kg, atwood.gravity);
  const auto fixed = machines::atwoodMotion(atwood.light_kg, atwood.heavy_kg, 0.0, atwood.gravity);
  all.push_back({"atwood", 1, [atwood] { return machines::atwood(atwood).scene; }, machine.heavy, machine.cable,
                 turning.acceleration, turning.tension_light, fixed.acceleration, fixed.tension_light});
  for (const int K : {2, 8, 32}) {
    machines::ZigZagSpec spec;
    spec.wheels = K;
    const machines::ZigZag z = machines::zigzag(spec);
    const auto turning = machines::zigzagMotion(K, spec.light_kg, spec.heavy_kg, spec.wheel_kg, spec.gravity);
    const auto fixed = machines::zigzagMotion(K, spec.light_kg, spec.heavy_kg, 0.0, spec.gravity);
    all.push_back({"zigzag", K, [spec] { return machines::zigzag(spec).scene; }, z.heavy, z.cable,
                   turning.acceleration, turning.tensions[0], fixed.acceleration, fixed.tensions[0]});
  }
  return all;
}

// What a run reads: the heavy box's height and the light side's tension
// at the end of the second, and the most the cable ever stretched.
struct Observed {
  double heavy_y = kNaN, tension = kNaN, max_stretch = 0.0;
};

// A case's Reeve scene; the rope's stretch is its spans' lengths over
// their rest lengths.
class ReeveRope : public SceneRun {
 public:
  explicit ReeveRope(const Case& c, machines::Budget budget = {})
      : SceneRun([c, budget] {
          Scene s = c.make();
          s.world->settings().substeps = budget.substeps;
          s.world->settings().iterations = budget.iterations;
          return s;
        }),
        heavy_(c.heavy),
        cable_(c.cable) {}
  void observe(int frame) override {
    const CableSystem& cables = *scene().cables;
    double stretch = 0.0;
    for (int j = 0; j < static_cast<int>(cables.cables()[cable_].joints.size()); ++j)
      if (cables.jointEnabled(cable_, j)) stretch += cables.length(cable_, j) - cables.restLength(cable_, j);
    observed.max_stretch = frame == 0 ? stretch : std::max(observed.max_stretch, stretch);
    if (frame + 1 < kFrames) return;
    observed.heavy_y = scene().world->body(heavy_).x.y();
    observed.tension = cables.tension(cable_, 0);
  }
  Observed observed;

 private:
  BodyId heavy_;
  int cable_;
};

// "x y z", exactly (17 digits).
std::string xyz(const Vec3& v) {
  std::ostringstream s;
  s.precision(17);
  s << v.x() << ' ' << v.y() << ' ' << v.z();
  return s.str();
}

// The cable of `scene` as a MuJoCo model: each box tied to it a free body
// with a site at the tie point, each wheel a fixed cylinder the tendon
// wraps, its side picked by a sidesite beyond the wheel (above it where the
// cable runs clockwise, i.e. over the top as it travels +x as in these
// machines; below it otherwise). MuJoCo allows one wrap between two sites,
// so a site sits on each straight span between wheels; the wheels do not
// move, so it stays on the span and the rope runs straight through it.
// The tendon is limited to at most `length_m` (none when 0); contacts off.
std::string mjcf(const Scene& scene, int cable, double length_m) {
  const World& world = *scene.world;
  const Cable& c = scene.cables->cables()[cable];
  std::ostringstream xml, bodies, path;
  xml.precision(17);
  bodies.precision(17);
  xml << "<mujoco model=\"" << scene.name << "\">\n  <option timestep=\"" << 1.0 / (kFrameHz * kStepsPerFrame)
      << "\" gravity=\"" << xyz(world.settings().gravity) << "\"><flag contact=\"disable\"/></option>\n";
  for (std::size_t i = 0; i < c.links.size(); ++i) {
    const Link& link = c.links[i];
    const BodyState& body = world.body(link.body);
    const std::string name = world.bodyDef(link.body).name;
    if (link.type == LinkType::Attachment) {
      const Vec3 half = world.bodyDef(link.body).shape.half_extents;
      bodies << "    <body name=\"" << name << "\" pos=\"" << xyz(body.x) << "\"><joint type=\"free\"/>"
             << "<geom type=\"box\" size=\"" << xyz(half) << "\" mass=\"" << 1.0 / body.inv_mass << "\"/>"
             << "<site name=\"" << name << "_tie\" pos=\"" << xyz(link.point) << "\"/></body>\n";
      path << "      <site site=\"" << name << "_tie\"/>\n";
      continue;
    }
    const Shape& wheel = world.bodyDef(link.body).shape;
    const double r = wheel.radius, side = link.orientation < 0 ? 1.0 : -1.0;
    bodies << "    <geom name=\"" << name << "\" type=\"cylinder\" size=\"" << r << ' ' << wheel.half_length
           << "\" pos=\"" << xyz(body.x) << "\"/>\n    <site name=\"" << name << "_side\" pos=\""
           << xyz(body.x + Vec3(0.0, 2.0 * side * r, 0.0)) << "\"/>\n";
    path << "      <geom geom=\"" << name << "\" sidesite=\"" << name << "_side\"/>\n";
    const Link& next = c.links[i + 1];
    if (next.type == LinkType::Attachment) continue;
    // Equal wheels: a crossing span passes through the midpoint of the
    // centres, one on the same side runs parallel to them, r off.
    const Vec3 to = world.body(next.body).x, along = (to - body.x).normalized();
    const double next_side = next.orientation < 0 ? 1.0 : -1.0;
    const Vec3 at = 0.5 * (body.x + to) + (side == next_side ? side * r : 0.0) * Vec3(-along.y(), along.x(), 0.0);
    bodies << "    <site name=\"" << name << "_span\" pos=\"" << xyz(at) << "\"/>\n";
    path << "      <site site=\"" << name << "_span\"/>\n";
  }
  xml << "  <worldbody>\n" << bodies.str() << "  </worldbody>\n  <tendon>\n    <spatial name=\"rope\"";
  if (length_m > 0.0) xml << " limited=\"true\" range=\"0 " << length_m << "\"";
  xml << ">\n" << path.str() << "    </spatial>\n  </tendon>\n</mujoco>\n";
  return xml.str();
}

using ModelPtr = std::unique_ptr<mjModel, decltype(&mj_deleteModel)>;
using DataPtr = std::unique_ptr<mjData, decltype(&mj_deleteData)>;

ModelPtr load(const std::string& xml) {
  auto vfs = std::make_unique<mjVFS>();  // megabytes: not on the stack
  mj_defaultVFS(vfs.get());
  const char* file = "rope.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), file, static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("MuJoCo: cannot make its virtual file");
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), file)], xml.data(), xml.size());
  char error[1000] = "";
  ModelPtr model(mj_loadXML(file, vfs.get(), error, sizeof error), mj_deleteModel);
  mj_deleteVFS(vfs.get());
  if (!model) throw std::runtime_error(std::string("MuJoCo: ") + error + "\n" + xml);
  return model;
}

// A case as MuJoCo's model (mjcf()), each frame `steps` mj_steps.
class MujocoRope : public FrameRun {
 public:
  // The rope's length is what MuJoCo measures on the model without the
  // limit, so it starts taut; it must be Reeve's cable's, or a wrap went
  // round the wrong side.
  explicit MujocoRope(const Case& c, int steps = kStepsPerFrame) : steps_(steps) {
    const Scene scene = c.make();
    {
      const ModelPtr free = load(mjcf(scene, c.cable, 0.0));
      const DataPtr d(mj_makeData(free.get()), mj_deleteData);
      mj_forward(free.get(), d.get());
      length_ = d->ten_length[0];
    }
    const double reeve_length = scene.cables->totalLength(c.cable);
    if (std::abs(length_ - reeve_length) > 1e-9 * reeve_length)
      throw std::runtime_error("peers: MuJoCo's tendon is " + std::to_string(length_) + " m, Reeve's cable " +
                               std::to_string(reeve_length) + " m: a wrap is on the wrong side");
    model_ = load(mjcf(scene, c.cable, length_));
    model_->opt.timestep = 1.0 / (kFrameHz * steps);
    data_.reset(mj_makeData(model_.get()));
    const int heavy = mj_name2id(model_.get(), mjOBJ_BODY, scene.world->bodyDef(c.heavy).name.c_str());
    heavy_y_ = model_->jnt_qposadr[model_->body_jntadr[heavy]] + 1;
  }
  void reset() override { mj_resetData(model_.get(), data_.get()); }
  void step() override {
    for (int i = 0; i < steps_; ++i) mj_step(model_.get(), data_.get());
  }
  // ten_length and efc_force are those of the last mj_step's start, 1/600 s
  // before qpos: read as they are, so observing changes nothing.
  void observe(int frame) override {
    const mjData* d = data_.get();
    const double stretch = d->ten_length[0] - length_;
    observed.max_stretch = frame == 0 ? stretch : std::max(observed.max_stretch, stretch);
    if (frame + 1 < kFrames) return;
    for (int w = 0; w < mjNWARNING; ++w)
      if (d->warning[w].number > 0)
        throw std::runtime_error(std::string("MuJoCo: ") + mju_warningText(w, d->warning[w].lastinfo));
    observed.heavy_y = d->qpos[heavy_y_];
    observed.tension = 0.0;  // no limit row: the tendon is slack
    for (int i = 0; i < d->nefc; ++i)
      if (d->efc_type[i] == mjCNSTR_LIMIT_TENDON && d->efc_id[i] == 0) observed.tension = d->efc_force[i];
  }
  int wraps() const {
    int n = 0;
    for (int i = 0; i < model_->tendon_num[0]; ++i)
      n += model_->wrap_type[model_->tendon_adr[0] + i] == mjWRAP_CYLINDER;
    return n;
  }
  Observed observed;

 private:
  int steps_;
  ModelPtr model_{nullptr, mj_deleteModel};
  DataPtr data_{nullptr, mj_deleteData};
  double length_ = 0.0;
  int heavy_y_ = 0;
};

// (x - expected) / expected.
double relative(double x, double expected) { return (x - expected) / expected; }

// Within 1 % of the closed form of the engine's own model, in the heavy
// box's acceleration over the second (from its fall) and the light side's
// tension at its end: `run` stepped once, untimed, and observed.
template <class Run>
bool withinOnePercent(Run& run, double y0, double a_own, double tension_own) {
  run.reset();
  for (int f = 0; f < kFrames; ++f) {
    run.step();
    run.observe(f);
  }
  const double T = kFrames / kFrameHz;
  const double a = 2.0 * (y0 - run.observed.heavy_y) / (T * T);
  return std::abs(relative(a, a_own)) <= 0.01 && std::abs(relative(run.observed.tension, tension_own)) <= 0.01;
}

// Steps a frame tried for the cheapest setting within 1 %, cheapest first:
// Reeve's substeps x iterations (the direct solver), MuJoCo's mj_steps. A
// frame of h = 1 / 60 s is 1.7 % off by itself (the 1 + h / (1 s) of
// semi-implicit Euler), so neither passes at one step.
const machines::Budget kReeveBudgets[] = {{1, 1}, {2, 1}, {2, 2}, {3, 1}, {5, 1}, {5, 2}, {10, 2}, {20, 2}};
const int kMujocoSteps[] = {1, 2, 3, 5, 10, 20, 50};

// The cheapest setting within 1 % of each engine on `c`, timed: a row of
// the equal-accuracy table, and the cost ratio Reeve / MuJoCo.
void equalAccuracy(const Case& c, double y0, const TimingOptions& timing, Table& table) {
  std::string reeve_setting = "none", mujoco_setting = "none";
  double reeve_ms = kNaN, mujoco_ms = kNaN;
  std::optional<ReeveRope> reeve;
  std::optional<MujocoRope> mujoco;
  for (const machines::Budget& b : kReeveBudgets) {
    reeve.emplace(c, b);
    if (!withinOnePercent(*reeve, y0, c.a_turning, c.tension_turning)) continue;
    reeve_setting = std::to_string(b.substeps) + " x " + std::to_string(b.iterations);
    break;
  }
  for (const int steps : kMujocoSteps) {
    mujoco.emplace(c, steps);
    if (!withinOnePercent(*mujoco, y0, c.a_fixed, c.tension_fixed)) continue;
    mujoco_setting = std::to_string(steps) + " steps";
    break;
  }
  // Timed in turn: the ratio is of the same stretch of the machine's time.
  if (reeve_setting != "none" && mujoco_setting != "none") {
    const auto [r, m] = timeFramesInTurn(*reeve, *mujoco, kFrames, timing);
    reeve_ms = r.median_ms;
    mujoco_ms = m.median_ms;
  } else if (reeve_setting != "none") {
    reeve_ms = timeFrames(*reeve, kFrames, timing).median_ms;
  } else if (mujoco_setting != "none") {
    mujoco_ms = timeFrames(*mujoco, kFrames, timing).median_ms;
  }
  table.add({c.name, std::to_string(c.K), reeve_setting, number(reeve_ms, 3), mujoco_setting, number(mujoco_ms, 3),
             number(reeve_ms / mujoco_ms, 3)});
}

}  // namespace

bool peersAvailable() { return true; }

int peers(const PeersOptions& options) {
  if (!options.output.plot.empty()) throw std::invalid_argument("peers has no plot: drop --plot");
  checkOutput(options.output);
  const Environment env = environment();
  printEnvironment(stdout, env);
  std::printf(
      "# %d frames at %g Hz (1 s). Reeve: %d substeps x %d iterations, direct solver. MuJoCo %s: timestep\n"
      "# 1/%g s (%d steps per frame), default solver and soft constraints otherwise. Boxes are free bodies in\n"
      "# both; MuJoCo's rope is a spatial tendon wrapping fixed cylinders, as long as Reeve's cable (checked),\n"
      "# its length limited from above (one-sided, like a cable).\n"
      "# accel_error: the heavy box's a = 2 (y0 - y(1 s)) / (1 s)^2 against the closed form of the engine's\n"
      "# own model (MuJoCo's: massless wheels); vs_turning_wheels: against the real machine's. Both engines\n"
      "# step with semi-implicit Euler, which carries a box at constant a 1 + h / (1 s) = 1.0017 times as far\n"
      "# in 1 s: +0.0017 is exact stepping at h = 1/600 s. tension_error: the light side's tension at 1 s\n"
      "# against its own model's. joints: Reeve's cable joints, MuJoCo's tendon wraps. max_stretch_mm: the\n"
      "# rope's length over its rest length, at most. ms/frame: min / median / max over %d runs.\n",
      kFrames, kFrameHz, machines::Budget{}.substeps, machines::Budget{}.iterations, mj_versionString(),
      kFrameHz * kStepsPerFrame, kStepsPerFrame, options.repeats);
  Table table({"engine", "case", "K", "joints", "min_ms", "median_ms", "max_ms", "accel_error",
               "accel_error_vs_turning_wheels", "tension_error", "max_stretch_mm"});
  Table equal({"case", "K", "reeve_setting", "reeve_ms", "mujoco_setting", "mujoco_ms", "cost_ratio"});
  TimingOptions timing;
  timing.repeats = options.repeats;
  const double T = kFrames / kFrameHz;
  for (const Case& c : cases()) {
    const double y0 = c.make().world->body(c.heavy).x.y();
    const auto add = [&](const char* engine, int joints, const FrameTiming& t, const Observed& o, double a_own,
                         double tension_own) {
      const double a = 2.0 * (y0 - o.heavy_y) / (T * T);
      table.add({engine, c.name, std::to_string(c.K), std::to_string(joints), number(t.min_ms, 3),
                 number(t.median_ms, 3), number(t.max_ms, 3), number(relative(a, a_own), 3),
                 number(relative(a, c.a_turning), 3), number(relative(o.tension, tension_own), 3),
                 number(1e3 * o.max_stretch, 3)});
    };
    ReeveRope reeve(c);
    const FrameTiming reeve_timing = timeFrames(reeve, kFrames, timing);
    const int joints = static_cast<int>(reeve.scene().cables->cables()[c.cable].joints.size());
    add("reeve", joints, reeve_timing, reeve.observed, c.a_turning, c.tension_turning);
    MujocoRope mujoco(c);
    const FrameTiming mujoco_timing = timeFrames(mujoco, kFrames, timing);
    add("mujoco", mujoco.wraps(), mujoco_timing, mujoco.observed, c.a_fixed, c.tension_fixed);
    equalAccuracy(c, y0, timing, equal);
  }
  std::printf(
      "MuJoCo's tendon wraps are frictionless and its pulleys never turn; Reeve's wheels turn with the cable.\n");
  table.print(stdout);
  std::printf(
      "\n# Equal accuracy: each engine at its cheapest setting within 1 %% of its own model's closed form\n"
      "# (acceleration and tension; Reeve's with turning wheels, MuJoCo's massless), ms/frame median of %d;\n"
      "# cost_ratio: Reeve's time over MuJoCo's (below 1: Reeve is cheaper).\n",
      options.repeats);
  equal.print(stdout);
  writeOutputs(options.output, table, env, "peers");
  return 0;
}

}  // namespace reeve::bench
