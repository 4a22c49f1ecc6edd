#include "supersample.h"

#include <algorithm>
#include <cstddef>

namespace reeve {

Image downsample(const std::vector<std::uint8_t>& rgba, int width, int height, int factor) {
  Image image{width, height, std::vector<std::uint8_t>(3 * std::size_t(width) * height)};
  const std::size_t source_row = 4 * std::size_t(width) * factor;
  const int area = factor * factor;
  std::vector<int> sums(3 * std::size_t(width));
  for (int y = 0; y < height; ++y) {
    std::fill(sums.begin(), sums.end(), 0);
    for (int sy = 0; sy < factor; ++sy) {
      const std::uint8_t* row = rgba.data() + (std::size_t(y) * factor + sy) * source_row;
      for (int x = 0; x < width; ++x)
        for (int sx = 0; sx < factor; ++sx, row += 4)
          for (int c = 0; c < 3; ++c) sums[3 * x + c] += row[c];
    }
    // Source row 0 is the bottom of the picture, Image row 0 the top.
    std::uint8_t* out = image.rgb.data() + 3 * std::size_t(width) * (height - 1 - y);
    for (int i = 0; i < 3 * width; ++i) out[i] = static_cast<std::uint8_t>((sums[i] + area / 2) / area);
  }
  return image;
}

}  // namespace reeve
