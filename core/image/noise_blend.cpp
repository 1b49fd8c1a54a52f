#include "image/noise_blend.h"

#include "image/box_mean.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace dp {

namespace {

constexpr double kBoxPixels = double((2 * kNoiseBlendRadius + 1) * (2 * kNoiseBlendRadius + 1));
const double kScatter = std::sqrt(2.0 / kBoxPixels);

}  // namespace

Image blend_by_noise(const Image& raw, const Image& denoised, const Image& variance) {
    if (raw.width() != denoised.width() || raw.height() != denoised.height())
        throw std::invalid_argument("blend_by_noise: the denoised image differs in size from the raw one");
    if (variance.empty()) return denoised;
    if (variance.width() != raw.width() || variance.height() != raw.height())
        throw std::invalid_argument("blend_by_noise: the variance differs in size from the raw image");
    const int W = raw.width(), H = raw.height();
    std::vector<double> v(raw.size()), d2(raw.size()), value(raw.size());
    for (size_t i = 0; i < raw.size(); ++i) {
        const double d = double(luminance(denoised[i])) - double(luminance(raw[i]));
        d2[i] = std::isfinite(d) ? d * d : 0.0;
        const double var = variance[i].x;
        v[i] = std::isnan(var) || var < 0 ? 0.0 : std::isinf(var) ? d2[i] : var;  // unknown: all noise
        const double l = luminance(raw[i]);
        value[i] = std::isfinite(l) ? std::abs(l) : 0.0;
    }
    const BoxSums noise(W, H, v), moved(W, H, d2), level(W, H, value);
    Image out(W, H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t i = size_t(y) * W + x;
            if (denoised[i] == raw[i]) {
                out[i] = raw[i];  // keeps the photo's bits where neither touched it
                continue;
            }
            // The mean of n squared noise samples scatters by about V sqrt(2 / n): only a
            // difference beyond two of those counts as the filter's bias.
            const double V = noise.mean(x, y, kNoiseBlendRadius);
            const double bias2 = std::max(0.0, moved.mean(x, y, kNoiseBlendRadius) - V * (1.0 + 2.0 * kScatter));
            // A raw picture this noisy also carries the photon estimate's early bias, which its
            // variance does not show: the filter is trusted there.
            const double rel = std::sqrt(V) / std::max(level.mean(x, y, kNoiseBlendRadius), 1e-6);
            const double trust = std::clamp((rel - kRawTrusted) / (kFilterTrusted - kRawTrusted), 0.0, 1.0);
            const double w = std::max(trust, V + bias2 > 0 ? V / (V + bias2) : 0.0);
            const vec3 o = raw[i] + float(w) * (denoised[i] - raw[i]);
            out[i] = is_finite(o) ? o : raw[i];
        }
    return out;
}

}  // namespace dp
