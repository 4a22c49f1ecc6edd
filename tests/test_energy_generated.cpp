// The energy ledger's invariant over generated machines (issue 28): small
// machines drawn from fixed seeds (masses 1e-3 to 1e3 kg, cable friction
// mu 0 to 10, compliance 0 to 1e-3 m/N with and without damping, hinge
// and prismatic drives with and without caps, limits and schedules,
// winches hauling, holding and paying out, pinholes, static, dynamic and
// kinematic anchors), written as scene JSON and loaded with parseScene as
// a user's file is, run 2.5 s at 1 x 1, 1 x 10, 10 x 2 and 32 x 32 with
// both solvers. No frame may create energy beyond the watch's tolerance
// (EnergyWatch: rounding and the budget's own O(h) error).
//
// The cells that create energy today are listed with what was measured
// behind each (DESIGN.md, "Energy ledger"): the test checks they still
// do, so that a fix must take its cell off the list, and that no other
// cell does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "reeve/scene/energy.h"
#include "reeve/scene/scene.h"
#include "ledger_ratchet.h"
#include "solver_budgets.h"

namespace reeve::test_energy_generated {
namespace {

using nlohmann::json;

constexpr double kG = 9.81;
constexpr double kDuration_s = 2.5;
constexpr int kMachines = 21;

// What a machine is built around; each kind is drawn with each anchor kind.
enum class Kind { Atwood, PinholeAtwood, Ring, Winch, DrumDrive, Arm, Slider };
constexpr int kKinds = 7;
const char* kindName(Kind k) {
  static const char* names[] = {"atwood", "pinhole", "ring", "winch", "drum", "arm", "slider"};
  return names[static_cast<int>(k)];
}
// Where the machine's wheel, eye, drum, arm or rail is held.
enum class Anchor { Static, Dynamic, Kinematic };
const char* anchorName(Anchor a) {
  static const char* names[] = {"static", "dynamic", "kinematic"};
  return names[static_cast<int>(a)];
}

json vec(double x, double y, double z = 0.0) { return json::array({x, y, z}); }

// One machine's scene, drawn from its seed. The direct solver gets masses
// log-uniform over 1e-3..1e3 kg, each body its own; Gauss-Seidel, which is
// right only while wheels are about as heavy as their loads (README, "Substeps,
// iterations and the solver"), the same draws squeezed into one decade about
// a machine-wide scale that is itself log-uniform over 1e-3..1e3 kg. Every
// other draw is the same for both, so both solvers run the same machine.
class Generator {
 public:
  Generator(int index, SolverKind solver)
      : rng_(20261125u + 7919u * static_cast<unsigned>(index)),
        solver_(solver),
        kind_(static_cast<Kind>(index % kKinds)),
        anchor_(static_cast<Anchor>((index + index / kKinds) % 3)) {
    mass_scale_log_ = uniform(-3.0, 3.0);
  }

  Kind kind() const { return kind_; }
  Anchor anchor() const { return anchor_; }

  json scene() {
    switch (kind_) {
      case Kind::Atwood: atwood(false); break;
      case Kind::PinholeAtwood: atwood(true); break;
      case Kind::Ring: ring(); break;
      case Kind::Winch: winch(); break;
      case Kind::DrumDrive: drum(); break;
      case Kind::Arm: arm(); break;
      case Kind::Slider: slider(); break;
    }
    json s = {{"name", std::string(kindName(kind_)) + "_" + anchorName(anchor_)},
              {"solver", {{"frame_rate_hz", 60}}},
              {"duration_s", kDuration_s},
              {"bodies", bodies_},
              {"hinges", hinges_},
              {"joints", joints_},
              {"cables", cables_}};
    return s;
  }

 private:
  // From mt19937's own output, which the standard fixes; the standard's
  // distributions are not the same in every library, and the machines, and
  // so the list of cells below, must be.
  double uniform(double a, double b) { return a + (b - a) * (static_cast<double>(rng_()) / 4294967296.0); }
  bool coin(double p = 0.5) { return uniform(0.0, 1.0) < p; }
  double mass() {
    const double u = uniform(0.0, 1.0);
    const double log_m = solver_ == SolverKind::Direct ? -3.0 + 6.0 * u : mass_scale_log_ + (u - 0.5);
    return std::pow(10.0, log_m);
  }

  void box(const std::string& name, double m, double x, double y, double half) {
    bodies_.push_back({{"name", name},
                       {"shape", {{"type", "box"}, {"half_extents_m", vec(half, half, half)}}},
                       {"mass_kg", m},
                       {"position_m", vec(x, y)}});
  }
  void wheel(const std::string& name, double m, double x, double y, double r) {
    bodies_.push_back({{"name", name},
                       {"shape", {{"type", "cylinder"}, {"radius_m", r}, {"half_length_m", 0.05}}},
                       {"mass_kg", m},
                       {"position_m", vec(x, y)}});
  }
  void fixedBody(const std::string& name, double x, double y) {
    bodies_.push_back({{"name", name},
                       {"shape", {{"type", "box"}, {"half_extents_m", vec(0.1, 0.1, 0.1)}}},
                       {"static", true},
                       {"position_m", vec(x, y)}});
  }
  // A kinematic carrier: speeds up to (vx, vy) over 0.5 s, reverses by 1.5 s
  // and stops at 2 s, back where it started.
  void carrier(const std::string& name, double x, double y, double speed) {
    const double a = uniform(0.0, 6.283185307179586);  // a direction, radians
    const double vx = speed * std::cos(a), vy = speed * std::sin(a);
    bodies_.push_back({{"name", name},
                       {"shape", {{"type", "box"}, {"half_extents_m", vec(0.1, 0.1, 0.1)}}},
                       {"position_m", vec(x, y)},
                       {"motion", json::array({{{"t_s", 0.0}, {"velocity_m_per_s", vec(0, 0)}},
                                               {{"t_s", 0.5}, {"velocity_m_per_s", vec(vx, vy)}},
                                               {{"t_s", 1.5}, {"velocity_m_per_s", vec(-vx, -vy)}},
                                               {{"t_s", 2.0}, {"velocity_m_per_s", vec(0, 0)}}})}});
  }

  // The body a wheel, eye or rail is held by, at (x, y): the world or a
  // static body, a dynamic block hung from a static one on two ropes (it
  // sways, tilts and bobs with what it carries), or a kinematic carrier. Returns
  // its name ("world" for the world).
  std::string holder(double x, double y, double carried_weight_N) {
    switch (anchor_) {
      case Anchor::Static:
        if (coin()) return "world";
        fixedBody("frame", x, y);
        return "frame";
      case Anchor::Dynamic: {
        box("block", mass(), x, y, 0.1);
        fixedBody("ceiling", x, y + 1.0);
        for (const double side : {-1.0, 1.0}) {
          const json top = {{"body", "ceiling"}, {"type", "attachment"}, {"point_m", vec(0.3 * side, 0)}};
          const json bottom = {{"body", "block"}, {"type", "attachment"}, {"point_m", vec(0.1 * side, 0.1)}};
          json hanger = {{"name", side < 0 ? "hanger_left" : "hanger_right"}, {"links", json::array({top, bottom})}};
          elastic(hanger, 0.9, carried_weight_N / 2.0);
          cables_.push_back(hanger);
        }
        return "block";
      }
      case Anchor::Kinematic:
        carrier("carrier", x, y, uniform(0.05, 0.5));
        return "carrier";
    }
    return "world";
  }

  // Compliance 0 (half the cables) or log-uniform 1e-8..1e-3 m/N, no more
  // than stretches `length_m` of cable by 10 % under `tension_N`; damping on
  // half the elastic ones, up to twice critical for `tension_N / g` on it.
  void elastic(json& cable, double length_m, double tension_N) {
    const bool compliant = coin();
    const double log_c = uniform(-8.0, -3.0);
    const bool damped = coin();
    const double zeta = uniform(0.0, 2.0);
    if (!compliant) return;
    const double c = std::min(std::pow(10.0, log_c), 0.1 * length_m / std::max(tension_N, 1e-12));
    cable["compliance_m_per_N"] = c;
    if (damped) cable["damping_N_s_per_m"] = 2.0 * zeta * std::sqrt(tension_N / kG / c);
  }
  // Cable friction: none (a no-slip wheel or a frictionless eye), 0 (an
  // ideal pulley) or 0..10.
  void friction(json& link) {
    const double u = uniform(0.0, 1.0), mu = uniform(0.0, 10.0);
    if (u < 1.0 / 3.0) return;
    link["mu"] = u < 0.5 ? 0.0 : mu;
  }
  // Rope hanging below a wheel or eye long enough that neither load reaches
  // it within the run (a load falls at most g T^2 / 2).
  static double fallRoom_m() { return 1.0 + 0.5 * kG * kDuration_s * kDuration_s; }

  // Two loads on a rope over a wheel (or through an eye) on the holder.
  void atwood(bool pinhole) {
    const double m1 = mass(), m2 = mass();
    const double r = uniform(0.1, 0.4);
    const double hang = fallRoom_m();
    std::string wheel_body;
    if (pinhole) {
      const std::string h = holder(0.0, 0.0, (m1 + m2) * kG * 2.0);
      if (h == "world") {
        fixedBody("eye", 0.0, 0.0);
        wheel_body = "eye";
      } else {
        wheel_body = h;
      }
    } else {
      wheel("wheel", mass(), 0.0, 0.0, r);
      const std::string h = holder(0.0, 0.0, (m1 + m2) * kG * 2.0);
      hinges_.push_back({{"body", "wheel"}, {"other", h}, {"anchor_m", vec(0, 0)}, {"axis", vec(0, 0, 1)}});
      wheel_body = "wheel";
    }
    box("load_left", m1, -r, -hang, 0.05);
    box("load_right", m2, r, -hang - uniform(0.0, 0.5), 0.05);
    json over = pinhole ? json{{"body", wheel_body}, {"type", "pinhole"}, {"point_m", vec(0, 0)}}
                        : json{{"body", wheel_body}, {"type", "rolling"}, {"orientation", "cw"}};
    friction(over);
    json rope = {{"name", "rope"},
                 {"links", json::array({{{"body", "load_left"}, {"type", "attachment"}, {"point_m", vec(0, 0.05)}},
                                        over,
                                        {{"body", "load_right"}, {"type", "attachment"}, {"point_m", vec(0, 0.05)}}})}};
    elastic(rope, 2.0 * hang, std::max(m1, m2) * kG);
    cables_.push_back(rope);
  }

  // A ring (an eye on a dynamic body) on a line between two posts on the
  // holders, let go off its equilibrium.
  void ring() {
    const double m = mass();
    const double span = uniform(2.0, 4.0), rise = uniform(-0.5, 0.5);
    const std::string left = holder(-span / 2, 0.0, m * kG * 2.0);
    fixedBody("post", span / 2, rise);
    const std::string left_body = left == "world" ? (fixedBody("post_left", -span / 2, 0.0), "post_left") : left;
    box("ring", m, uniform(-0.3, 0.3) * span, -uniform(0.5, 1.5), 0.05);
    json eye = {{"body", "ring"}, {"type", "pinhole"}, {"point_m", vec(0, 0)}};
    friction(eye);
    json line = {{"name", "line"},
                 {"links", json::array({{{"body", left_body}, {"type", "attachment"}, {"point_m", vec(0, 0)}}, eye,
                                        {{"body", "post"}, {"type", "attachment"}, {"point_m", vec(0, 0)}}})}};
    elastic(line, span + 2.0, m * kG * 3.0);
    cables_.push_back(line);
  }

  // A winch hauls in, holds and pays out (speed commands), or hauls to a
  // length and back (length commands), with or without a pull cap; its
  // drum is on the holder and the rope runs over a sheave to the load, or
  // (a dynamic holder) the winch rides the load, climbing its rope.
  void winch() {
    const double m = mass();
    const double v = uniform(0.05, 0.5);
    json commands = coin() ? json::array({{{"from_s", 0.0}, {"speed_m_per_s", v}},
                                          {{"from_s", 0.8}, {"speed_m_per_s", 0.0}},
                                          {{"from_s", 1.4}, {"speed_m_per_s", -v}},
                                          {{"from_s", 2.2}, {"speed_m_per_s", 0.0}}})
                           : json::array({{{"from_s", 0.0}, {"stored_m", 0.8 * v}},  // hauls 0.8 s, pays it out
                                          {{"from_s", 1.5}, {"stored_m", 0.0}}});
    json w = {{"end", "last"}, {"max_speed_m_per_s", v}, {"commands", commands}};
    if (coin()) w["max_pull_N"] = m * kG * uniform(0.5, 3.0);  // below the weight: it stalls, holds or pays out
    const double hang = uniform(1.0, 2.0);
    json rope;
    if (anchor_ == Anchor::Dynamic) {
      fixedBody("ceiling", 0.0, 0.0);
      box("climber", m, 0.0, -hang, 0.05);
      rope = {{"name", "rope"},
              {"links", json::array({{{"body", "ceiling"}, {"type", "attachment"}, {"point_m", vec(0, 0)}},
                                     {{"body", "climber"}, {"type", "attachment"}, {"point_m", vec(0, 0.05)}}})},
              {"winch", w}};
    } else {
      const double r = uniform(0.1, 0.3);
      wheel("sheave", mass(), 0.0, 0.0, r);
      hinges_.push_back({{"body", "sheave"}, {"other", "world"}, {"anchor_m", vec(0, 0)}, {"axis", vec(0, 0, 1)}});
      const std::string h = holder(r, -1.0, m * kG);
      const std::string drum = h == "world" ? (fixedBody("drum", r, -1.0), "drum") : h;
      box("load", m, -r, -hang, 0.05);
      json over = {{"body", "sheave"}, {"type", "rolling"}, {"orientation", "cw"}};
      friction(over);
      rope = {{"name", "rope"},
              {"links", json::array({{{"body", "load"}, {"type", "attachment"}, {"point_m", vec(0, 0.05)}}, over,
                                     {{"body", drum}, {"type", "attachment"}, {"point_m", vec(0, 0)}}})},
              {"winch", w}};
    }
    elastic(rope, hang + 1.0, m * kG * 1.5);
    cables_.push_back(rope);
  }

  // A hinge drive turns a drum that winds a load's rope: velocity or angle,
  // a constant target or a schedule, with or without a torque cap (below
  // the load's moment it is overpowered) and a limit.
  void drum() {
    const double m = mass(), r = uniform(0.1, 0.3);
    wheel("drum", mass(), 0.0, 0.0, r);
    const std::string h = holder(0.0, 0.0, m * kG * 2.0);
    hinges_.push_back({{"body", "drum"}, {"other", h}, {"anchor_m", vec(0, 0)}, {"axis", vec(0, 0, 1)},
                       {"drive", hingeDrive(m * kG * r, 0.5 / r)}});
    if (coin()) hinges_.back()["limit"] = {{"lower_rad", -uniform(0.5, 3.0)}, {"upper_rad", uniform(0.5, 3.0)}};
    const double hang = uniform(1.0, 2.0);
    box("load", m, -r, -hang, 0.05);
    // The load, overpowering a capped drive, unwinds at most g T^2 / 2.
    json rope = {{"name", "rope"},
                 {"links", json::array({{{"body", "drum"}, {"type", "rolling"}, {"orientation", "ccw"},
                                         {"stored_m", fallRoom_m()}},
                                        {{"body", "load"}, {"type", "attachment"}, {"point_m", vec(0, 0.05)}}})}};
    elastic(rope, hang, m * kG * 1.5);
    cables_.push_back(rope);
  }

  // A hinge drive on an arm pivoted at its end; a load hangs from its tip.
  void arm() {
    const double m_arm = mass(), m = mass();
    const double length = uniform(0.5, 1.2);
    const std::string h = holder(0.0, 0.0, (m + m_arm) * kG * 2.0);
    box("arm", m_arm, length / 2, 0.0, 0.05);
    bodies_.back()["shape"]["half_extents_m"] = vec(length / 2, 0.05, 0.05);
    hinges_.push_back({{"body", "arm"}, {"other", h}, {"anchor_m", vec(0, 0)}, {"axis", vec(0, 0, 1)},
                       {"drive", hingeDrive((m + m_arm / 2) * kG * length, 1.0)}});
    if (coin()) hinges_.back()["limit"] = {{"lower_rad", -uniform(0.3, 1.5)}, {"upper_rad", uniform(0.3, 1.5)}};
    const double hang = uniform(0.5, 1.5);
    box("load", m, length, -hang, 0.05);
    json rope = {{"name", "rope"},
                 {"links", json::array({{{"body", "arm"}, {"type", "attachment"}, {"point_m", vec(length / 2, 0)}},
                                        {{"body", "load"}, {"type", "attachment"}, {"point_m", vec(0, 0.05)}}})}};
    elastic(rope, hang, m * kG * 3.0);
    cables_.push_back(rope);
  }

  // A drive: velocity (up to `speed` rad/s) or angle (up to 2 rad), a
  // constant target or a schedule over the run; capped at 0.5 to 4 times
  // `moment_N_m` or not.
  json hingeDrive(double moment_N_m, double speed) {
    const bool velocity = coin(), scheduled = coin(), capped = coin();
    const double a = uniform(-1.0, 1.0), b = uniform(-1.0, 1.0), cap = uniform(0.5, 4.0);
    json d = {{"mode", velocity ? "velocity" : "angle"}};
    const char* key = velocity ? "target_rad_per_s" : "target_rad";
    const double scale = velocity ? speed : 2.0;
    if (scheduled)
      d["schedule"] = json::array({{{"t_s", 0.0}, {key, 0.0}}, {{"t_s", 1.0}, {key, a * scale}},
                                   {{"t_s", 2.0}, {key, b * scale}}});
    else
      d[key] = a * scale;
    if (capped) d["max_torque_N_m"] = cap * moment_N_m;
    return d;
  }

  // A carriage on a rail (tilted up to 10 degrees) hauls a load over a
  // sheave: a velocity or position drive, constant or scheduled, with or
  // without a force cap and a limit (without one the cap keeps the
  // carriage off the sheave: at least 1.5 times the load's weight).
  void slider() {
    const double m = mass(), m_carriage = mass(), r = uniform(0.1, 0.3);
    wheel("sheave", mass(), 0.0, 0.0, r);
    hinges_.push_back({{"body", "sheave"}, {"other", "world"}, {"anchor_m", vec(0, 0)}, {"axis", vec(0, 0, 1)}});
    const double x0 = -uniform(1.5, 2.5);
    const std::string h = holder(x0, r, m * kG);
    box("carriage", m_carriage, x0, r, 0.05);
    const double tilt = uniform(-0.17, 0.17);
    const bool velocity = coin(), scheduled = coin(), limited = coin(), capped = coin();
    const double a = uniform(-1.0, 0.3), b = uniform(-1.0, 0.3);
    const double cap = (m + m_carriage) * kG * uniform(limited ? 0.5 : 1.5, 4.0);
    json d = {{"mode", velocity ? "velocity" : "position"}};
    const char* key = velocity ? "target_m_per_s" : "target_m";
    const double scale = velocity ? 0.5 : 0.6;
    if (scheduled)
      d["schedule"] = json::array({{{"t_s", 0.0}, {key, 0.0}}, {{"t_s", 1.0}, {key, a * scale}},
                                   {{"t_s", 2.0}, {key, b * scale}}});
    else
      d[key] = a * scale;
    if (capped) d["max_force_N"] = cap;
    json rail = {{"type", "prismatic"}, {"body", "carriage"}, {"other", h},
                 {"anchor_m", vec(x0, r)}, {"axis", vec(std::cos(tilt), std::sin(tilt))}, {"drive", d}};
    // The carriage stays at least 0.6 m short of the sheave.
    if (limited) rail["limit"] = {{"lower_m", -1.0}, {"upper_m", std::min(0.5, -x0 - 1.0)}};
    joints_.push_back(rail);
    const double hang = uniform(1.0, 2.0);
    box("load", m, r, -hang, 0.05);
    json over = {{"body", "sheave"}, {"type", "rolling"}, {"orientation", "cw"}};
    friction(over);
    json rope = {{"name", "rope"},
                 {"links", json::array({{{"body", "carriage"}, {"type", "attachment"}, {"point_m", vec(0, 0)}}, over,
                                        {{"body", "load"}, {"type", "attachment"}, {"point_m", vec(0, 0.05)}}})}};
    elastic(rope, hang - x0, m * kG * 1.5);
    cables_.push_back(rope);
  }

  std::mt19937 rng_;
  SolverKind solver_;
  Kind kind_;
  Anchor anchor_;
  double mass_scale_log_ = 0.0;
  json bodies_ = json::array(), hinges_ = json::array(), joints_ = json::array(), cables_ = json::array();
};

struct Cell {
  int machine;
  test::Budget budget;
};

std::string machineName(int i) {
  const Generator g(i, SolverKind::Direct);
  char text[64];
  std::snprintf(text, sizeof text, "m%02d_%s_%s", i, kindName(g.kind()), anchorName(g.anchor()));
  return text;
}

std::string cellName(const Cell& c) {
  return machineName(c.machine) + " " + (c.budget.solver == SolverKind::Direct ? "direct" : "gauss-seidel") + " " +
         std::to_string(c.budget.substeps) + "x" + std::to_string(c.budget.iterations);
}

void PrintTo(const Cell& c, std::ostream* os) { *os << cellName(c); }

// Machine, solver and budget of the cells that create energy today, and why.
const std::set<std::string>& knownCreating() {
  static const std::set<std::string> cells = {
      // A 2 kg sheave (mu 0.97 over half a turn) between 8.7 kg and a winch
      // on a kinematic carrier that reverses, paying out: after the catch
      // (2.2 kN in a frame) the wrap sticks and slips by turns, substep by
      // substep, each solve consistent (a stuck one within the bound, a
      // slipping one sliding with its friction) but the pair not: +0.21 J
      // (0.14 %) in 0.05 s. At 10, 16, 20 and 128 substeps it sticks and
      // meets the closed form, 78.57 and 77.78 N; before the stick/slip
      // recheck (item 3) it slid at the bound at 20 to 128 substeps (47 to
      // 538 N on the load's side). Also at 64 substeps.
      "m10_winch_kinematic direct 32x32", "m10_winch_kinematic gauss-seidel 32x32",
      // Gauss-Seidel's one sweep a frame on stiff elastic cables (2e-8 to
      // 2e-5 m/N, most under grams): the stretch the unconverged sweep
      // leaves is elastic energy nothing put in (m01: +0.41 J in the first
      // frame from 60 g of bodies). None with the cables inextensible; all
      // pass at 1 x 10.
      "m01_pinhole_dynamic gauss-seidel 1x1", "m04_drum_dynamic gauss-seidel 1x1",
      "m06_slider_static gauss-seidel 1x1", "m12_arm_dynamic gauss-seidel 1x1",
      "m13_slider_kinematic gauss-seidel 1x1", "m14_atwood_dynamic gauss-seidel 1x1",
      "m19_arm_static gauss-seidel 1x1",
      // Gauss-Seidel's one sweep a frame on a driven drum on a kinematic
      // carrier, winding a load: since the rolling ends are
      // held on their wheels within a solve (issue 29, item 3) the sweep
      // winds the drive's turn straight onto the drum, +0.0053 J (1.5 % of
      // the scale) by 0.18 s; 2.4e-5 at 1 x 10. Not traced further.
      "m18_drum_kinematic gauss-seidel 1x1",
      // Gauss-Seidel's one sweep a frame on a rail held by a block hung on
      // two ropes: the 87 kg carriage, hauling 86 kg over a sheave, sags off
      // the rail of its 13.5 kg holder (4 cm by 0.1 s, 23 cm by 0.63 s),
      // +83 J by 0.1 s (+1.3 kJ in a frame at 0.73 s with the cables
      // inextensible). Passes at 1 x 10.
      "m20_slider_dynamic gauss-seidel 1x1",
      // Gauss-Seidel's one sweep a frame at a hinge limit: a 102 kg arm
      // driven into it with 46 kg on its tip, +77 J in a frame at 0.28 s
      // (2.1 %); none without the limit.
      "m05_arm_kinematic gauss-seidel 1x1",
  };
  return cells;
}

std::vector<Cell> cells() {
  std::vector<Cell> all;
  for (int i = 0; i < kMachines; ++i)
    for (const test::Budget& b : test::kFourBudgets) all.push_back({i, b});
  return all;
}

class GeneratedMachineAtFourBudgets : public testing::TestWithParam<Cell> {};

TEST_P(GeneratedMachineAtFourBudgets, CreatesNoEnergy) {
  const Cell& cell = GetParam();
  Generator generator(cell.machine, cell.budget.solver);
  json doc = generator.scene();
  doc["solver"]["method"] = solverMethodName(cell.budget.solver);
  doc["solver"]["substeps"] = cell.budget.substeps;
  doc["solver"]["iterations"] = cell.budget.iterations;
  Scene s;
  ASSERT_NO_THROW(s = parseScene(doc.dump(), machineName(cell.machine))) << doc.dump();
  EnergyWatch watch(s);
  std::optional<EnergyCreated> first;
  std::string broke;
  // The worst rise of the balance, within a frame or since its lowest
  // point, as a fraction of the watch's scale.
  // The whole run, past the first finding, for the worst rise.
  double lowest = watch.ledger().balance_J(), worst = 0.0, peak_kinetic_J = 0.0;
  for (int f = 0; f < s.frameCount(); ++f) {
    const double before = watch.ledger().balance_J();
    s.world->step(1.0 / s.frame_rate_hz);
    if (s.world->firstNonFinite()) broke = "a non-finite state";
    if (s.cables->firstBreach()) broke = "the cable bookkeeping broke: " + s.cables->firstBreach()->what;
    if (!broke.empty()) break;
    const std::optional<EnergyCreated> created = watch.check(s);
    if (created && !first) first = created;
    const double after = watch.ledger().balance_J();
    worst = std::max(worst, std::max(after - before, after - lowest) / watch.scale_J());
    // As the watch does: a finding is told once, the lowest point starts again.
    lowest = created ? after : std::min(lowest, after);
    peak_kinetic_J = std::max(peak_kinetic_J, watch.ledger().kinetic_J);
  }
  EXPECT_GT(peak_kinetic_J, 0.0) << cellName(cell) << ": the machine never moved";
  const double h = 1.0 / (s.frame_rate_hz * cell.budget.substeps);
  std::printf("[ measured ] %-40s worst rise %.3g of the scale (%.3g of the tolerance %.2g)%s%s\n",
              cellName(cell).c_str(), worst, worst / energyTolerance(h), energyTolerance(h),
              first ? ", creates energy" : "", broke.empty() ? "" : (", " + broke).c_str());
  const bool creates = first || !broke.empty();
  test::expectAsListed(knownCreating(), cellName(cell), creates,
                       (first ? energyCreatedMessage(*first) : broke) + "\n" + doc.dump());
}

INSTANTIATE_TEST_SUITE_P(EnergyLedger, GeneratedMachineAtFourBudgets, testing::ValuesIn(cells()),
                         [](const testing::TestParamInfo<Cell>& info) { return test::parameterName(cellName(info.param)); });

}  // namespace
}  // namespace reeve::test_energy_generated


