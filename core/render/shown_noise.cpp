#include "render/shown_noise.h"

#include <algorithm>
#include <cmath>

#include "image/denoise.h"
#include "image/image_metrics.h"

namespace dp {

double shown_rel_error(const Image& later, int m, const Image& earlier, int k, const Image& photo, const Image& alpha,
                       const Image& raw, float ceiling) {
    const size_t n = later.size();
    if (k <= 0 || m <= k || earlier.size() != n || photo.size() != n || alpha.size() != n || raw.size() != n) return -1;
    const float floor = value_floor(photo);
    const std::vector<bool> changes = changed_pixels(photo, raw, alpha, 0.01f, floor);
    std::vector<double> d2;
    double value = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!changes[i]) continue;
        const double a = std::clamp(double(luminance(later[i])), 0.0, double(ceiling));
        const double b = std::clamp(double(luminance(earlier[i])), 0.0, double(ceiling));
        if (!std::isfinite(a) || !std::isfinite(b)) continue;
        d2.push_back((a - b) * (a - b));
        value += std::max(a, double(floor));
    }
    const size_t changed = d2.size();
    if (changed == 0 || value <= 0) return -1;
    // The largest thousandth left out: a firefly in one of the two pictures would otherwise
    // make the estimate jump from one picture to the next.
    const size_t keep = changed - changed / 1000;
    std::nth_element(d2.begin(), d2.begin() + ptrdiff_t(keep - 1), d2.end());
    double e2 = 0;
    for (size_t i = 0; i < keep; ++i) e2 += d2[i];
    const double scale = double(k) / double(m - k);
    return std::sqrt(e2 * scale / double(keep)) / (value / double(changed));
}

double ShownNoise::add(uint64_t generation, int passes, std::shared_ptr<const Image> shown, const Image& photo,
                       const Image& alpha, const Image& raw) {
    if (generation != generation_ || (!kept_.empty() && kept_.back().image->size() != shown->size())) {
        kept_.clear();
        generation_ = generation;
    }
    // The latest earlier picture with at most 3/4 of the passes: m - k of at least m / 4 keeps
    // the difference's own noise from ruling the estimate.
    const Kept* earlier = nullptr;
    for (const Kept& k : kept_)
        if (4 * k.passes <= 3 * passes) earlier = &k;
    const double error = earlier ? shown_rel_error(*shown, passes, *earlier->image, earlier->passes, photo, alpha, raw,
                                                   denoise_ceiling(photo))
                                 : -1.0;
    if (!kept_.empty() && kept_.back().passes >= passes) return error;  // an older picture came late
    kept_.push_back({passes, std::move(shown)});
    // Thinned where two kept pictures are closest in passes (ratio), the first and last kept.
    while (kept_.size() > kKept) {
        size_t drop = 1;
        double closest = INFINITY;
        for (size_t i = 1; i + 1 < kept_.size(); ++i) {
            const double r = double(kept_[i + 1].passes) / double(kept_[i - 1].passes);
            if (r < closest) closest = r, drop = i;
        }
        kept_.erase(kept_.begin() + ptrdiff_t(drop));
    }
    return error;
}

}  // namespace dp
