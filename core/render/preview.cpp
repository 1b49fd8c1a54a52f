#include "render/preview.h"

#include <algorithm>
#include <cmath>

namespace dp {

RenderSettings PreviewPolicy::settings(const RenderSettings& full) const {
    RenderSettings quick = full;
    quick.photons_per_pass = std::max<int64_t>(2000, int64_t(double(full.photons_per_pass) * photon_fraction));
    quick.time_budget_s = 0;
    quick.passes = 1 << 20;  // refines at quick size until replaced
    if (quick.initial_radius) *quick.initial_radius *= 2.0f;
    return quick;
}

void PreviewPolicy::size(int width, int height, int& preview_width, int& preview_height) const {
    // The quick pass's cost is mostly per pixel: keep it under max_pixels whatever the size.
    const double s = std::min(scale, std::sqrt(max_pixels / std::max(1.0, double(width) * height)));
    preview_width = std::max(1, int(width * s));
    preview_height = std::max(1, int(height * s));
}

}  // namespace dp
