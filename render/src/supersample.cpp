#include "supersample.h"

#include <algorithm>
#include <cstddef>

namespace reeve {

Image downsample(const std::vector<std::uint8_t>& rgba, int width, int height, int factor) {
  Image image{width, height, std::vector<std::uint8_t>(3 * std::size_t(width) * height)};
  const std::size_t source_row = 4 * std::size_t(width) * factor;
  const float inv_area = 1.0f / float(factor * factor);
  std::vector<std::uint16_t> column_sums(source_row);  // 255 * area fits for factor <= 16
  for (int y = 0; y < height; ++y) {
    // Sum the block's rows first (contiguous, vectorizes), then across.
    std::fill(column_sums.begin(), column_sums.end(), 0);
    for (int sy = 0; sy < factor; ++sy) {
      const std::uint8_t* row = rgba.data() + (std::size_t(y) * factor + sy) * source_row;
      for (std::size_t i = 0; i < source_row; ++i) column_sums[i] += row[i];
    }
    // Source row 0 is the bottom of the picture, Image row 0 the top.
    std::uint8_t* out = image.rgb.data() + 3 * std::size_t(width) * (height - 1 - y);
    const std::uint16_t* block = column_sums.data();
    for (int x = 0; x < width; ++x, block += 4 * factor)
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int sx = 0; sx < factor; ++sx) sum += block[4 * sx + c];
        out[3 * x + c] = static_cast<std::uint8_t>(float(sum) * inv_area + 0.5f);
      }
  }
  return image;
}

}  // namespace reeve
