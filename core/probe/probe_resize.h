#pragma once
#include <cstdint>

#include "image/image.h"

namespace dp {

/// A lat-long map reduced to `width` x `height` with its light kept: each output pixel is the
/// solid-angle-weighted mean of the source pixels' parts that fall inside it (a box filter over
/// the sphere, source pixels split exactly where the output's edges cross them). The power
/// sum(L * Omega) of each channel is the source's up to float rounding, and a one-pixel sun
/// stays inside the output pixel that covers its direction. Throws std::invalid_argument for an
/// empty source or a non-positive size.
Image shrink_latlong(const Image& latlong, int width, int height);

/// The size a `width` x `height` lat-long map is reduced to so that it is at most `max_width`
/// wide: both sides scaled by the same factor (a non-2:1 map keeps its proportions), the height
/// rounded and at least 1. A map no wider than max_width keeps its size.
void shrunk_latlong_size(int width, int height, int max_width, int& out_width, int& out_height);

/// The widest probe kept on load unless the project says otherwise: 8192, halved while a probe
/// of that width (at `bytes_per_pixel` for its image and tables) would take more than a quarter
/// of `memory_bytes` (0: unknown, 8192), down to 1024.
int automatic_probe_max_width(uint64_t memory_bytes, double bytes_per_pixel);

}  // namespace dp
