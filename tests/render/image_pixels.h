// Reading pixels of an Image in the render tests.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "reeve/engine/math.h"
#include "reeve/render/image.h"

namespace reeve::test {

using Rgb = std::array<int, 3>;

inline Rgb pixel(const Image& image, int x, int y) {
  const std::uint8_t* p = &image.rgb[3 * (std::size_t(y) * image.width + x)];
  return {p[0], p[1], p[2]};
}

inline Rgb pixelAt(const Image& image, const Eigen::Vector2d& px) {
  return pixel(image, static_cast<int>(std::floor(px.x())), static_cast<int>(std::floor(px.y())));
}

/// Largest per-channel difference.
inline int distance(const Rgb& a, const Rgb& b) {
  int d = 0;
  for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a[c] - b[c]));
  return d;
}

}  // namespace reeve::test
