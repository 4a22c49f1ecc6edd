// The machines `reeve bench scaling` times as their count K grows
// (machines.h, "The series of reeve bench scaling"): each stands still, so
// every span's tension has one closed form.
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "common.h"

namespace reeve::machines {
namespace {

constexpr double kSheaveRadius = 0.1;  // m, sheaves, octagons and wound wheels
constexpr double kTackleDrop = 2.0;    // m from the upper sheaves' axles down to the lower ones'

// Where the K falls of a tackle run: K - 1 sheaves 2 r apart in x, the last
// one on the lower block and the others alternating before it; the cable is
// tied at x = -r to the block opposite sheave 0 and ends on the upper block
// at the last sheave's right side.
struct TackleLayout {
  int sheaves = 0;
  bool lower(int i) const { return (sheaves - 1 - i) % 2 == 0; }
  Vec3 centre(int i) const { return {2.0 * kSheaveRadius * i, lower(i) ? -kTackleDrop : 0.0, 0.0}; }
  bool tiedToLower() const { return !lower(0); }
  Vec3 tie() const { return {-kSheaveRadius, tiedToLower() ? -kTackleDrop : 0.0, 0.0}; }
  Vec3 end() const { return {2.0 * kSheaveRadius * (sheaves - 1) + kSheaveRadius, 0.0, 0.0}; }
  // The falls' centre in x, where the lower block's weight must act for it
  // not to tip: the falls stand at -r, r, 3r, ..., (2 sheaves - 1) r.
  double fallsCentre() const { return kSheaveRadius * (sheaves - 1); }
};

TackleLayout tackleLayout(const ScalingSpec& spec, const char* name) {
  if (spec.count < 2) throw std::invalid_argument(std::string(name) + ": needs at least 2 falls");
  return {spec.count - 1};
}

// The static upper block spanning the layout at y = 0.25, and the lower
// block of `kg` with its centre of mass at x = `x`, 0.3 m below the lower
// axles (it hangs like a pendulum, so it does not tip over).
std::pair<BodyId, BodyId> addTackleBlocks(World& world, const TackleLayout& layout, double kg, double x) {
  const double half_width = kSheaveRadius * (layout.sheaves + 1);
  BodyDef upper;
  upper.name = "upper_block";
  upper.is_static = true;
  upper.shape = Shape::box(Vec3(half_width, 0.1, 0.1));
  upper.position = Vec3(layout.fallsCentre(), 0.25, 0.0);
  const BodyId up = world.addBody(upper);
  const BodyId low = detail::addBox(world, "lower_block", Vec3(half_width, 0.1, 0.05), kg,
                                    Vec3(x, -kTackleDrop - 0.3, 0.0));
  return {up, low};
}

// A world point as a point of `body` (which has not been turned).
Vec3 local(const World& world, BodyId body, const Vec3& p) { return p - world.body(body).x; }

// A tackle's cable, "rope": tied to one block, round `interior`, ending on
// the upper block.
void addTackleRope(StaticMachine& m, const TackleLayout& layout, BodyId upper, BodyId lower,
                   std::vector<LinkDef> interior) {
  const World& world = *m.scene.world;
  const BodyId tied = layout.tiedToLower() ? lower : upper;
  CableDef cable;
  cable.name = "rope";
  cable.links = {LinkDef::attachment(tied, local(world, tied, layout.tie()))};
  cable.links.insert(cable.links.end(), interior.begin(), interior.end());
  cable.links.push_back(LinkDef::attachment(upper, local(world, upper, layout.end())));
  m.scene.cables->addCable(cable);
}

// An octagon of circumradius r about `centre` (m, body-local), with a
// vertex at each side so that vertical falls leave it where they leave a
// circle of radius r.
Section octagon(const Vec3& centre) {
  std::vector<Vec2> points;
  for (int j = 0; j < 8; ++j) {
    const double a = std::numbers::pi * j / 4.0;
    points.emplace_back(centre.x() + kSheaveRadius * std::cos(a), centre.y() + kSheaveRadius * std::sin(a));
  }
  return Section::polygon(points);
}

// A frictionless wrap: the cable slides round `body` with equal tensions.
LinkDef slidingWrap(BodyId body, int orientation) {
  LinkDef link = LinkDef::rolling(body, orientation);
  link.mu = 0.0;
  return link;
}

// A tackle's empty scene, every fall to carry m g (the lower block weighs
// K m with its sheaves).
StaticMachine tackleScene(const ScalingSpec& spec, const std::string& name, const std::string& description) {
  StaticMachine m{detail::emptyScene(name + " (generated)", spec.gravity, spec.budget), spec.load_kg * spec.gravity};
  m.scene.description = description + " (reeve/machines/machines.h).";
  return m;
}

}  // namespace

StaticMachine scalingChain(const ScalingSpec& spec) {
  ZigZagSpec z;
  z.wheels = spec.count;
  z.light_kg = z.heavy_kg = spec.load_kg;
  z.gravity = spec.gravity;
  z.budget = spec.budget;
  return {std::move(zigzag(z).scene), spec.load_kg * spec.gravity};
}

StaticMachine tackleHinged(const ScalingSpec& spec) {
  const TackleLayout layout = tackleLayout(spec, "tackleHinged");
  StaticMachine m = tackleScene(spec, "tackle_hinged", "A K-fall block and tackle on hinged sheaves");
  World& world = *m.scene.world;
  const double weight_kg = spec.count * spec.load_kg, sheave_kg = 0.01 * spec.load_kg;
  // The block's own centre of mass is placed so that, with its sheaves,
  // the whole hangs under the falls' centre.
  double sheaves_kg = 0.0, sheaves_moment = 0.0;
  for (int i = 0; i < layout.sheaves; ++i)
    if (layout.lower(i)) {
      sheaves_kg += sheave_kg;
      sheaves_moment += sheave_kg * layout.centre(i).x();
    }
  const double block_kg = weight_kg - sheaves_kg;
  const auto [upper, lower] =
      addTackleBlocks(world, layout, block_kg, (weight_kg * layout.fallsCentre() - sheaves_moment) / block_kg);
  std::vector<LinkDef> wraps;
  for (int i = 0; i < layout.sheaves; ++i) {
    const Vec3 at = layout.centre(i);
    const BodyId block = layout.lower(i) ? lower : upper;
    const BodyId sheave = detail::addWheel(world, "sheave" + std::to_string(i), kSheaveRadius, sheave_kg, at);
    world.addHinge({sheave, block, at, Vec3::UnitZ()});
    wraps.push_back(LinkDef::rolling(sheave, layout.lower(i) ? 1 : -1));  // under lower ones, over upper ones
  }
  addTackleRope(m, layout, upper, lower, wraps);
  return m;
}

StaticMachine tackleRolling(const ScalingSpec& spec, bool sliding) {
  const TackleLayout layout = tackleLayout(spec, "tackleRolling");
  StaticMachine m = tackleScene(spec, sliding ? "tackle_rolling" : "tackle_stuck",
                                "A K-fall block and tackle rolling on the blocks themselves");
  World& world = *m.scene.world;
  const auto [upper, lower] = addTackleBlocks(world, layout, spec.count * spec.load_kg, layout.fallsCentre());
  std::vector<LinkDef> wraps;
  for (int i = 0; i < layout.sheaves; ++i) {
    const BodyId block = layout.lower(i) ? lower : upper;
    LinkDef wrap = sliding ? slidingWrap(block, layout.lower(i) ? 1 : -1)
                           : LinkDef::rolling(block, layout.lower(i) ? 1 : -1);
    wrap.section = octagon(local(world, block, layout.centre(i)));
    wraps.push_back(wrap);
  }
  addTackleRope(m, layout, upper, lower, wraps);
  return m;
}

StaticMachine star(const ScalingSpec& spec, bool compliant) {
  if (spec.count < 1) throw std::invalid_argument("star: needs at least 1 cable");
  const double theta = std::numbers::pi / 6.0, length = 1.0, half = 0.05;
  const double tension = spec.load_kg * spec.gravity / std::cos(theta);
  StaticMachine m{detail::emptyScene(compliant ? "star_compliant (generated)" : "star_rigid (generated)",
                                     spec.gravity, spec.budget),
                  tension};
  m.scene.description = "An effector hung from K cables in a cone (reeve/machines/machines.h).";
  World& world = *m.scene.world;
  BodyDef frame;
  frame.name = "frame";
  frame.is_static = true;
  frame.shape = Shape::box(Vec3::Constant(half));
  const BodyId anchors = world.addBody(frame);
  const double drop = length * std::cos(theta), ring = length * std::sin(theta);
  const BodyId effector = detail::addBox(world, "effector", Vec3::Constant(half), spec.count * spec.load_kg,
                                         Vec3(0.0, -drop - half, 0.0));
  for (int k = 0; k < spec.count; ++k) {
    const double a = 2.0 * std::numbers::pi * k / spec.count;
    CableDef cable;
    cable.name = "cable" + std::to_string(k);
    cable.links = {LinkDef::attachment(anchors, Vec3(ring * std::cos(a), 0.0, ring * std::sin(a))),
                   LinkDef::attachment(effector, Vec3(0.0, half, 0.0))};
    if (compliant) {
      const double rest = length / 1.01;
      cable.rest_lengths = {rest};
      cable.compliance = (length - rest) / tension;
    }
    m.scene.cables->addCable(cable);
  }
  return m;
}

StaticMachine islands(const ScalingSpec& spec, bool braked) {
  if (spec.count < 1) throw std::invalid_argument("islands: needs at least 1 machine");
  StaticMachine m{detail::emptyScene("islands (generated)", spec.gravity, spec.budget), spec.load_kg * spec.gravity};
  m.scene.description = std::string("K separate balanced Atwood machines") + (braked ? ", each wheel braked" : "") +
                        " (reeve/machines/machines.h).";
  HingeDrive brake;
  if (braked) {
    brake.mode = HingeDrive::Mode::Angle;
    brake.max_torque = 1.0;
  }
  World& world = *m.scene.world;
  const double r = 0.3, box = 0.1, drop = 2.0;
  for (int k = 0; k < spec.count; ++k) {
    const std::string n = std::to_string(k);
    const Vec3 at(1.0 * k, 0.0, 0.0);
    const BodyId wheel = detail::addWheel(world, "wheel" + n, r, 2.0, at);
    world.addHinge({wheel, kWorldBody, at, Vec3::UnitZ(), 0.0, {}, brake});
    const BodyId left = detail::addBox(world, "left" + n, Vec3::Constant(box), spec.load_kg, at + Vec3(-r, -drop, 0.0));
    const BodyId right = detail::addBox(world, "right" + n, Vec3::Constant(box), spec.load_kg, at + Vec3(r, -drop, 0.0));
    CableDef cable;
    cable.name = "rope" + n;
    cable.links = {LinkDef::attachment(left, Vec3(0.0, box, 0.0)), LinkDef::rolling(wheel, -1),
                   LinkDef::attachment(right, Vec3(0.0, box, 0.0))};
    m.scene.cables->addCable(cable);
  }
  return m;
}

StaticMachine wound(const ScalingSpec& spec) {
  if (spec.count < 2 || spec.count % 2 != 0) throw std::invalid_argument("wound: needs an even number of wraps");
  StaticMachine m{detail::emptyScene("wound (generated)", spec.gravity, spec.budget), spec.load_kg * spec.gravity};
  m.scene.description = "One cable wound back and forth between two wheels (reeve/machines/machines.h).";
  World& world = *m.scene.world;
  const double r = kSheaveRadius, apart = 1.0, box = 0.05, drop = 2.0;
  BodyId wheels[2];
  for (int i = 0; i < 2; ++i) {
    const Vec3 at(apart * i, 0.0, 0.0);
    wheels[i] = detail::addWheel(world, i ? "second" : "first", r, 0.1, at);
    world.addHinge({wheels[i], kWorldBody, at, Vec3::UnitZ()});
  }
  const BodyId left = detail::addBox(world, "left", Vec3::Constant(box), spec.load_kg, Vec3(-r, -drop, 0.0));
  const BodyId right = detail::addBox(world, "right", Vec3::Constant(box), spec.load_kg, Vec3(apart + r, -drop, 0.0));
  CableDef cable;
  cable.name = "rope";
  cable.links.push_back(LinkDef::attachment(left, Vec3(0.0, box, 0.0)));
  // Clockwise round both: over the first to the second along the top, under
  // the second back along the bottom.
  for (int k = 0; k < spec.count; ++k) cable.links.push_back(slidingWrap(wheels[k % 2], -1));
  cable.links.push_back(LinkDef::attachment(right, Vec3(0.0, box, 0.0)));
  m.scene.cables->addCable(cable);
  return m;
}

StaticMachine threaded(const ScalingSpec& spec) {
  if (spec.count < 1) throw std::invalid_argument("threaded: needs at least 1 bar");
  constexpr double kPitch = 0.4, kHole = 0.1, kDrop = 2.0, kHalf = 0.05;  // m
  StaticMachine m{detail::emptyScene("threaded (generated)", spec.gravity, spec.budget), spec.load_kg * spec.gravity};
  m.scene.description = "One rope threaded through two holes of each of K bars (reeve/machines/machines.h).";
  World& world = *m.scene.world;
  const double last = kPitch * (spec.count - 1);
  BodyDef top;
  top.name = "upper_block";
  top.is_static = true;
  top.shape = Shape::box(Vec3(last / 2 + kPitch, 0.1, 0.1));
  top.position = Vec3(last / 2, 0.1, 0.0);
  const BodyId upper = world.addBody(top);
  // Its holes on hooks 5 cm below it: the rope between two of them clear
  // of its face, which it would otherwise lie on (and wrap, by rounding).
  const auto above = [&](double x) { return LinkDef::pinhole(upper, local(world, upper, Vec3(x, -kHalf, 0.0))); };
  CableDef cable;
  cable.name = "rope";
  cable.links.push_back(LinkDef::attachment(upper, local(world, upper, Vec3(-kHole, -kHalf, 0.0))));
  for (int k = 0; k < spec.count; ++k) {
    const double x = kPitch * k;
    const BodyId bar = detail::addBox(world, "bar" + std::to_string(k), Vec3(kHole + kHalf, kHalf, kHalf),
                                      2.0 * spec.load_kg, Vec3(x, -kDrop, 0.0));
    cable.links.push_back(LinkDef::pinhole(bar, Vec3(-kHole, kHalf, 0.0)));
    cable.links.push_back(LinkDef::pinhole(bar, Vec3(kHole, kHalf, 0.0)));
    cable.links.push_back(above(x + kHole));
    if (k + 1 < spec.count) cable.links.push_back(above(x + kPitch - kHole));
  }
  const BodyId load = detail::addBox(world, "load", Vec3::Constant(kHalf), spec.load_kg,
                                     Vec3(last + kHole, -kDrop, 0.0));
  cable.links.push_back(LinkDef::attachment(load, Vec3(0.0, kHalf, 0.0)));
  m.scene.cables->addCable(cable);
  return m;
}

}  // namespace reeve::machines
