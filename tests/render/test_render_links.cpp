// Rendered pixels of what the cable module's links and spans do: disabled
// joints, pinhole and hybrid markers, spool coils, loose spans, section
// outlines.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "atwood_rig.h"
#include "image_pixels.h"
#include "reeve/render/cable_path.h"
#include "reeve/render/renderer.h"
#include "rigs.h"

namespace reeve::test_render_links {
namespace {

using test::distance;
using test::pixel;
using test::projectToPixel;
using test::Rgb;

constexpr int kWidth = 640, kHeight = 360;

Renderer& renderer() {
  static Renderer r(kWidth, kHeight);
  return r;
}

// A frame of a rig and the camera it was seen through.
struct Frame {
  Camera camera;
  Image image;

  Eigen::Vector2d px(const Vec3& world) const {
    return projectToPixel(camera, world, kWidth, kHeight);
  }
  Rgb at(const Vec3& world) const { return test::pixelAt(image, px(world)); }
  Rgb background() const { return pixel(image, 1, 1); }
  // Pixels within [inner, outer] pixels of where `world` appears.
  template <class F>
  int countAround(const Vec3& world, double inner, double outer, F&& pred) const {
    const Eigen::Vector2d c = px(world);
    int n = 0;
    for (int y = int(c.y() - outer) - 1; y <= int(c.y() + outer) + 1; ++y)
      for (int x = int(c.x() - outer) - 1; x <= int(c.x() + outer) + 1; ++x) {
        const double r = (Eigen::Vector2d(x + 0.5, y + 0.5) - c).norm();
        if (r >= inner && r <= outer && x >= 0 && y >= 0 && x < kWidth && y < kHeight)
          n += pred(pixel(image, x, y));
      }
    return n;
  }
};

template <class R>
Frame shoot(const R& rig, const Camera* camera = nullptr) {
  Frame f;
  f.camera = camera ? *camera : frameScene(rig.world, rig.cables, double(kWidth) / kHeight);
  f.image = renderer().render(rig.world, rig.cables, f.camera);
  return f;
}

bool dark(const Rgb& p) { return p[0] < 80 && p[1] < 80 && p[2] < 80; }
bool reddish(const Rgb& p) { return p[0] > 140 && p[0] > p[1] + 70 && p[0] > p[2] + 70; }
bool greenish(const Rgb& p) { return p[1] > 110 && p[1] > p[0] + 50 && p[1] > p[2] + 50; }
bool bluish(const Rgb& p) { return p[2] > 150 && p[2] > p[0] + 70 && p[2] > p[1] + 40; }

TEST(RenderLinks, DisabledJointsAreNotDrawn) {
  test::InactiveLinkRig rig;
  ASSERT_FALSE(rig.cables.jointEnabled(rig.cable, 1));
  const Frame f = shoot(rig);
  // The enabled span is drawn...
  const Vec3 a = rig.cables.startPoint(rig.cable, 0), b = rig.cables.endPoint(rig.cable, 0);
  EXPECT_TRUE(dark(f.at(0.5 * (a + b))));
  // ...the disabled one, from the wheel (its stale anchors: the wheel's
  // and the right post's origins) to the right post, is not: wherever it
  // would run clear of the bodies the picture is light.
  const Vec3 p = rig.cables.startPoint(rig.cable, 1), q = rig.cables.endPoint(rig.cable, 1);
  for (double t = 0.25; t <= 0.85; t += 0.05) {
    const Rgb seen = f.at(p + t * (q - p));
    for (int c = 0; c < 3; ++c) EXPECT_GT(seen[c], 140) << "t = " << t;
  }
  // No red marker on the inactive wheel.
  const Rgb wheel = f.at(rig.world.body(rig.wheel).x);
  EXPECT_FALSE(reddish(wheel));
  EXPECT_EQ(f.countAround(rig.world.body(rig.wheel).x, 0.0, 60.0, reddish), 0);
}

TEST(RenderLinks, PinholeMarkerIsBlue) {
  test::PinholeRig rig;
  const Frame f = shoot(rig);
  EXPECT_TRUE(bluish(f.at(rig.hole))) << f.at(rig.hole)[0] << "," << f.at(rig.hole)[1] << ","
                                      << f.at(rig.hole)[2];
  // The ends are attachments: green.
  EXPECT_TRUE(greenish(f.at(rig.cables.startPoint(rig.cable, 0))));
  EXPECT_TRUE(greenish(f.at(rig.cables.endPoint(rig.cable, 1))));
}

TEST(RenderLinks, HybridMarkerIsRedWithAGreenRingRollingAndGreenWithARedRingTied) {
  test::SpoolRig rig(0.6);  // a hinged drum paying out 0.6 m, then tied
  {
    const Frame f = shoot(rig);
    const Vec3 at = rig.cables.startPoint(rig.cable, 0);
    EXPECT_TRUE(reddish(f.at(at)));
    // Ring: about 1.3 marker radii (2.3 x 2.5 px) out.
    EXPECT_GT(f.countAround(at, 6.5, 8.5, greenish), 30);
    EXPECT_EQ(f.countAround(at, 0.0, 3.0, greenish), 0);
  }
  for (int i = 0; i < 100 && !rig.cables.cables()[rig.cable].links[0].attached; ++i) rig.run(1);
  ASSERT_TRUE(rig.cables.cables()[rig.cable].links[0].attached);
  {
    const Frame f = shoot(rig);
    const Vec3 at = rig.cables.startPoint(rig.cable, 0);
    EXPECT_TRUE(greenish(f.at(at)));
    EXPECT_GT(f.countAround(at, 6.5, 8.5, reddish), 30);
    EXPECT_EQ(f.countAround(at, 0.0, 3.0, reddish), 0);
  }
}

// Of the directions from the drum's centre in its plane at `degrees`,
// how many show dark cable between 0.3 and 4 cable radii outside the drum.
int coilDirections(const Frame& f, const test::SpoolRig& rig,
                   const std::vector<double>& degrees) {
  const double pixel_m = 2.0 * (f.camera.target - f.camera.eye).norm() *
                         std::tan(f.camera.fov_y_deg * std::numbers::pi / 360.0) / kHeight;
  const double cable_m = 2.5 * pixel_m;
  const Vec3 centre = rig.world.body(rig.drum).x;
  int found = 0;
  for (double deg : degrees) {
    const double a = deg * std::numbers::pi / 180.0;
    bool any = false;
    for (double k = 0.3; k <= 4.0; k += 0.25) {
      const double r = test::SpoolRig::kRadius + k * cable_m;
      any |= dark(f.at(centre + Vec3(r * std::cos(a), r * std::sin(a), 0.0)));
    }
    found += any;
  }
  return found;
}

TEST(RenderLinks, SpoolShowsItsStoredCableAsACoil) {
  const test::SpoolRig full(4.0, LinkType::Rolling, false);  // 2.1 turns on a static drum
  const test::SpoolRig empty(0.0, LinkType::Rolling, false);
  const Frame with = shoot(full);
  const Frame without = shoot(empty, &with.camera);
  // Round the top and the left, away from the span leaving on the right
  // and from the bottom, where the drum's front rim hides the mid-plane.
  std::vector<double> degrees;
  for (double d = 30.0; d <= 210.0; d += 10.0) degrees.push_back(d);
  EXPECT_GE(coilDirections(with, full, degrees), int(0.9 * degrees.size()));
  EXPECT_EQ(coilDirections(without, empty, degrees), 0);
}

TEST(RenderLinks, LooseSpanHangsAndTautSpanIsStraight) {
  test::SlackRig rig(1.3);
  const Frame f = shoot(rig);
  const auto path = test::onePath(rig.cables, rig.cable, 0.05);
  Vec3 lowest = path.front();
  for (const Vec3& p : path)
    if (p.y() < lowest.y()) lowest = p;
  EXPECT_TRUE(dark(f.at(lowest)));
  EXPECT_FALSE(dark(f.at(0.5 * (rig.a + rig.b))));  // no straight chord
  // Pulled taut, it is the chord.
  rig.cables.setRestLength(rig.cable, 0, (rig.b - rig.a).norm());
  const Frame taut = shoot(rig, &f.camera);
  EXPECT_TRUE(dark(taut.at(0.5 * (rig.a + rig.b))));
  EXPECT_FALSE(dark(taut.at(lowest)));
}

TEST(RenderLinks, SectionTheBodyDoesNotShowIsOutlined) {
  // A thin axle carrying a larger square section: its corners, away from
  // the cable, are outlined in thin air.
  test::Rig rig;
  const BodyId axle = rig.addStatic(Shape::cylinder(0.04, 0.2), Vec3::Zero(), "axle");
  const BodyId box = rig.addDynamic(Shape::box(Vec3(0.1, 0.1, 0.1)), 1.0, Vec3(0.4, -1.0, 0));
  CableDef def;
  def.links = {test::rolling(axle, -1, boxSection(0.3, 0.3)),
               test::attachment(box, Vec3(0.0, 0.1, 0.0))};
  def.links[0].stored = 0.0;
  rig.cable = rig.cables.addCable(def);
  const Frame f = shoot(rig);
  const Vec3 corner(-0.3, -0.3, 0.0);  // bottom left: no cable there
  EXPECT_GT(distance(f.at(corner), f.background()), 60);
  const Vec3 edge_middle(-0.3, 0.0, 0.0);
  EXPECT_GT(distance(f.at(edge_middle), f.background()), 60);
  // A section the body shows is not outlined: the Atwood wheel's rim
  // below the cable shows the wheel's blue, not a dark line.
  test::AtwoodRig atwood;
  const Frame plain = shoot(atwood);
  const Vec3 bottom = atwood.world.body(atwood.wheel).x + Vec3(0.0, -0.29, 0.06);
  EXPECT_GT(plain.at(bottom)[2], 100);
}

TEST(RenderLinks, ABodySmallerThanAMarkerGetsARingInItsColourAndALargeOneDoesNot) {
  // A 1 cm ball in a 2.5 m scene is about 3 pixels across: a ring round it
  // in its warm grey (radius: its own, ~1.3 px, plus the marker's, 5.75 px,
  // times 1.6, plus a pixel: ~11.5 px; its tube ~2.8 px thick) keeps it in
  // sight.
  test::Rig rig;
  const Vec3 peg(0.0, 0.0, 0.0), box(1.5, -2.0, 0.0);
  rig.addStatic(Shape::sphere(0.01), peg, "peg");
  rig.addDynamic(Shape::box(Vec3(0.2, 0.2, 0.2)), 1.0, box);
  const Frame f = shoot(rig);
  const auto grey = [&](const Rgb& p) {
    return distance(p, f.background()) > 40 && std::abs(p[0] - p[2]) < 40 && std::abs(p[0] - p[1]) < 40;
  };
  const double band = 2.0 * std::numbers::pi * 11.5 * 4.0;  // pixels between 9.5 and 13.5 px
  EXPECT_GT(f.countAround(peg, 9.5, 13.5, grey), 0.6 * band);
  EXPECT_EQ(f.countAround(peg, 4.0, 7.0, grey), 0) << "the ring is hollow";
  // The box, 0.2 m half size, shows by itself: no blue ring round it.
  const double half_px = (f.px(box + Vec3(0.2, 0.0, 0.0)) - f.px(box)).norm();
  EXPECT_GT(half_px, 10.0);
  EXPECT_GT(f.countAround(box, 0.0, half_px, bluish), 100);
  EXPECT_EQ(f.countAround(box, 2.2 * half_px, 2.2 * half_px + 12.0, bluish), 0) << "past its corners";
}

}  // namespace
}  // namespace reeve::test_render_links
