// Box-filter reduction of a supersampled frame.
#pragma once

#include <cstdint>
#include <vector>

#include "reeve/render/image.h"

namespace reeve {

/// Averages each `factor` x `factor` block (factor 1, 2 or 3, else
/// std::invalid_argument) of `rgba` (an RGBA frame of
/// width*factor x height*factor pixels, bottom row first, as OpenGL reads
/// it) into one pixel of a width x height RGB Image, top row first.
Image downsample(const std::vector<std::uint8_t>& rgba, int width, int height, int factor);

}  // namespace reeve
