// A scene's bodies as written may overlap by the rounding of their poses:
// `contacts.json`'s slider, on a 35 degree ramp, written to 0.1 mm, lay
// 31 um into it. The first substep's contact sweep pushed that out, and
// v = dx / h made it a speed: 31 um / h, 1.9 m/s at 1000 substeps a frame
// (3.7 J on 2 kg), 0.19 m/s at 100, the finer the substeps the faster
// (DESIGN, "Forty-fourth session"). Before the first substep the overlaps
// are pushed out along the contacts' normals as poses alone: the first
// integration starts from the poses as moved, and no body gains a speed.
// (Done at a scene's load instead, it pushed an MJCF model's touching
// geoms apart before its poses were read: 0.26 rad.)
#include <algorithm>

#include "reeve/engine/correction.h"
#include "reeve/engine/world.h"

namespace reeve {
namespace {

constexpr int kOverlapSweeps = 64;  // a stack's overlaps reach its bottom in as many sweeps as it is tall
// m: an overlap this shallow is left, so that bodies placed touching to
// rounding start on their bits as before (a stack on a ramp at 1 x 10,
// its stick and slip decided substep by substep, slid 0.5 % faster from
// poses moved by 1e-17 m); at a thousand substeps a frame it would make
// 6e-5 m/s.
constexpr double kOverlapLeft = 1e-9;

}  // namespace

void World::settleInitialOverlaps() {
  if (overlaps_settled_) return;
  overlaps_settled_ = true;
  if (!hasContacts()) return;
  findContacts();
  // What the scene placed, for the run to say (placedOverlaps()).
  for (const Contact& c : contacts_) {
    const double C = ((body(c.b).x + body(c.b).q * c.local_b) - (body(c.a).x + body(c.a).q * c.local_a)).dot(c.normal);
    if (!(C < -kOverlapLeft)) continue;
    const auto same = [&](const PlacedOverlap& o) { return o.a == c.a && o.b == c.b; };
    const auto found = std::find_if(placed_overlaps_.begin(), placed_overlaps_.end(), same);
    if (found == placed_overlaps_.end()) placed_overlaps_.push_back({c.a, c.b, -C});
    else found->depth_m = std::max(found->depth_m, -C);
  }
  std::sort(placed_overlaps_.begin(), placed_overlaps_.end(),
            [](const PlacedOverlap& p, const PlacedOverlap& q) { return p.depth_m > q.depth_m; });
  for (int sweep = 0; sweep < kOverlapSweeps; ++sweep) {
    double deepest = 0.0;
    for (const Contact& c : contacts_) {
      // The contact's normal row (contact.cpp): C = (p_b - p_a) . n, pushed
      // to 0 where negative.
      BodyState &a = body(c.a), &b = body(c.b);
      const Vec3 r_a = a.q * c.local_a, r_b = b.q * c.local_b;
      const double C = ((b.x + r_b) - (a.x + r_a)).dot(c.normal);
      if (!(C < -kOverlapLeft)) continue;
      const double dl = positionalDeltaLambda(a, b, r_a, r_b, c.normal, C, 0.0, 0.0);
      if (!(dl > 0.0)) continue;
      applyPositionalImpulse(a, b, r_a, r_b, dl * c.normal);
      deepest = std::max(deepest, -C);
    }
    if (deepest == 0.0) break;
  }
  // Found again where the first substep's integration leaves the bodies;
  // no friction anchor or impulse is carried from here.
  contacts_.clear();
  manifolds_.clear();
  previous_manifolds_.clear();
  for (BodyState& b : bodies_) b.impulse = b.angular_impulse = b.solve_turn = Vec3::Zero();
}

}  // namespace reeve
