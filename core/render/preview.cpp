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

double drag_preview_pixels(int level, double max_pixels) {
    return max_pixels * std::exp2(-0.5 * std::clamp(level, 0, kDragPreviewLevels - 1));
}

double invisible_relative_error(double mean_value, double exposure_stops) {
    // sRGB's slope at displayed value x is 1.055/2.4 x^(1/2.4 - 1): half a code value (0.5/255)
    // is a relative change of (0.5/255) * 2.4 / (1.055 x^(1/2.4)). Beyond white, clipping
    // hides noise; deep shadows are judged as at 0.002 (the curve's linear toe is near).
    const double x = std::clamp(mean_value * std::exp2(exposure_stops), 0.002, 1.0);
    return (0.5 / 255.0) * 2.4 / (1.055 * std::pow(x, 1.0 / 2.4));
}

}  // namespace dp
