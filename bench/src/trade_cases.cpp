#include "trade_cases.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "reeve/machines/closed_forms.h"
#include "reeve/machines/machines.h"
#include "reeve/machines/segment_scene.h"

namespace reeve::bench {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

constexpr double kFrame = 1.0 / 60.0;

double relative(double got, double want) { return std::abs(got - want) / std::abs(want); }

Json readJson(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot read");
  std::stringstream text;
  text << in.rdbuf();
  return Json::parse(text.str());
}

Json& bodyNamed(Json& scene, const std::string& name) {
  for (Json& b : scene["bodies"])
    if (b["name"] == name) return b;
  throw std::runtime_error("scene has no body '" + name + "'");
}

BodyId find(const Scene& s, const std::string& name) {
  if (const auto id = s.world->findBody(name)) return *id;
  throw std::runtime_error(s.name + ": no body '" + name + "'");
}

// scenes/atwood.json (g = 9.81, wheel of radius 0.3 m on a fixed axle)
// with boxes of m1 < m2 and a wheel of M kg; 0.5 s, the heavy box falling
// y(T) = a T^2 / 2 with (m1 + m2 + M/2) a = (m2 - m1) g.
class AtwoodCase : public ClosedFormCase {
 public:
  AtwoodCase(std::string name, const fs::path& dir, double m1, double m2, double M)
      : name_(std::move(name)), m1_(m1), m2_(m2), M_(M), json_(readJson(dir / "atwood.json")) {
    bodyNamed(json_, "light")["mass_kg"] = m1;
    bodyNamed(json_, "heavy")["mass_kg"] = m2;
    bodyNamed(json_, "wheel")["mass_kg"] = M;
    text_ = json_.dump();
  }
  std::string name() const override { return name_; }
  std::string description() const override {
    return "Atwood " + num(m1_) + ":" + num(m2_) + " kg over a " + num(M_) +
           " kg wheel: the heavy box's fall and both tensions at 0.5 s";
  }
  int frames() const override { return 30; }
  Scene make() const override { return parseScene(text_, name_); }
  void start(const Scene& s) override { y0_ = s.world->body(find(s, "heavy")).x.y(); }
  Errors errors(const Scene& s) const override {
    const machines::AtwoodMotion want = machines::atwoodMotion(m1_, m2_, M_, kG);
    const double T = frames() * kFrame;
    const double fall = y0_ - s.world->body(find(s, "heavy")).x.y();
    return {{{"acceleration", relative(2.0 * fall / (T * T), want.acceleration)},
             {"tension_light", relative(s.cables->tension(0, 0), want.tension_light)},
             {"tension_heavy", relative(s.cables->tension(0, 1), want.tension_heavy)}}};
  }
  const Json& json() const { return json_; }
  double m1() const { return m1_; }
  double m2() const { return m2_; }
  double M() const { return M_; }
  static constexpr double kG = 9.81, kRadius = 0.3;

 private:
  static std::string num(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  }
  std::string name_;
  double m1_, m2_, M_;
  Json json_;
  std::string text_;
  double y0_ = 0.0;
};

// The same machine with its cable as N rigid cylinders of radius rho on
// spherical joints, total mass m_r, length L (lambda = m_r / L per metre).
// Falling by y moves 2 y lambda of chain to the heavy side, and the chain
// rides the wheel at r + rho, so M_eff y'' = (m2 - m1) g + 2 lambda g y with
// M_eff = m1 + m2 + m_r + M r^2 / (2 (r + rho)^2): y(T) = (m2 - m1) / (2 lambda)
// (cosh(w T) - 1), w^2 = 2 lambda g / M_eff. L is the chain's own: lifted
// clear of the wheel, it is longer than the cable.
//
// That holds while the rope grips the wheel. Its rods hold it by their
// contacts' friction, a capstan: T_heavy / T_light <= exp(mu_s pi) over the
// half turn (mu_s, mu_d the contacts' coefficients, the mean of the two
// surfaces': 0.5 and 0.3 by default). Spinning up the 1:100 machine's 100
// kg wheel takes 337 N against 16 N, 21 times, where exp(0.5 pi) = 4.8:
// the rope slides over the wheel, and the boxes move as over a fixed drum,
// m2 (g - a) = exp(mu_d pi) m1 (g + a) (the rope's 0.01 kg left out: 1e-4
// of the boxes). Measured with 20 rods at 50 x 20: the heavy box falls at
// 9.29 m/s^2 against this 9.32 (the gripping rope's 6.43), the wheel
// turning at a twelfth of the rope's speed over r. Each engine is held to
// its own model's closed form, as MuJoCo's massless pulleys are in
// `reeve bench peers`.
class RopeAtwoodCase : public ClosedFormCase {
 public:
  RopeAtwoodCase(const AtwoodCase& cable, int segments) : name_(cable.name()), cable_(cable) {
    const Scene s = cable.make();
    SegmentOptions options;
    options.cable = "rope";
    options.segments = segments;
    text_ = segmentScene(cable.json(), s, options).dump();
    // The chain's joints are its vertices in order (the Atwood scene has
    // no other ball joints).
    const Scene chain = parseScene(text_, name_);
    const World& w = *chain.world;
    for (std::size_t i = 1; i < w.sphericals().size(); ++i) {
      const SphericalJoint &before = w.sphericals()[i - 1], &at = w.sphericals()[i];
      length_ += (w.body(at.a).toWorld(at.frame.anchor_a) - w.body(before.a).toWorld(before.frame.anchor_a)).norm();
    }
    radius_ = options.radius_m;
    rope_kg_ = options.rope_mass_kg.value_or(0.01 * cable.m1());
    contact_ = combine(w.bodyDef(find(chain, "wheel")).material, w.bodyDef(w.sphericals().front().a).material);
  }
  std::string name() const override { return name_; }
  std::string description() const override { return cable_.description() + " (segmented rope: the fall)"; }
  int frames() const override { return cable_.frames(); }
  Scene make() const override { return parseScene(text_, name_ + " (segmented)"); }
  void start(const Scene& s) override { y0_ = s.world->body(find(s, "heavy")).x.y(); }
  Errors errors(const Scene& s) const override {
    const double g = AtwoodCase::kG, r = AtwoodCase::kRadius, T = frames() * kFrame;
    const double m1 = cable_.m1(), m2 = cable_.m2();
    const double wheel_kg = cable_.M() * r * r / ((r + radius_) * (r + radius_));  // as the rope at r + rho feels it
    const double lambda = rope_kg_ / length_;
    const double M_eff = m1 + m2 + rope_kg_ + 0.5 * wheel_kg;
    const double w = std::sqrt(2.0 * lambda * g / M_eff);
    double want = (m2 - m1) / (2.0 * lambda) * (std::cosh(w * T) - 1.0);
    const machines::AtwoodMotion grip = machines::atwoodMotion(m1, m2, wheel_kg, g);
    if (grip.tension_heavy > std::exp(contact_.static_friction * std::numbers::pi) * grip.tension_light) {  // slides
      const double k = std::exp(contact_.dynamic_friction * std::numbers::pi);
      want = 0.5 * g * (m2 - k * m1) / (m2 + k * m1) * T * T;
    }
    const double fall = y0_ - s.world->body(find(s, "heavy")).x.y();
    return {{{"acceleration", relative(fall, want)}}};
  }

 private:
  std::string name_;
  const AtwoodCase& cable_;
  std::string text_;
  double length_ = 0, radius_ = 0, rope_kg_ = 0, y0_ = 0;
  ContactMaterial contact_;  // the rods' on the wheel
};

// The paper's Simple scene (Fig. 12, g = 10) without its push: at rest,
// the bottom-left span holds 1 kg, the rest of the cable 2 kg.
class SimpleCase : public ClosedFormCase {
 public:
  SimpleCase() {
    Json j = Json::parse(defaultSceneJson());
    bodyNamed(j, "left_bottom").erase("linear_velocity_m_per_s");
    text_ = j.dump();
  }
  std::string name() const override { return "simple_equilibrium"; }
  std::string description() const override { return "Simple scene at rest: its 4 tensions (10, 20, 20, 20 N) at 2 s"; }
  int frames() const override { return 120; }
  Scene make() const override { return parseScene(text_, "simple"); }
  void start(const Scene&) override {}
  Errors errors(const Scene& s) const override {
    const double want[] = {10.0, 20.0, 20.0, 20.0};
    Errors e;
    for (int j = 0; j < 4; ++j) e.parts.push_back({"tension_" + std::to_string(j), relative(s.cables->tension(0, j), want[j])});
    return e;
  }

 private:
  std::string text_;
};

// scenes/gear_1_to_4.json: 1 and 4 kg balance through a 1:4 belt gear;
// the weights' drift over 2 s against free fall g T^2 / 2, and the belt's
// tension difference against m_s g h / R_small = 9.81 N.
class GearCase : public ClosedFormCase {
 public:
  explicit GearCase(const fs::path& dir) : file_(dir / "gear_1_to_4.json") {}
  std::string name() const override { return "gear_1_to_4"; }
  std::string description() const override { return "1:4 belt gear in balance: drift and tension difference at 2 s"; }
  int frames() const override { return 120; }
  Scene make() const override { return loadScene(file_); }
  void start(const Scene& s) override {
    small0_ = s.world->body(find(s, "weight_small")).x;
    large0_ = s.world->body(find(s, "weight_large")).x;
  }
  Errors errors(const Scene& s) const override {
    const double g = 9.81, T = frames() * kFrame, fall = 0.5 * g * T * T;
    const double drift = std::max((s.world->body(find(s, "weight_small")).x - small0_).norm(),
                                  (s.world->body(find(s, "weight_large")).x - large0_).norm());
    const double diff = std::abs(s.cables->tension(0, 0) - s.cables->tension(0, 1));
    return {{{"drift", drift / fall}, {"tension_difference", relative(diff, 1.0 * g * 0.25 / 0.25)}}};
  }

 private:
  fs::path file_;
  Vec3 small0_, large0_;
};

// scenes/spool.json: 1 kg unwinding a 2 kg spool falls with a = g / 2;
// the fall and the tension m (g - a) at 0.5 s.
class SpoolCase : public ClosedFormCase {
 public:
  explicit SpoolCase(const fs::path& dir) : file_(dir / "spool.json") {}
  std::string name() const override { return "spool"; }
  std::string description() const override { return "weight unwinding a spool: fall and tension at 0.5 s"; }
  int frames() const override { return 30; }
  Scene make() const override { return loadScene(file_); }
  void start(const Scene& s) override { y0_ = s.world->body(find(s, "weight")).x.y(); }
  Errors errors(const Scene& s) const override {
    const double g = 9.81, a = g / 2.0, T = frames() * kFrame;
    const double fall = y0_ - s.world->body(find(s, "weight")).x.y();
    return {{{"acceleration", relative(2.0 * fall / (T * T), a)}, {"tension", relative(s.cables->tension(0, 0), g - a)}}};
  }

 private:
  fs::path file_;
  double y0_ = 0.0;
};

// scenes/elastic.json: 1 kg on a cable of compliance 0.01 m/N stretches
// it by 0.01 x 9.81 m once at rest (8 s).
class ElasticCase : public ClosedFormCase {
 public:
  explicit ElasticCase(const fs::path& dir) : file_(dir / "elastic.json") {}
  std::string name() const override { return "elastic"; }
  std::string description() const override { return "1 kg on a 0.01 m/N cable: stretch and tension at rest (8 s)"; }
  int frames() const override { return 480; }
  Scene make() const override { return loadScene(file_); }
  void start(const Scene&) override {}
  Errors errors(const Scene& s) const override {
    const double T = 9.81, stretch = s.cables->length(0, 0) - s.cables->restLength(0, 0);
    return {{{"stretch", relative(stretch, 0.01 * T)}, {"tension", relative(s.cables->tension(0, 0), T)}}};
  }

 private:
  fs::path file_;
};

// scenes/pinhole.json: a 1 kg ring on a cable of length S between posts D
// apart rests at equal angles, cos a = D / S, each side pulling
// m g / (2 sin a); after 15 s, the ring's distance from that point / S.
class PinholeCase : public ClosedFormCase {
 public:
  explicit PinholeCase(const fs::path& dir) : file_(dir / "pinhole.json") {}
  std::string name() const override { return "pinhole"; }
  std::string description() const override { return "ring on a pinhole at rest (15 s): where, and the tensions"; }
  int frames() const override { return 900; }
  Scene make() const override { return loadScene(file_); }
  void start(const Scene& s) override {
    const Vec3 left = s.world->body(find(s, "post_left")).x, right = s.world->body(find(s, "post_right")).x;
    S_ = s.cables->totalLength(0);
    angle_ = std::acos((right.x() - left.x()) / S_);
    const double l1 = 0.5 * (S_ - (right.y() - left.y()) / std::sin(angle_));
    rest_ = left + l1 * Vec3(std::cos(angle_), -std::sin(angle_), 0.0);
  }
  Errors errors(const Scene& s) const override {
    const double T = 9.81 / (2.0 * std::sin(angle_));
    return {{{"position", (s.world->body(find(s, "ring")).x - rest_).norm() / S_},
             {"tension_left", relative(s.cables->tension(0, 0), T)},
             {"tension_right", relative(s.cables->tension(0, 1), T)}}};
  }

 private:
  fs::path file_;
  double S_ = 0, angle_ = 0;
  Vec3 rest_;
};

// The generated block and tackle (reeve/machines/machines.h): a 4 kg block
// on four strands against a 1.5 kg counterweight, sheaves of 4 g; the
// block's rise and the five strand tensions at 0.5 s
// (blockAndTackleMotion).
class TackleCase : public ClosedFormCase {
 public:
  TackleCase() { spec_.counterweight_kg = 1.5; }
  std::string name() const override { return "block_and_tackle"; }
  std::string description() const override { return "block and tackle, 4 strands: the block's rise and 5 tensions at 0.5 s"; }
  int frames() const override { return 30; }
  Scene make() const override {
    machines::BlockAndTackle m = machines::blockAndTackle(spec_);
    m.scene.name = "block_and_tackle";
    return std::move(m.scene);
  }
  void start(const Scene& s) override { y0_ = s.world->body(find(s, "lower_block")).x.y(); }
  Errors errors(const Scene& s) const override {
    const machines::ChainMotion want =
        machines::blockAndTackleMotion(spec_.block_kg, spec_.sheave_kg, spec_.counterweight_kg, spec_.gravity);
    const double T = frames() * kFrame, rise = s.world->body(find(s, "lower_block")).x.y() - y0_;
    Errors e{{{"acceleration", relative(2.0 * rise / (T * T), want.acceleration)}}};
    for (int j = 0; j <= 4; ++j)
      e.parts.push_back({"tension_" + std::to_string(j), relative(s.cables->tension(0, j), want.tensions[j])});
    return e;
  }

 private:
  machines::BlockAndTackleSpec spec_;
  double y0_ = 0.0;
};

std::vector<std::unique_ptr<AtwoodCase>> atwoodCases(const fs::path& dir) {
  std::vector<std::unique_ptr<AtwoodCase>> cases;
  cases.push_back(std::make_unique<AtwoodCase>("atwood_1_2", dir, 1.0, 2.0, 2.0));
  cases.push_back(std::make_unique<AtwoodCase>("atwood_1_100", dir, 1.0, 100.0, 100.0));
  cases.push_back(std::make_unique<AtwoodCase>("atwood_light_wheel", dir, 1.0, 2.0, 1e-3));
  return cases;
}

}  // namespace

std::pair<std::string, double> Errors::worst() const {
  std::pair<std::string, double> w{"", 0.0};
  for (const auto& p : parts)
    if (!(p.second <= w.second)) w = p;  // a NaN part is the worst
  return w;
}

std::vector<std::unique_ptr<ClosedFormCase>> tradeCases(const fs::path& dir) {
  std::vector<std::unique_ptr<ClosedFormCase>> cases;
  for (auto& c : atwoodCases(dir)) cases.push_back(std::move(c));
  cases.push_back(std::make_unique<SimpleCase>());
  cases.push_back(std::make_unique<GearCase>(dir));
  cases.push_back(std::make_unique<SpoolCase>(dir));
  cases.push_back(std::make_unique<ElasticCase>(dir));
  cases.push_back(std::make_unique<PinholeCase>(dir));
  cases.push_back(std::make_unique<TackleCase>());
  return cases;
}

std::vector<std::unique_ptr<ClosedFormCase>> ropeCases(const fs::path& dir, int segments) {
  // Each rope case keeps its cable case (for the masses and the JSON).
  struct Owning : RopeAtwoodCase {
    Owning(std::unique_ptr<AtwoodCase> c, int n) : RopeAtwoodCase(*c, n), cable(std::move(c)) {}
    std::unique_ptr<AtwoodCase> cable;
  };
  std::vector<std::unique_ptr<ClosedFormCase>> cases;
  for (auto& c : atwoodCases(dir)) cases.push_back(std::make_unique<Owning>(std::move(c), segments));
  return cases;
}

}  // namespace reeve::bench
