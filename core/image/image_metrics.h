#pragma once
#include <cstddef>
#include <limits>
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
/// empty), both clamped to `ceiling` per channel first (so that a few pixels showing the sun
/// need not decide the figure). Non-finite pixels of `a` count as an infinite error. Throws
/// std::invalid_argument if the sizes differ.
ImageError image_error(const Image& a, const Image& truth, const std::vector<bool>& mask = {},
                       float ceiling = std::numeric_limits<float>::infinity());

/// The luminance below which the fraction `q` of the image's pixels lie (0 for an empty image).
float luminance_quantile(const Image& image, double q);

/// A tenth of the photo's mean luminance (negative values as 0): pixel values below it count as
/// this much when a change is judged against a pixel's value, so that a black pixel's change is
/// measured against the image, not against zero.
float value_floor(const Image& photo);

/// The pixels a virtual object changes: seen through it (alpha > 0) or with a luminance change
/// from the photograph larger than `threshold` times the photo's (floored at `floor`).
std::vector<bool> changed_pixels(const Image& photo, const Image& truth, const Image& alpha,
                                 float threshold = 0.01f, float floor = 1e-3f);

/// Pixel-wise mean of two images of the same size.
Image mean_image(const Image& a, const Image& b);

}  // namespace dp
