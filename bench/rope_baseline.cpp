// The segmented-rope baseline (cable joints paper, sec. 5 and Fig. 14):
// the Atwood machine with its rope as one cable (scenes/atwood.json: two
// cable joints) and as 100 rigid cylinders on spherical joints resting on
// the wheel through contacts (scenes/rope_segments.json, made by
// `reeve segment scenes/atwood.json --cable rope --segments 100`), run for
// 1 s at equal solver budgets (substeps x iterations). Prints one table;
// nothing here passes or fails.
//
// Columns:
//   ms/frame   median over 3 runs of the physics step per frame
//   stretch    cable: max over frames and spans of (length - rest) / rest;
//              segments: max over frames of (sum over the chain's spherical
//              joints of the distance between their two anchors) / L0, the
//              growth of the chain's end-to-end length along the rope (the
//              segments are rigid, so only the joints can open), L0 the
//              chain's initial length (= the cable's total length)
//   a err      heavy box: a = 2 (y0 - y(1 s)) / (1 s)^2 against
//              (m2 - m1) g / (m1 + m2 + m_rope + M/2): the rope's mass is
//              counted as moving with the boxes; the imbalance of its
//              hanging parts (a few mm of rope per cm moved) is ignored
//              (< 0.4 % here)
//   off        max horizontal distance (m) of the heavy box from its
//              straight-down path; "FELL OFF" beyond 0.2 m, or (segments)
//              when no segment touches the wheel in the last substep
//   contacts   rope-wheel contact points in the last substep (segments)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "reeve/scene/scene.h"

namespace {

struct Result {
  double ms = 0, stretch = 0, a = 0, off = 0;
  int contacts = 0;
  bool finite = true;
};

// Body-local anchors of a spherical joint.
std::pair<reeve::Vec3, reeve::Vec3> anchors(const reeve::SphericalJoint& j) {
  return {j.frame.anchor_a, j.frame.anchor_b};
}

bool isSegment(const reeve::World& w, reeve::BodyId id) {
  return id >= 0 && w.bodyDef(id).name.rfind("rope_seg_", 0) == 0;
}

Result runOnce(const std::string& file, int substeps, int iterations) {
  reeve::Scene s = reeve::loadScene(file);
  reeve::World& w = *s.world;
  w.settings().substeps = substeps;
  w.settings().iterations = iterations;
  const reeve::BodyId heavy = *w.findBody("heavy");
  const reeve::BodyId wheel = *w.findBody("wheel");
  const reeve::Vec3 x0 = w.body(heavy).x;
  const bool cable = !s.cables->cables().empty();
  double l0 = 0.0;
  if (cable) {
    l0 = s.cables->totalLength(0);
  } else {
    // Anchors of consecutive chain joints: the chain's vertices.
    reeve::Vec3 prev;
    bool first = true;
    for (const reeve::SphericalJoint& j : w.sphericals()) {
      if (!isSegment(w, j.a) && !isSegment(w, j.b)) continue;
      const reeve::Vec3 p = w.body(j.a).toWorld(anchors(j).first);
      if (!first) l0 += (p - prev).norm();
      prev = p;
      first = false;
    }
  }
  Result r;
  const double dt = 1.0 / s.frame_rate_hz;
  const int frames = static_cast<int>(std::lround(1.0 * s.frame_rate_hz));
  double stepping = 0.0;
  for (int f = 0; f < frames; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    w.step(dt);
    stepping += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (w.firstNonFiniteBody()) {
      r.finite = false;
      break;
    }
    if (cable) {
      for (std::size_t j = 0; j < s.cables->cables()[0].joints.size(); ++j) {
        const double rest = s.cables->restLength(0, static_cast<int>(j));
        if (rest > 0) r.stretch = std::max(r.stretch, (s.cables->length(0, static_cast<int>(j)) - rest) / rest);
      }
    } else {
      double gaps = 0.0;
      for (const reeve::SphericalJoint& j : w.sphericals())
        if (isSegment(w, j.a) || isSegment(w, j.b))
          gaps += (w.body(j.a).toWorld(anchors(j).first) - w.body(j.b).toWorld(anchors(j).second)).norm();
      r.stretch = std::max(r.stretch, gaps / l0);
    }
    const reeve::Vec3 d = w.body(heavy).x - x0;
    r.off = std::max(r.off, std::hypot(d.x(), d.z()));
  }
  r.ms = 1e3 * stepping / frames;
  r.a = 2.0 * (x0.y() - w.body(heavy).x.y()) / 1.0;
  for (const reeve::Contact& c : w.contacts())
    if ((c.a == wheel && isSegment(w, c.b)) || (c.b == wheel && isSegment(w, c.a))) ++r.contacts;
  return r;
}

Result run(const std::string& file, int substeps, int iterations) {
  std::vector<Result> rs;
  for (int k = 0; k < 3; ++k) rs.push_back(runOnce(file, substeps, iterations));
  std::sort(rs.begin(), rs.end(), [](const Result& a, const Result& b) { return a.ms < b.ms; });
  return rs[1];
}

double ropeMass(const std::string& file) {
  reeve::Scene s = reeve::loadScene(file);
  double m = 0.0;
  for (reeve::BodyId id = 0; id < s.world->bodyCount(); ++id)
    if (isSegment(*s.world, id)) m += s.world->bodyMass(id);
  return m;
}

std::string offText(const Result& r, bool segments) {
  if (!r.finite) return "NaN";
  char buf[32];
  const bool fell = r.off > 0.2 || (segments && r.contacts == 0);
  std::snprintf(buf, sizeof buf, "%.3f%s", r.off, fell ? " FELL OFF" : "");
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : REEVE_SCENES_DIR;
  const std::string cable_file = dir + "/atwood.json", seg_file = dir + "/rope_segments.json";
  const double m1 = 1.0, m2 = 2.0, M = 2.0, g = 9.81;
  const double m_rope = ropeMass(seg_file);
  const double a_cable = (m2 - m1) * g / (m1 + m2 + 0.5 * M);
  const double a_seg = (m2 - m1) * g / (m1 + m2 + m_rope + 0.5 * M);
  std::printf("Atwood machine, 1 s: cable (2 cable joints) vs %s (rope %.3g kg)\n", seg_file.c_str(), m_rope);
  std::printf("analytic a: cable %.4f m/s^2, segmented %.4f m/s^2\n\n", a_cable, a_seg);
  std::printf("%-9s | %9s %10s %9s %7s | %9s %10s %9s %15s %8s\n", "sub x it", "cable ms", "stretch", "a err",
              "off m", "segs ms", "stretch", "a err", "off m", "contacts");
  const int budgets[][2] = {{10, 2}, {1, 20}, {20, 5}, {1, 100}};
  for (const auto& b : budgets) {
    const Result c = run(cable_file, b[0], b[1]);
    const Result s = run(seg_file, b[0], b[1]);
    char setting[16];
    std::snprintf(setting, sizeof setting, "%d x %d", b[0], b[1]);
    std::printf("%-9s | %9.4f %10.2e %8.2f%% %7s | %9.3f %10.2e %8.1f%% %15s %8d\n", setting, c.ms, c.stretch,
                100.0 * (c.a - a_cable) / a_cable, offText(c, false).c_str(), s.ms, s.stretch,
                100.0 * (s.a - a_seg) / a_seg, offText(s, true).c_str(), s.contacts);
  }
  return 0;
}
