#include "supersample.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>

namespace reeve {
namespace {

// The factor is a template argument so the inner loops unroll.
template <int kFactor>
Image downsampleBy(const std::vector<std::uint8_t>& rgba, int width, int height) {
  Image image{width, height, std::vector<std::uint8_t>(3 * std::size_t(width) * height)};
  const std::size_t source_row = 4 * std::size_t(width) * kFactor;
  constexpr float kInvArea = 1.0f / (kFactor * kFactor);
  std::vector<std::uint16_t> column_sums(source_row);  // 255 * kFactor fits
  for (int y = 0; y < height; ++y) {
    // Sum the block's rows first (contiguous, vectorizes), then across.
    std::fill(column_sums.begin(), column_sums.end(), 0);
    for (int sy = 0; sy < kFactor; ++sy) {
      const std::uint8_t* row = rgba.data() + (std::size_t(y) * kFactor + sy) * source_row;
      for (std::size_t i = 0; i < source_row; ++i) column_sums[i] += row[i];
    }
    // Source row 0 is the bottom of the picture, Image row 0 the top.
    std::uint8_t* out = image.rgb.data() + 3 * std::size_t(width) * (height - 1 - y);
    const std::uint16_t* block = column_sums.data();
    for (int x = 0; x < width; ++x, block += 4 * kFactor)
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int sx = 0; sx < kFactor; ++sx) sum += block[4 * sx + c];
        out[3 * x + c] = static_cast<std::uint8_t>(float(sum) * kInvArea + 0.5f);
      }
  }
  return image;
}

}  // namespace

Image downsample(const std::vector<std::uint8_t>& rgba, int width, int height, int factor) {
  switch (factor) {
    case 1: return downsampleBy<1>(rgba, width, height);
    case 2: return downsampleBy<2>(rgba, width, height);
    case 3: return downsampleBy<3>(rgba, width, height);
  }
  throw std::invalid_argument("downsample: factor must be 1, 2 or 3");
}

}  // namespace reeve
