// Frames of the test rigs for a person to look at, and the time a frame
// takes: written only when REEVE_RENDER_GALLERY names a directory, e.g.
//   REEVE_RENDER_GALLERY=/tmp/gallery ./reeve_render_tests --gtest_filter='Gallery*'
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <numbers>
#include <vector>

#include "atwood_rig.h"
#include "reeve/render/renderer.h"
#include "rigs.h"

namespace reeve::test_gallery {
namespace {

std::filesystem::path galleryDir() {
  const char* dir = std::getenv("REEVE_RENDER_GALLERY");
  return dir ? std::filesystem::path(dir) : std::filesystem::path();
}

// Renders `frames` frames `every` physics frames apart, writing
// <name>_<k>.png; prints the mean render time.
template <class R>
void shoot(Renderer& renderer, R& rig, const std::string& name, int frames, int every) {
  const std::filesystem::path dir = galleryDir();
  const Camera camera =
      frameScene(rig.world, rig.cables, double(renderer.width()) / renderer.height());
  double seconds = 0.0;
  for (int k = 0; k < frames; ++k) {
    if (k > 0) rig.run(every);
    const auto t0 = std::chrono::steady_clock::now();
    const Image image = renderer.render(rig.world, rig.cables, camera);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    char file[64];
    std::snprintf(file, sizeof file, "%s_%02d.png", name.c_str(), k);
    writePng(dir / file, image);
  }
  std::printf("%-14s %6.1f ms/frame (%dx%d)\n", name.c_str(), 1e3 * seconds / frames,
              renderer.width(), renderer.height());
}

TEST(Gallery, WritesFramesOfEveryRig) {
  if (galleryDir().empty()) GTEST_SKIP() << "set REEVE_RENDER_GALLERY to a directory";
  std::filesystem::create_directories(galleryDir());
  Renderer renderer(1280, 720);
  {
    test::AtwoodRig rig;
    shoot(renderer, rig, "atwood", 3, 20);
  }
  {
    test::SquareWheelRig rig;
    shoot(renderer, rig, "square_wheel", 4, 15);
  }
  {
    test::PinholeRig rig;
    shoot(renderer, rig, "pinhole", 4, 15);
  }
  {
    test::SpoolRig rig(6.0);
    shoot(renderer, rig, "spool", 8, 12);
  }
  {
    // A square section on a round drum: the outline shows the square.
    test::SpoolRig rig(2.0, LinkType::Hybrid, true, boxSection(0.2, 0.2));
    shoot(renderer, rig, "square_spool", 4, 15);
  }
  {
    test::SlackRig rig(1.3);
    shoot(renderer, rig, "slack", 1, 1);
  }
  {
    test::InactiveLinkRig rig;
    shoot(renderer, rig, "inactive", 1, 1);
  }
  {
    test::BeltRig rig;
    shoot(renderer, rig, "belt", 1, 1);
  }
  {
    test::SpoolRig rig(40.0);  // more than kMaxCoilTurns
    shoot(renderer, rig, "big_spool", 1, 1);
  }
  {
    // A cable over a thin axle whose cable plane holds a hexagon larger
    // than the axle (thin air but for the outline); the left span loose.
    test::Rig rig;
    const BodyId axle = rig.addStatic(Shape::cylinder(0.05, 0.3), Vec3::Zero(), "axle");
    const BodyId left = rig.addDynamic(Shape::box(Vec3(0.1, 0.1, 0.1)), 1.0, Vec3(-0.3, -0.9, 0));
    const BodyId right = rig.addDynamic(Shape::box(Vec3(0.1, 0.1, 0.1)), 1.2, Vec3(0.3, -0.9, 0));
    std::vector<Vec2> hexagon;
    for (int i = 0; i < 6; ++i)
      hexagon.emplace_back(0.3 * std::cos(i * std::numbers::pi / 3.0 + 0.2),
                           0.3 * std::sin(i * std::numbers::pi / 3.0 + 0.2));
    CableDef def;
    LinkDef over = test::rolling(axle, -1, Section::polygon(hexagon));
    over.plane_offset = 0.1;
    def.links = {test::attachment(left, Vec3(0, 0.1, 0)), over,
                 test::attachment(right, Vec3(0, 0.1, 0))};
    rig.cable = rig.cables.addCable(def);
    rig.cables.setRestLength(rig.cable, 0, rig.cables.restLength(rig.cable, 0) + 0.4);
    shoot(renderer, rig, "hexagon_slack", 4, 10);
  }
}

}  // namespace
}  // namespace reeve::test_gallery
