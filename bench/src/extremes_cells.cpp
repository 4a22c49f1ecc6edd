#include "extremes_cells.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "reeve/machines/closed_forms.h"
#include "reeve/machines/machines.h"
#include "reeve/machines/probe.h"

namespace reeve::bench {
namespace {

using Json = nlohmann::ordered_json;
constexpr double kG = 10.0;

// The machine of a cell, ready to run, with the closed form of its taut
// motion: span tensions (N), or a jerk's speed after the snap (m/s).
struct Rig {
  Scene scene;
  double seconds = 1.0;
  std::vector<double> tensions;  // per cable joint; empty: none applies
  BodyId light = 0, heavy = 0;
  double speed_after_snap = 0.0;  // > 0 for a jerk
};

// Masses (kg) of the light side, heavy side and each wheel of `c`.
struct Masses {
  double light, heavy, wheel;
};
Masses masses(const Condition& c) {
  if (c.load_N > 0.0) return {c.load_N / kG, 2.0 * c.load_N / kG, 1.0};
  return {1.0, c.load_ratio, c.wheel_ratio};
}

Rig atwoodRig(const Condition& c, const CellBudget& b) {
  machines::AtwoodSpec spec;
  const Masses m = masses(c);
  spec.light_kg = m.light;
  spec.heavy_kg = m.heavy;
  spec.wheel_kg = m.wheel;
  spec.compliance_m_per_N = c.compliance_m_per_N;
  spec.budget = {b.substeps, b.iterations, b.solver};
  spec.drop_m = 6.0;  // free fall for 1 s leaves the light box short of the wheel
  Rig rig;
  if (c.slack_m > 0.0) {
    spec.gravity = 0.0;
    spec.drop_m = 20.0;
    spec.slack_m = c.slack_m;
    spec.heavy_speed_m_per_s = c.speed_m_per_s;
    rig.seconds = c.slack_m / c.speed_m_per_s + 0.2;
    // Inelastic snap: the heavy box's momentum shared with the rest.
    rig.speed_after_snap = m.heavy * c.speed_m_per_s / (m.light + m.heavy + 0.5 * m.wheel);
  } else {
    spec.gravity = kG;
    const machines::AtwoodMotion want = machines::atwoodMotion(m.light, m.heavy, m.wheel, kG);
    rig.tensions = {want.tension_light, want.tension_heavy};
  }
  machines::Atwood a = machines::atwood(spec);
  rig.light = a.light;
  rig.heavy = a.heavy;
  rig.scene = std::move(a.scene);
  return rig;
}

// scenes/simple.json without its push: two 1 kg boxes on the left (the
// light side, 2 kg) and the heavy box on the right, over two wheels of M:
// a = (m_R - m_L) g / (m_L + m_R + M); T0 = m_lb (g + a), T1 = m_L (g + a),
// each wheel adds M a / 2.
Rig simpleRig(const Condition& c, const CellBudget& b) {
  const Masses m = masses(c);
  Json j = Json::parse(defaultSceneJson());
  for (Json& body : j["bodies"]) {
    body.erase("density_kg_per_m3");
    body.erase("linear_velocity_m_per_s");
    const std::string name = body["name"];
    body["mass_kg"] = name.rfind("wheel", 0) == 0 ? m.wheel : name == "right" ? 2.0 * m.heavy : m.light;
  }
  j["solver"]["frame_rate_hz"] = b.rate_hz;
  j["solver"]["substeps"] = b.substeps;
  j["solver"]["iterations"] = b.iterations;
  j["solver"]["method"] = solverMethodName(b.solver);
  j["cables"][0]["compliance_m_per_N"] = c.compliance_m_per_N;
  Rig rig;
  rig.scene = parseScene(j.dump(), "simple (" + c.name + ")");
  rig.seconds = 0.5;
  const double mL = 2.0 * m.light, mR = 2.0 * m.heavy, M = m.wheel;
  const double a = (mR - mL) * kG / (mL + mR + M);
  rig.tensions = {m.light * (kG + a), mL * (kG + a), mL * (kG + a) + 0.5 * M * a, mL * (kG + a) + M * a};
  rig.heavy = *rig.scene.world->findBody("right");
  return rig;
}

// A light body that only cables hold (README, "Substeps and iterations"):
// the bead, bead_ratio x the 1 kg load, 1 m above the load's tie point on
// one rigid cable and tied by another to a ceiling anchor 1 m above it
// and offset_m to the side. Bent, the chain lets the load fall until it
// lines up (2.2 cm at 0.3 m), then swings it; the bead, cheap to move, is
// whipped across and caught by cables near a straight line, where their
// pull sideways on it is their tension times their small angle (a
// tightrope). No closed form: energy and stretch only.
Rig beadRig(const Condition& c, const CellBudget& b) {
  const auto box = [](double x, double y, double z) { return Json{{"type", "box"}, {"half_extents_m", {x, y, z}}}; };
  const auto tie = [](const char* body, double y) {
    return Json{{"body", body}, {"type", "attachment"}, {"point_m", {0.0, y, 0.0}}};
  };
  Json j = {
      {"name", "bead"},
      {"solver",
       {{"frame_rate_hz", b.rate_hz},
        {"substeps", b.substeps},
        {"iterations", b.iterations},
        {"method", solverMethodName(b.solver)},
        {"gravity_m_per_s2", {0.0, -kG, 0.0}}}},
      {"bodies",
       {{{"name", "ceiling"}, {"static", true}, {"shape", box(0.1, 0.02, 0.1)}, {"position_m", {c.offset_m, 1.02, 0.0}}},
        {{"name", "bead"},
         {"shape", {{"type", "sphere"}, {"radius_m", 0.02}}},
         {"mass_kg", c.bead_ratio},
         {"position_m", {0.0, 0.0, 0.0}}},
        {{"name", "load"}, {"shape", box(0.1, 0.1, 0.1)}, {"mass_kg", 1.0}, {"position_m", {0.0, -1.1, 0.0}}}}},
      {"cables",
       {{{"name", "upper"}, {"links", {tie("ceiling", -0.02), tie("bead", 0.0)}}},
        {{"name", "lower"}, {"links", {tie("bead", 0.0), tie("load", 0.1)}}}}}};
  Rig rig;
  rig.scene = parseScene(j.dump(), "bead (" + c.name + ")");
  rig.light = *rig.scene.world->findBody("bead");
  rig.heavy = *rig.scene.world->findBody("load");
  return rig;
}

double kineticEnergy(const World& w) {
  double e = 0.0;
  for (BodyId id = 0; id < w.bodyCount(); ++id) {
    const BodyState& s = w.body(id);
    const Vec3 omega = s.q.conjugate() * s.omega;  // body axes
    e += 0.5 * w.bodyMass(id) * s.v.squaredNorm() + 0.5 * omega.dot(s.inertia * omega);
  }
  return e;
}

// Kinetic + gravity + the elastic energy T (length - rest) / 2 of
// stretched spans (T = stretch / compliance).
double energy(const Scene& s) {
  const World& w = *s.world;
  double e = kineticEnergy(w);
  for (BodyId id = 0; id < w.bodyCount(); ++id) e -= w.bodyMass(id) * w.settings().gravity.dot(w.body(id).x);
  for (int c = 0; c < static_cast<int>(s.cables->cables().size()); ++c)
    for (int j = 0; j < static_cast<int>(s.cables->cables()[c].joints.size()); ++j)
      if (s.cables->jointEnabled(c, j) && s.cables->cables()[c].compliance_per_m > 0.0)
        e += 0.5 * s.cables->tension(c, j) * std::max(0.0, s.cables->length(c, j) - s.cables->restLength(c, j));
  return e;
}

}  // namespace

std::string shortNumber(double x) {
  char buf[32];
  const bool exponent_form = x != 0.0 && (std::abs(x) >= 1e4 || std::abs(x) < 1e-3);
  std::snprintf(buf, sizeof buf, exponent_form ? "%.3g" : "%g", x);
  std::string s = buf;
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string exponent = s.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return s.substr(0, e + 1) + (negative ? "-" : "") + exponent;
}

std::vector<Condition> conditions(const std::string& machine) {
  if (machine != "atwood" && machine != "simple" && machine != "bead")
    throw std::invalid_argument("unknown machine '" + machine + "', expected atwood, simple or bead");
  std::vector<Condition> list;
  const auto add = [&](std::string name, auto set) {
    Condition c;
    c.machine = machine;
    c.name = std::move(name);
    set(c);
    list.push_back(c);
  };
  if (machine == "bead") {
    for (double r : {1e-6, 1e-3, 1.0})
      for (double offset : {0.05, 0.3})
        add("bead_ratio=" + shortNumber(r) + "_offset=" + shortNumber(offset), [&](Condition& c) {
          c.bead_ratio = r;
          c.offset_m = offset;
        });
    return list;
  }
  for (double r : {1.0, 1e2, 1e4, 1e6}) add("load_ratio=" + shortNumber(r), [&](Condition& c) { c.load_ratio = r; });
  for (double r : {1e-6, 1e-3, 1.0, 1e3, 1e6})
    add("wheel_ratio=" + shortNumber(r), [&](Condition& c) { c.wheel_ratio = r; });
  for (double a : {1e-4, 1e-2, 1.0})
    add("compliance=" + shortNumber(a), [&](Condition& c) { c.compliance_m_per_N = a; });
  for (double load : {1e4, 1e5}) add("load_N=" + shortNumber(load), [&](Condition& c) { c.load_N = load; });
  if (machine == "atwood")
    for (double slack : {1.0, 5.0})
      for (double speed : {10.0, 100.0})
        add("jerk_slack=" + shortNumber(slack) + "_speed=" + shortNumber(speed), [&](Condition& c) {
          c.slack_m = slack;
          c.speed_m_per_s = speed;
        });
  return list;
}

std::string cellKey(const Condition& c, const CellBudget& b) {
  return c.machine + "/" + c.name + "/" + shortNumber(b.rate_hz) + "Hz/" + std::to_string(b.substeps) + "x" +
         std::to_string(b.iterations) + "/" + solverMethodName(b.solver);
}

CellResult runCell(const Condition& c, const CellBudget& b) {
  CellResult r;
  try {
    Rig rig = c.machine == "atwood" ? atwoodRig(c, b) : c.machine == "bead" ? beadRig(c, b) : simpleRig(c, b);
    Scene& s = rig.scene;
    const double total_length = s.cables->totalLength(0);
    const double static_strain =
        rig.tensions.empty() ? 0.0
                             : c.compliance_m_per_N * *std::max_element(rig.tensions.begin(), rig.tensions.end()) /
                                   total_length;
    r.stretch_limit = 0.01 + 2.0 * static_strain;  // a load applied at once overshoots to twice
    double weight = 0.0;
    for (BodyId id = 0; id < s.world->bodyCount(); ++id) weight += s.world->bodyMass(id);
    weight *= s.world->settings().gravity.norm();
    const double e0 = energy(s);
    double e_max = e0, kinetic_max = kineticEnergy(*s.world);
    const int frames = std::max(1, static_cast<int>(std::ceil(rig.seconds * b.rate_hz - 1e-9)));
    r.finite = true;
    for (int f = 0; f < frames; ++f) {
      s.world->step(1.0 / b.rate_hz);
      if (s.world->firstNonFiniteBody()) {
        r.finite = false;
        break;
      }
      if (const auto& broken = s.cables->firstBreach()) {  // checked after every substep's update
        r.bookkeeping = broken->what;
        break;
      }
      for (int cable = 0; cable < static_cast<int>(s.cables->cables().size()); ++cable)
        r.peak_stretch = std::max(r.peak_stretch, machines::maxStretch(*s.cables, cable));
      for (HingeId h = 0; h < static_cast<HingeId>(s.world->hinges().size()); ++h)
        r.axle_offset = std::max(r.axle_offset, machines::axleOffset(*s.world, h));
      e_max = std::max(e_max, energy(s));
      kinetic_max = std::max(kinetic_max, kineticEnergy(*s.world));
    }
    r.finished = true;
    if (r.finite) {
      r.energy_growth = (e_max - e0) / (kinetic_max + 0.01 * weight);
      if (!rig.tensions.empty()) {
        r.tension_error = 0.0;
        for (std::size_t j = 0; j < rig.tensions.size(); ++j)
          r.tension_error = std::max(r.tension_error, std::abs(s.cables->tension(0, static_cast<int>(j)) - rig.tensions[j]) /
                                                          rig.tensions[j]);
      }
      if (rig.speed_after_snap > 0.0) {  // both boxes: the light one must not outrun the cable
        const double down = -s.world->body(rig.heavy).v.y(), up = s.world->body(rig.light).v.y();
        r.speed_error = std::max(std::abs(down - rig.speed_after_snap), std::abs(up - rig.speed_after_snap)) /
                        rig.speed_after_snap;
      }
    }
  } catch (const std::exception& e) {
    r.cause = std::string("exception: ") + e.what();
    return r;
  }
  if (!r.bookkeeping.empty()) {
    r.cause = "cable bookkeeping broken: " + r.bookkeeping;
    return r;
  }
  char why[96] = "";
  if (!r.finite)
    std::snprintf(why, sizeof why, "non-finite state");
  else if (!(r.peak_stretch <= r.stretch_limit))
    std::snprintf(why, sizeof why, "stretch %.3g > %.3g", r.peak_stretch, r.stretch_limit);
  else if (!(r.energy_growth <= 0.01))
    std::snprintf(why, sizeof why, "energy grew %.3g", r.energy_growth);
  r.cause = why;
  return r;
}

}  // namespace reeve::bench
