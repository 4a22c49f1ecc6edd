#include <gtest/gtest.h>

#include <numbers>
#include <set>

#include "atwood_rig.h"
#include "image_pixels.h"
#include "reeve/render/renderer.h"

namespace reeve::test_renderer {
namespace {

using test::AtwoodRig;
using test::distance;
using test::pixel;
using test::pixelAt;
using test::projectToPixel;
using test::Rgb;

constexpr int kWidth = 1280, kHeight = 720;

// One context and one rendered frame of the rig (in motion for half a
// second), shared by the tests below.
class RenderedAtwood : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    renderer_ = new Renderer(kWidth, kHeight);
    rig_ = new AtwoodRig;
    rig_->run(30);
    camera_ = frameScene(rig_->world, rig_->cables, double(kWidth) / kHeight);
    image_ = new Image(renderer_->render(rig_->world, rig_->cables, camera_));
  }
  static void TearDownTestSuite() {
    delete image_;
    delete rig_;
    delete renderer_;
  }
  static Rgb at(const Vec3& world) {
    return pixelAt(*image_, projectToPixel(camera_, world, kWidth, kHeight));
  }
  static Rgb background() { return pixel(*image_, 1, 1); }  // top-left corner

  static Renderer* renderer_;
  static AtwoodRig* rig_;
  static Camera camera_;
  static Image* image_;
};

Renderer* RenderedAtwood::renderer_ = nullptr;
AtwoodRig* RenderedAtwood::rig_ = nullptr;
Camera RenderedAtwood::camera_;
Image* RenderedAtwood::image_ = nullptr;

TEST_F(RenderedAtwood, ImageIs1280x720AndNotBlank) {
  EXPECT_EQ(image_->width, kWidth);
  EXPECT_EQ(image_->height, kHeight);
  ASSERT_EQ(image_->rgb.size(), 3u * kWidth * kHeight);
  std::set<int> colours;
  int background_pixels = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const Rgb p = pixel(*image_, x, y);
      colours.insert((p[0] << 16) | (p[1] << 8) | p[2]);
      background_pixels += p == background();
    }
  EXPECT_GT(colours.size(), 300u);
  EXPECT_LT(background_pixels, 0.9 * kWidth * kHeight);
  EXPECT_GT(background_pixels, 0.2 * kWidth * kHeight);
}

TEST_F(RenderedAtwood, BackgroundIsLightGreyInTheCorners) {
  for (const Rgb p : {pixel(*image_, 1, 1), pixel(*image_, kWidth - 2, 1)}) {
    for (int c = 0; c < 3; ++c) EXPECT_GT(p[c], 215);
    EXPECT_LT(distance(p, {p[0], p[0], p[0]}), 12);  // grey
  }
}

TEST_F(RenderedAtwood, BodiesCoverTheirProjectedCentres) {
  const World& w = rig_->world;
  for (BodyId id : {rig_->wheel, rig_->light_box, rig_->heavy_box, rig_->beam})
    EXPECT_GT(distance(at(w.body(id).x), background()), 60) << w.bodyDef(id).name << id;
  const Rgb box = at(w.body(rig_->heavy_box).x);
  EXPECT_GT(box[2], box[0] + 40);  // dynamic: blue
  const Rgb beam = at(w.body(rig_->beam).x);
  EXPECT_GE(beam[0], beam[2]);  // static: warm grey
}

TEST_F(RenderedAtwood, StraightSpansAreDarkCable) {
  for (int j = 0; j < 2; ++j) {
    const Vec3 mid = 0.5 * (rig_->cables.startPoint(rig_->cable, j) +
                            rig_->cables.endPoint(rig_->cable, j));
    const Rgb p = at(mid);
    for (int c = 0; c < 3; ++c) EXPECT_LT(p[c], 70) << "span " << j;
  }
}

TEST_F(RenderedAtwood, EdgesAreAntiAliased) {
  // Along the lower silhouette of the wheel (its front cap's rim, where no
  // cable runs), pixels are partly covered: lighter than the blue cap,
  // darker than the background.
  const BodyState& wheel = rig_->world.body(rig_->wheel);
  int samples = 0, partial = 0;
  for (double deg = 200.0; deg <= 340.0; deg += 2.0, ++samples) {
    const double a = deg * std::numbers::pi / 180.0;
    const Vec3 rim(AtwoodRig::kRadius * std::cos(a), AtwoodRig::kRadius * std::sin(a), 0.06);
    const Rgb p = at(wheel.x + rim);  // the cap does not turn out of its plane
    partial += p[1] > 125 && p[1] < background()[1] - 15;
  }
  EXPECT_GT(partial, samples / 4) << partial << " of " << samples;
}

TEST_F(RenderedAtwood, CableWrapsOverTheTopOfTheWheel) {
  // The top of the wheel's circle in its cable plane: on the arc, seen
  // from slightly above past the front cap.
  const Rgb top = at(rig_->world.body(rig_->wheel).x + Vec3(0.0, AtwoodRig::kRadius, 0.0));
  for (int c = 0; c < 3; ++c) EXPECT_LT(top[c], 70);
}

TEST_F(RenderedAtwood, LinkMarkersInThePapersColours) {
  const Rgb rolling = at(rig_->cables.startPoint(rig_->cable, 1));  // leaves the wheel
  EXPECT_GT(rolling[0], 150);
  EXPECT_GT(rolling[0], rolling[1] + 80);
  EXPECT_GT(rolling[0], rolling[2] + 80);
  const Rgb attachment = at(rig_->cables.endPoint(rig_->cable, 1));  // on the heavy box
  EXPECT_GT(attachment[1], attachment[0] + 60);
  EXPECT_GT(attachment[1], attachment[2] + 60);
}

TEST_F(RenderedAtwood, GroundGridIsDrawnBelowTheBodies) {
  // The bottom row crosses the floor: a fill lighter than the background,
  // ruled by darker grid lines.
  const int y = kHeight - 3;
  int lines = 0, fill = 0;
  bool on_line = false;
  for (int x = 0; x < kWidth; ++x) {
    const int g = pixel(*image_, x, y)[1];
    fill += g > background()[1] + 4;
    const bool dark = g < background()[1] - 20;
    lines += dark && !on_line;
    on_line = dark;
  }
  EXPECT_GT(fill, kWidth / 4);
  EXPECT_GE(lines, 5);
}

TEST_F(RenderedAtwood, RenderingAgainGivesTheSameImage) {
  // No GL state leaks from one frame into the next.
  const Image again = renderer_->render(rig_->world, rig_->cables, camera_);
  EXPECT_TRUE(again.rgb == image_->rgb);
}

TEST(Renderer, RejectsAnEmptyImageSize) {
  EXPECT_THROW(Renderer(0, 720), std::invalid_argument);
  EXPECT_THROW(Renderer(1280, -1), std::invalid_argument);
}

TEST(Renderer, ImagesBeyondOsmesaLimitsThrowAndWideOnesAreDrawnInFull) {
  EXPECT_THROW(Renderer(20000, 10), std::runtime_error);
  // 6000 x 3 supersamples would pass OSMesa's 16384 limit, which clips
  // drawing without an error: the renderer must sample less, not clip.
  // A wall in front of a narrow camera fills the whole image.
  World world;
  CableSystem cables(world);
  BodyDef wall;
  wall.shape = Shape::box(Vec3(100.0, 100.0, 0.1));
  wall.is_static = true;
  world.addBody(wall);
  Renderer renderer(6000, 8);
  Camera narrow;
  narrow.fov_y_deg = 0.1;  // 0.1 x 750 wide
  const Image image = renderer.render(world, cables, narrow);
  const Rgb left = pixel(image, 0, 4), right = pixel(image, 5999, 4);
  EXPECT_EQ(left, right);
  EXPECT_LT(left[2], 200);  // the wall, not the light background
}

TEST(Renderer, RendersAnEmptyWorld) {
  World world;
  CableSystem cables(world);
  Renderer renderer(64, 48);
  const Image image = renderer.render(world, cables, Camera());
  EXPECT_EQ(image.width, 64);
  EXPECT_EQ(image.height, 48);
  EXPECT_EQ(image.rgb.size(), 64u * 48 * 3);
}

}  // namespace
}  // namespace reeve::test_renderer
