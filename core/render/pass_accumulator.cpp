#include "render/pass_accumulator.h"

#include <cmath>
#include <stdexcept>

namespace dp {

PassAccumulator::PassAccumulator(size_t pixels)
    : sum_delta_(pixels, dvec3(0)), sum_dL_(pixels, dvec3(0)), sum_alpha_(pixels, 0.0) {}

size_t PassAccumulator::add(const std::vector<SampleResult>& samples) {
    if (samples.size() != sum_delta_.size())
        throw std::invalid_argument("PassAccumulator::add: one sample per pixel expected");
    size_t bad = 0;
    for (size_t i = 0; i < samples.size(); ++i) {
        const SampleResult& r = samples[i];
        if (!is_finite(r.delta) || !is_finite(r.dL) || !std::isfinite(r.alpha)) {
            ++bad;
            continue;
        }
        sum_delta_[i] += dvec3(r.delta);
        sum_dL_[i] += dvec3(r.dL);
        sum_alpha_[i] += r.alpha;
    }
    ++passes_;
    return bad;
}

}  // namespace dp
