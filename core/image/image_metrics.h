#pragma once
#include <cstddef>
#include <vector>

#include "image/image.h"

namespace dp {

/// Error of an image against a truth over a set of pixels (or all of them).
struct ImageError {
    double rmse = 0;      ///< sqrt(mean over pixels and channels of (a - truth)^2)
    double rel_rmse = 0;  ///< rmse / mean luminance of the truth over the same pixels
    size_t pixels = 0;    ///< pixels compared (0: the relative error is undefined and 0)
};

/// Compares `a` with `truth` over the pixels where `mask` is true (all pixels if `mask` is
/// empty). Non-finite pixels of `a` count as an infinite error. Throws std::invalid_argument
/// if the sizes differ.
ImageError image_error(const Image& a, const Image& truth, const std::vector<bool>& mask = {});

/// The pixels a virtual object changes: seen through it (alpha > 0) or with a luminance change
/// from the photograph larger than `threshold` times the photo's (floored at `floor`).
std::vector<bool> changed_pixels(const Image& photo, const Image& truth, const Image& alpha,
                                 float threshold = 0.01f, float floor = 1e-3f);

/// Pixel-wise mean of two images of the same size.
Image mean_image(const Image& a, const Image& b);

}  // namespace dp
