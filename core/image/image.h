#pragma once
#include <cstddef>
#include <vector>

#include "base/math.h"

namespace dp {

/// Linear-float RGB image, row-major, row 0 at the top (the photograph's convention).
class Image {
public:
    Image() = default;
    /// Throws OutOfMemory (naming the size) when the pixels cannot be allocated.
    Image(int width, int height, vec3 fill = vec3(0));

    int width() const { return width_; }
    int height() const { return height_; }
    bool empty() const { return pixels_.empty(); }
    size_t size() const { return pixels_.size(); }

    vec3& at(int x, int y) { return pixels_[size_t(y) * width_ + x]; }
    const vec3& at(int x, int y) const { return pixels_[size_t(y) * width_ + x]; }
    vec3& operator[](size_t i) { return pixels_[i]; }
    const vec3& operator[](size_t i) const { return pixels_[i]; }
    vec3* data() { return pixels_.data(); }
    const vec3* data() const { return pixels_.data(); }

    /// Bilinear lookup in continuous pixel coordinates where pixel (i, j) has its centre at
    /// (i, j) (OpenCV's convention); clamps at the border.
    vec3 bilinear(float x, float y) const;

    bool operator==(const Image& o) const {
        return width_ == o.width_ && height_ == o.height_ && pixels_ == o.pixels_;
    }

private:
    int width_ = 0, height_ = 0;
    std::vector<vec3> pixels_;
};

/// Resamples an image bilinearly to width x height (pixel centres mapped onto each other),
/// averaging a small footprint when shrinking so that previews do not alias.
Image resample(const Image& image, int width, int height);

/// The one NaN/Inf policy of every image that enters or leaves diffphoton: each non-finite
/// channel becomes 0 (the other channels of the pixel are kept). Returns how many were replaced.
size_t replace_non_finite(Image& image);

}  // namespace dp
