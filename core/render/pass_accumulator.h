#pragma once
#include <cstddef>
#include <vector>

#include "base/math.h"
#include "render/shading.h"

namespace dp {

/// Per-pixel sums of the pass images, in double: shadow and caustic photons nearly cancel, and
/// a long render adds thousands of passes. A sample with a NaN/Inf channel is dropped whole, so
/// that one never reaches the image.
class PassAccumulator {
public:
    PassAccumulator() = default;
    explicit PassAccumulator(size_t pixels);

    /// Adds one pass's samples (one per pixel, in pixel order); returns how many were dropped
    /// because they were not finite.
    size_t add(const std::vector<SampleResult>& samples);

    int passes() const { return passes_; }
    size_t size() const { return sum_delta_.size(); }
    /// Means over the passes so far (zero before the first pass).
    dvec3 mean_delta(size_t i) const { return passes_ ? sum_delta_[i] / double(passes_) : dvec3(0); }
    dvec3 mean_dL(size_t i) const { return passes_ ? sum_dL_[i] / double(passes_) : dvec3(0); }
    double mean_alpha(size_t i) const { return passes_ ? sum_alpha_[i] / passes_ : 0.0; }
    /// True while no pass has changed pixel i: it keeps the photo bit for bit.
    bool untouched(size_t i) const { return sum_delta_[i] == dvec3(0); }

private:
    std::vector<dvec3> sum_delta_, sum_dL_;
    std::vector<double> sum_alpha_;
    int passes_ = 0;
};

}  // namespace dp
