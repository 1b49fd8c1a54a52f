#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dp {

/// Grows a pixel mask (row-major, non-zero = set) by `pixels` in each direction: a square
/// structuring element, clipped at the image's border.
void dilate_mask(std::vector<uint8_t>& mask, int width, int height, int pixels);

}  // namespace dp
