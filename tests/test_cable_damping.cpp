// Cable damping (issue 28): a load released from rest at the rest length of
// a damped elastic cable is the damped oscillator
//   m x'' = m g - k x - b x',   x(0) = x'(0) = 0,
// x the stretch, k = 1 / compliance, b the damping. With sigma = b / 2m,
// w0^2 = k / m it settles to m g / k, oscillating at wd = sqrt(w0^2 -
// sigma^2) under an envelope exp(-sigma t) when underdamped. XPBD is
// implicit Euler on this linear system (v1 = v0 + h (g - k x1 / m - b v1 /
// m), x1 = x0 + h v1), whose solution decays by |1 - h lambda| per substep
// for the continuous rates lambda = -sigma +- i wd: the decay rate is
// ln|1 - h lambda| / h = sigma + h (wd^2 - sigma^2) / 2 + O(h^2), the
// frequency arg(1 / (1 - h lambda)) / h = wd (1 - h sigma) + O(h^2). The
// tests check the measured rates against both: tightly against the
// scheme's, and against the closed form within that O(h) error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <vector>

#include "reeve/cable/cable.h"
#include "solver_budgets.h"

namespace reeve::test_cable_damping {
namespace {

constexpr double kG = 9.81, kFrame = 1.0 / 60.0;

using test::Budget;
using test::kFourBudgets;
using test::name;

// m (kg), k (N/m), b (N s/m).
struct Oscillator {
  double mass, stiffness, damping;
  double w0() const { return std::sqrt(stiffness / mass); }
  double sigma() const { return damping / (2.0 * mass); }
  double settled() const { return mass * kG / stiffness; }  // m
  // The continuous rate lambda = -sigma + i wd (underdamped) or the slow
  // real root -sigma + sqrt(sigma^2 - w0^2).
  std::complex<double> lambda() const {
    return -sigma() + std::sqrt(std::complex<double>(sigma() * sigma() - w0() * w0()));
  }
  static Oscillator withRatio(double mass, double w0, double zeta) {
    return {mass, mass * w0 * w0, 2.0 * zeta * mass * w0};
  }
};

// Implicit Euler's decay rate (1/s) and frequency (rad/s) at substep h.
double schemeDecay(const Oscillator& o, double h) { return std::log(std::abs(1.0 - h * o.lambda())) / h; }
double schemeFrequency(const Oscillator& o, double h) { return -std::arg(1.0 - h * o.lambda()) / h; }

SolverSettings settingsOf(const Budget& b) {
  SolverSettings s;
  s.solver = b.solver;
  s.substeps = b.substeps;
  s.iterations = b.iterations;
  return s;
}

// The load (a 0.1 m box, the cable tied at its centre) 1 m below a static
// frame at the origin, on one span; or, `pinhole`, on a cable from a static
// anchor 1 m to the side through a frictionless pinhole at the origin: one
// path of two segments, 2 m of rest length, whose compliance and damping
// are the whole cable's.
struct Rig {
  World world;
  CableSystem cables{world};
  BodyId load = 0;
  int cable = 0;
  Rig(const Budget& b, const Oscillator& o, bool pinhole = false,
      double breaking_tension = std::numeric_limits<double>::infinity())
      : world(settingsOf(b)) {
    BodyDef frame;
    frame.is_static = true;
    frame.shape = Shape::box(Vec3::Constant(0.1));
    const BodyId top = world.addBody(frame);
    BodyDef def;
    def.shape = Shape::box(Vec3::Constant(0.1));
    def.mass = o.mass;
    def.position = Vec3(0.0, -1.0, 0.0);
    load = world.addBody(def);
    CableDef c;
    c.compliance = 1.0 / o.stiffness;
    c.damping = o.damping;
    c.breaking_tension = breaking_tension;
    if (pinhole) {
      frame.position = Vec3(-1.0, 0.0, 0.0);
      const BodyId side = world.addBody(frame);
      c.links = {LinkDef::attachment(side, Vec3::Zero()), LinkDef::pinhole(top, Vec3::Zero()),
                 LinkDef::attachment(load, Vec3::Zero())};
    } else {
      c.links = {LinkDef::attachment(top, Vec3::Zero()), LinkDef::attachment(load, Vec3::Zero())};
    }
    cable = cables.addCable(c);
  }
  double stretch() const { return -world.body(load).x.y() - 1.0; }
  // kinetic + gravity + elastic - (work) + losses: constant but for the
  // losses nothing measures.
  double balance() const {
    const WorldEnergy e = world.energy();
    return e.kinetic + e.gravity + e.elastic + e.damping_loss + e.contact_loss + e.cable_damping_loss;
  }
};

// The stretch less the settled one at the end of each frame, from t = 0.
std::vector<double> record(Rig& rig, const Oscillator& o, double seconds) {
  std::vector<double> y{rig.stretch() - o.settled()};
  for (int f = 0; f < std::lround(seconds / kFrame); ++f) {
    rig.world.step(kFrame);
    y.push_back(rig.stretch() - o.settled());
  }
  return y;
}

struct Measured {
  double decay = 0.0, frequency = 0.0;  // 1/s, rad/s
};

// From the extremes of y (each the vertex of the parabola through a frame's
// sample and its neighbours, while above `floor`): the envelope's decay
// rate (least squares on ln|y|) and the frequency, pi over their spacing.
Measured measure(const std::vector<double>& y, double floor) {
  std::vector<double> t, log_peak;
  for (std::size_t i = 1; i + 1 < y.size(); ++i) {
    const double a = y[i - 1], b = y[i], c = y[i + 1];
    if (!(std::abs(b) >= std::abs(a) && std::abs(b) > std::abs(c) && a * b > 0.0 && b * c > 0.0)) continue;
    const double curvature = a - 2.0 * b + c, shift = 0.5 * (a - c) / curvature;
    const double peak = b - 0.25 * (a - c) * shift;
    if (std::abs(peak) < floor) break;
    t.push_back((static_cast<double>(i) + shift) * kFrame);
    log_peak.push_back(std::log(std::abs(peak)));
  }
  Measured m;
  const std::size_t n = t.size();
  if (n < 3) return m;
  double st = 0.0, sl = 0.0, stt = 0.0, stl = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    st += t[i], sl += log_peak[i], stt += t[i] * t[i], stl += t[i] * log_peak[i];
  }
  m.decay = -(n * stl - st * sl) / (n * stt - st * st);
  m.frequency = std::numbers::pi * static_cast<double>(n - 1) / (t[n - 1] - t[0]);
  return m;
}

double substep(const Budget& b) { return kFrame / b.substeps; }

TEST(CableDamping, AnUnderdampedLoadDecaysAtBOver2mAndSwingsAtTheDampedFrequency) {
  // 1 kg on 100 N/m (w0 = 10 rad/s) damped with 2 N s/m: zeta = 0.1, sigma
  // = 1/s, wd = 9.95 rad/s. Implicit Euler adds h w0^2 / 2 to the decay:
  // 0.83/s at 1 substep a frame, 0.026/s at 32. A single span and a path
  // through a pinhole; both solvers, four budgets.
  const Oscillator o{1.0, 100.0, 2.0};
  const double wd = std::sqrt(o.w0() * o.w0() - o.sigma() * o.sigma());
  for (const bool pinhole : {false, true}) {
    for (const SolverKind solver : {SolverKind::Direct, SolverKind::GaussSeidel}) {
      double last_error = std::numeric_limits<double>::infinity();
      for (const Budget& b : kFourBudgets) {
        if (b.solver != solver) continue;
        SCOPED_TRACE(name(b) + (pinhole ? ", through a pinhole" : ", one span"));
        Rig rig(b, o, pinhole);
        const std::vector<double> y = record(rig, o, 4.0);
        const Measured m = measure(y, 1e-3 * o.settled());
        const double h = substep(b);
        const double decay = schemeDecay(o, h), frequency = schemeFrequency(o, h);
        // The scheme, to what sampling at 60 Hz reads (the peaks' vertices
        // are good to (w dt)^2 / 8 = 0.3 %, which the fit over 4 s divides).
        EXPECT_NEAR(m.decay, decay, 0.01 * decay);
        EXPECT_NEAR(m.frequency, frequency, 0.002 * frequency);
        // The closed form, within the scheme's O(h) error.
        EXPECT_NEAR(m.decay, o.sigma(), 0.01 * decay + h * (wd * wd - o.sigma() * o.sigma()) / 2.0);
        EXPECT_NEAR(m.frequency, wd, 0.002 * frequency + h * wd * (o.sigma() + h * wd * wd / 3.0));
        std::printf("  %-24s %s: decay %.4f /s (scheme %.4f, closed form %.4f), frequency %.4f rad/s (scheme %.4f, "
                    "closed form %.4f)\n",
                    name(b).c_str(), pinhole ? "pinhole" : "span", m.decay, decay, o.sigma(), m.frequency, frequency,
                    wd);
        // More substeps never worse (1 x 1 and 1 x 10 share h).
        const double error = std::abs(m.decay - o.sigma());
        EXPECT_LE(error, last_error * (1.0 + 1e-3));
        last_error = error;
        // Settling at m g / k: the envelope is down to e^-4 of the start's
        // offset at 4 s, or further (the scheme decays faster).
        EXPECT_NEAR(y.back(), 0.0, std::exp(-o.sigma() * 4.0) * o.settled());
      }
    }
  }
}

TEST(CableDamping, AnEngineDistanceConstraintIsDampedAsACableIs) {
  // The same swing on a World's own distance constraint, pull-only and
  // two-sided (a spring and dashpot that push as well, released 0.35 m
  // stretched: it swings 0.045 m or more past its rest length, pushed
  // back), without the cable
  // layer: the Gauss-Seidel kernel and the direct solver's distance rows.
  const Oscillator o{1.0, 100.0, 2.0};
  for (const bool unilateral : {true, false})
    for (const Budget& b : kFourBudgets) {
      SCOPED_TRACE(name(b) + (unilateral ? ", pull-only" : ", two-sided"));
      World world(settingsOf(b));
      BodyDef def;
      def.shape = Shape::box(Vec3::Constant(0.1));
      def.mass = o.mass;
      def.position = Vec3(0.0, unilateral ? -1.0 : -1.35, 0.0);
      const BodyId load = world.addBody(def);
      DistanceConstraint c;
      c.a = kWorldBody;
      c.b = load;
      c.rest_length = 1.0;
      c.compliance = 1.0 / o.stiffness;
      c.damping = o.damping;
      c.unilateral = unilateral;
      world.addDistance(c);
      std::vector<double> y;
      for (int f = 0; f <= 240; ++f) {
        if (f > 0) world.step(kFrame);
        y.push_back(-world.body(load).x.y() - 1.0 - o.settled());
      }
      if (!unilateral) {  // pushed
        EXPECT_LT(*std::min_element(y.begin(), y.end()) + o.settled(), -0.04);
      }
      const Measured m = measure(y, 1e-3 * o.settled());
      const double decay = schemeDecay(o, substep(b)), frequency = schemeFrequency(o, substep(b));
      EXPECT_NEAR(m.decay, decay, 0.01 * decay);
      EXPECT_NEAR(m.frequency, frequency, 0.002 * frequency);
    }
}

TEST(CableDamping, CriticalAndOverdampedLoadsCreepToTheirRestWithoutOvershoot) {
  // 1 kg on 100 N/m damped with 20 N s/m (zeta = 1: x_eq - x = x_eq (1 +
  // w0 t) e^(-w0 t)) and 40 N s/m (zeta = 2: its slow root -sigma +
  // sqrt(sigma^2 - w0^2) = -2.679/s, the fast one -37.3/s gone by 1 s).
  for (const double zeta : {1.0, 2.0}) {
    const Oscillator o = Oscillator::withRatio(1.0, 10.0, zeta);
    const double slow = -o.lambda().real();
    for (const Budget& b : kFourBudgets) {
      SCOPED_TRACE(name(b) + ", zeta " + std::to_string(zeta));
      Rig rig(b, o);
      const std::vector<double> y = record(rig, o, 4.0);
      const double h = substep(b);
      for (const double yf : y) ASSERT_LE(yf, 1e-9 * o.settled());  // never past its rest
      if (zeta == 1.0) {
        // The closed form, within the O(h) error of the scheme's rate: its
        // double root decays at ln(1 + h w0) / h = w0 - h w0^2 / 2 + ..., and
        // dy/dw0 = x_eq w0 t^2 e^(-w0 t) <= 4 x_eq e^-2 / w0 (at t = 2 / w0),
        // so |y - exact| <= 2 h w0 e^-2 x_eq to first order; 1.5 times that.
        double worst = 0.0;
        for (std::size_t f = 0; f < y.size(); ++f) {
          const double t = f * kFrame, exact = -o.settled() * (1.0 + o.w0() * t) * std::exp(-o.w0() * t);
          worst = std::max(worst, std::abs(y[f] - exact));
        }
        const double allowed = 3.0 * h * o.w0() * std::exp(-2.0) * o.settled();
        EXPECT_LE(worst, allowed) << "closed form missed by " << worst << " m";
        std::printf("  %-24s zeta 1: worst |x - closed form| %.3g m (allowed %.3g m)\n", name(b).c_str(), worst,
                    allowed);
      } else {
        // The slow rate from 2 s to 4 s (the fast mode e^-75 gone).
        const std::size_t f2 = std::lround(2.0 / kFrame), f4 = y.size() - 1;
        const double rate = std::log(y[f2] / y[f4]) / 2.0;
        const double scheme = std::log(1.0 + h * slow) / h;
        EXPECT_NEAR(rate, scheme, 1e-3 * scheme);
        EXPECT_NEAR(rate, slow, 1e-3 * scheme + h * slow * slow / 2.0);
        std::printf("  %-24s zeta 2: slow rate %.4f /s (scheme %.4f, closed form %.4f)\n", name(b).c_str(), rate,
                    scheme, slow);
      }
    }
  }
}

TEST(CableDamping, TheLedgerCreditsWhatTheDampingTookAndNeverRises) {
  // 1 kg on 100 N/m, zeta = 0.5 (sigma = 5/s), settles from rest at the
  // rest length: potential m g x_eq went, elastic k x_eq^2 / 2 stayed, so
  // m g x_eq / 2 = 0.481 J was lost. Implicit Euler loses per substep
  // exactly m dv^2 / 2 + k dx^2 / 2 itself, the damping h b v^2, which the
  // ledger credits: the uncredited share, about h w0^2 / (2 sigma + h
  // w0^2) (the scheme's extra decay against the whole), is 0.14 at 1
  // substep a frame and 0.005 at 32; and the balance never rises.
  const Oscillator o = Oscillator::withRatio(1.0, 10.0, 0.5);
  const double lost = 0.5 * o.mass * kG * o.settled();
  for (const bool pinhole : {false, true})
    for (const Budget& b : kFourBudgets) {
      SCOPED_TRACE(name(b) + (pinhole ? ", through a pinhole" : ", one span"));
      Rig rig(b, o, pinhole);
      const double start = rig.balance();
      double last = start;
      for (int f = 0; f < 300; ++f) {
        rig.world.step(kFrame);
        const double now = rig.balance();
        ASSERT_LE(now, last + 1e-10 * lost) << "at " << rig.world.time() << " s";
        last = now;
      }
      const WorldEnergy e = rig.world.energy();
      const double h = substep(b), went = start - (e.kinetic + e.gravity + e.elastic);
      EXPECT_NEAR(went, lost, 1e-6 * lost);  // settled
      const double credited = e.cable_damping_loss;
      const double share = h * o.w0() * o.w0() / (2.0 * o.sigma() + h * o.w0() * o.w0());
      EXPECT_LE(credited, went * (1.0 + 1e-9));
      EXPECT_GE(credited, went * (1.0 - 1.5 * share));
      std::printf("  %-24s %s: credited %.6f J of %.6f J lost (uncredited %.4f, about %.4f expected)\n",
                  name(b).c_str(), pinhole ? "pinhole" : "span", credited, went, 1.0 - credited / went, share);
    }
}

TEST(CableDamping, LightAndHeavyLoadsOnStiffAndSoftCablesStayFiniteAndSettle) {
  // 1e-3 and 1e3 kg; w0 = 1 rad/s (soft: h w0 = 5e-4 at 32 substeps) and
  // 1e4 rad/s (stiff: h w0 = 167 at one substep, where implicit Euler all
  // but stops the swing); zeta 0.7 and 1e3 (gamma = 2 zeta / (w0 h) from
  // 8e-3 to 4e6). Settled within e^-6 of the start's offset from rest (7
  // over the slowest rate, less what the scheme slows an overdamped creep),
  // the balance never rising beyond rounding (the load's weight times 1 m
  // of position, 1e-13 of it).
  for (const Budget& b : kFourBudgets)
    for (const double mass : {1e-3, 1e3})
      for (const double w0 : {1.0, 1e4})
        for (const double zeta : {0.7, 1e3}) {
          SCOPED_TRACE(name(b) + ", " + std::to_string(mass) + " kg, w0 " + std::to_string(w0) + ", zeta " +
                       std::to_string(zeta));
          const Oscillator o = Oscillator::withRatio(mass, w0, zeta);
          Rig rig(b, o);
          // Settling time: 7 / (the slowest rate), the soft overdamped one's
          // w0 / (2 zeta) too slow to wait for; its creep is checked instead.
          const double slowest = -o.lambda().real(), seconds = std::clamp(7.0 / slowest, 1.0, 20.0);
          const double start = rig.balance(), allowed = 1e-9 * mass * kG * o.settled() + 1e-13 * mass * kG;
          double last = start;
          for (int f = 0; f < std::lround(seconds / kFrame); ++f) {
            rig.world.step(kFrame);
            ASSERT_TRUE(std::isfinite(rig.stretch()) && rig.world.body(rig.load).v.allFinite());
            const double now = rig.balance();
            ASSERT_LE(now, last + allowed) << "at " << rig.world.time() << " s";
            last = now;
          }
          const double y = rig.stretch() - o.settled();
          if (seconds < 20.0) {
            EXPECT_NEAR(y, 0.0, std::exp(-6.0) * o.settled());
          } else {  // creeping at about the slow rate, never past its rest
            EXPECT_TRUE(y <= 0.0 && y >= -o.settled() * std::exp(-0.5 * slowest * seconds)) << y;
          }
        }
}

TEST(CableDamping, AWinchHaulingAtConstantSpeedIsNotDamped) {
  // The winch reels cable in at its drum: the span's length shrinks but it
  // does not stretch, so the damping holds nothing back. 5 kg hauled at 0.2
  // m/s for 2 s on a 1 m cable of 1e-3 m/N damped with 50 N s/m (the jerk's
  // swing gone as e^(-b t / 2m) = e^-10): rising steadily, it pulls its
  // weight m g, stretched by the compliance of what is left of it (1e-3
  // m/N per metre) times m g, 0.0294 m, as an undamped cable is. Read as
  // the cable shortening, the damping would push back with b v (the
  // span's b = 50 N s / rest length) and the spring stretch by b v / k =
  // 0.01 m more to hold the weight; the reeled cable read unstretched,
  // by that times the strain, 5e-4 m more.
  for (const Budget& b : kFourBudgets) {
    SCOPED_TRACE(name(b));
    const Oscillator o{5.0, 1e3, 50.0};
    Rig rig(b, o);
    WinchDef w;
    w.at_start = true;  // the drum is the static frame
    w.speed = 0.2;
    rig.cables.setWinch(rig.cable, w);
    for (int f = 0; f < 120; ++f) rig.world.step(kFrame);
    const double rest = rig.cables.restLength(rig.cable, 0), stretch = 1e-3 * rest * o.mass * kG;
    EXPECT_NEAR(rest, 0.6, 1e-9);
    EXPECT_NEAR(rig.cables.length(rig.cable, 0) - rest, stretch, 1e-3 * stretch);
    EXPECT_NEAR(rig.cables.winchPull(rig.cable), o.mass * kG, 1e-3 * o.mass * kG);
  }
}

TEST(CableDamping, ACableJerkedFasterThanItsDashpotBearsParts) {
  // 1 kg moving down at v0 = 1 m/s on a taut cable of 1000 N/m and 100 N
  // s/m rated 50 N: the dashpot alone pulls b v0 = 100 N at once. Its
  // spring alone never reaches 50 N: held at 50 N the load stops within
  // v0^2 / (2 (50 / m - g)) = 0.0125 m, a quarter of the 0.05 m stretch
  // that takes. Implicit Euler pulls in the first substep with
  //   T1 = (k h + b) v1,  v1 = (v0 + g h) / (1 + (k h + b) h / m):
  // 96 N at 32 substeps a frame and 88 N at 10, so it parts then; 46 N at
  // one (the load's speed at the substep's end is what the dashpot
  // feels, and that has all but gone), so it holds.
  const Oscillator o{1.0, 1e3, 100.0};
  const double v0 = 1.0, rating = 50.0;
  for (const Budget& b : kFourBudgets) {
    SCOPED_TRACE(name(b));
    const double h = substep(b), kh_b = o.stiffness * h + o.damping;
    const double first_pull = kh_b * (v0 + kG * h) / (1.0 + kh_b * h / o.mass);
    Rig rig(b, o, false, rating);
    rig.world.body(rig.load).v = Vec3(0.0, -v0, 0.0);
    std::vector<CableEvent> events;
    for (int f = 0; f < 30; ++f) {  // a break is seen by the next substep's update
      rig.world.step(kFrame);
      for (const CableEvent& e : rig.cables.takeEvents()) events.push_back(e);
    }
    if (first_pull < rating) {
      EXPECT_TRUE(events.empty()) << first_pull << " N";
      continue;
    }
    ASSERT_EQ(events.size(), 1u) << first_pull << " N";
    EXPECT_EQ(events[0].kind, CableEvent::Kind::Break);
    EXPECT_NEAR(events[0].time_s, substep(b), 1e-12);  // the end of the first solve
  }
}

TEST(CableDamping, NegativeNonFiniteAndRigidDampingAreRefused) {
  for (const double bad : {-1.0, std::numeric_limits<double>::infinity(), std::nan("")}) {
    World world;
    CableSystem cables(world);
    BodyDef def;
    def.shape = Shape::box(Vec3::Constant(0.1));
    const BodyId a = world.addBody(def);
    def.position = Vec3(0.0, -1.0, 0.0);
    const BodyId b = world.addBody(def);
    CableDef c;
    c.name = "rope";
    c.compliance = 1e-3;
    c.damping = bad;
    c.links = {LinkDef::attachment(a, Vec3::Zero()), LinkDef::attachment(b, Vec3::Zero())};
    EXPECT_THROW(cables.addCable(c), std::invalid_argument) << bad;
    c.damping = 1.0;
    c.compliance = 0.0;
    EXPECT_THROW(cables.addCable(c), std::invalid_argument);
  }
}

}  // namespace
}  // namespace reeve::test_cable_damping
