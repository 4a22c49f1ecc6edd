// 8-bit RGB images and PNG output.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace reeve {

/// An 8-bit RGB image: `rgb` holds width * height * 3 bytes, rows top to
/// bottom (row 0 is the top of the picture), pixels left to right.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

/// Writes `image` as an 8-bit RGB PNG file at `path` (libpng), replacing any
/// existing file. Throws std::invalid_argument if rgb.size() is not
/// width * height * 3 or the image is empty, std::runtime_error naming the
/// path and the reason if the file cannot be written.
void writePng(const std::filesystem::path& path, const Image& image);

}  // namespace reeve
