#include <gtest/gtest.h>

#include <png.h>

#include "reeve/render/image.h"
#include "temp_dir.h"

namespace reeve::test_png {
namespace {

Image gradient(int width, int height) {
  Image image{width, height, std::vector<std::uint8_t>(3 * width * height)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = &image.rgb[3 * (y * width + x)];
      p[0] = static_cast<std::uint8_t>(x * 7), p[1] = static_cast<std::uint8_t>(y * 13);
      p[2] = static_cast<std::uint8_t>((x ^ y) * 3);
    }
  return image;
}

Image readPng(const std::filesystem::path& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) throw std::runtime_error(png.message);
  png.format = PNG_FORMAT_RGB;
  Image image{int(png.width), int(png.height), std::vector<std::uint8_t>(PNG_IMAGE_SIZE(png))};
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr))
    throw std::runtime_error(png.message);
  return image;
}

TEST(WritePng, ReadsBackIdenticalPixels) {
  test::TempDir dir;
  const Image image = gradient(97, 41);  // odd sizes: no row padding assumptions
  writePng(dir.path() / "gradient.png", image);
  const Image back = readPng(dir.path() / "gradient.png");
  EXPECT_EQ(back.width, image.width);
  EXPECT_EQ(back.height, image.height);
  EXPECT_TRUE(back.rgb == image.rgb);
}

TEST(WritePng, MissingDirectoryThrowsNamingThePath) {
  test::TempDir dir;
  const auto path = dir.path() / "no_such_dir" / "frame.png";
  try {
    writePng(path, gradient(4, 4));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file"), std::string::npos) << e.what();
  }
}

TEST(WritePng, InconsistentImageIsRejected) {
  test::TempDir dir;
  Image image = gradient(4, 4);
  image.rgb.pop_back();
  EXPECT_THROW(writePng(dir.path() / "bad.png", image), std::invalid_argument);
  EXPECT_THROW(writePng(dir.path() / "empty.png", Image{}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "bad.png"));
}

}  // namespace
}  // namespace reeve::test_png
