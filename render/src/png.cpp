#include <algorithm>
#include <stdexcept>
#include <string>

#include <png.h>

#include "reeve/render/image.h"

namespace reeve {

void writePng(const std::filesystem::path& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != 3 * std::size_t(image.width) * image.height)
    throw std::invalid_argument("writePng: '" + path.string() + "': image of " +
                                std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " needs " +
                                std::to_string(3 * std::size_t(std::max(image.width, 0)) *
                                               std::max(image.height, 0)) +
                                " RGB bytes, has " + std::to_string(image.rgb.size()));
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  const bool ok = png_image_write_to_file(&png, path.c_str(), 0, image.rgb.data(),
                                          3 * image.width, nullptr);
  const std::string reason = png.message;
  png_image_free(&png);
  if (!ok) throw std::runtime_error("writePng: cannot write '" + path.string() + "': " + reason);
}

}  // namespace reeve
