#include "image/noise_blend.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace dp {

namespace {

constexpr double kBoxPixels = double((2 * kNoiseBlendRadius + 1) * (2 * kNoiseBlendRadius + 1));
const double kScatter = std::sqrt(2.0 / kBoxPixels);

/// Box sums over (2 r + 1)^2 windows, clipped at the borders, of a per-pixel value.
class BoxMean {
public:
    BoxMean(int w, int h, const std::vector<double>& v) : w_(w), h_(h), sum_(size_t(w + 1) * (h + 1), 0.0) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t o = size_t(y + 1) * (w + 1) + x + 1;
                sum_[o] = v[size_t(y) * w + x] + sum_[o - 1] + sum_[o - size_t(w + 1)] - sum_[o - size_t(w + 1) - 1];
            }
    }
    double operator()(int x, int y, int r) const {
        const int x0 = std::max(0, x - r), y0 = std::max(0, y - r);
        const int x1 = std::min(w_, x + r + 1), y1 = std::min(h_, y + r + 1);
        auto at = [&](int xx, int yy) { return sum_[size_t(yy) * (w_ + 1) + xx]; };
        return (at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0)) / double((x1 - x0) * (y1 - y0));
    }

private:
    int w_, h_;
    std::vector<double> sum_;
};

}  // namespace

Image blend_by_noise(const Image& raw, const Image& denoised, const Image& variance) {
    if (raw.width() != denoised.width() || raw.height() != denoised.height())
        throw std::invalid_argument("blend_by_noise: the denoised image differs in size from the raw one");
    if (variance.empty()) return denoised;
    if (variance.width() != raw.width() || variance.height() != raw.height())
        throw std::invalid_argument("blend_by_noise: the variance differs in size from the raw image");
    const int W = raw.width(), H = raw.height();
    std::vector<double> v(raw.size()), d2(raw.size());
    for (size_t i = 0; i < raw.size(); ++i) {
        const double d = double(luminance(denoised[i])) - double(luminance(raw[i]));
        d2[i] = std::isfinite(d) ? d * d : 0.0;
        const double var = variance[i].x;
        v[i] = std::isnan(var) || var < 0 ? 0.0 : std::isinf(var) ? d2[i] : var;  // unknown: all noise
    }
    std::vector<double> value(raw.size());
    for (size_t i = 0; i < raw.size(); ++i) {
        const double l = luminance(raw[i]);
        value[i] = std::isfinite(l) ? std::abs(l) : 0.0;
    }
    const BoxMean noise(W, H, v), moved(W, H, d2), level(W, H, value);
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
            const double V = noise(x, y, kNoiseBlendRadius);
            const double bias2 = std::max(0.0, moved(x, y, kNoiseBlendRadius) - V * (1.0 + 2.0 * kScatter));
            // A raw picture this noisy also carries the photon estimate's early bias, which its
            // variance does not show: the filter is trusted there.
            const double rel = std::sqrt(V) / std::max(level(x, y, kNoiseBlendRadius), 1e-6);
            const double trust = std::clamp((rel - kRawTrusted) / (kFilterTrusted - kRawTrusted), 0.0, 1.0);
            const double w = std::max(trust, V + bias2 > 0 ? V / (V + bias2) : 0.0);
            const vec3 o = raw[i] + float(w) * (denoised[i] - raw[i]);
            out[i] = is_finite(o) ? o : raw[i];
        }
    return out;
}

}  // namespace dp
