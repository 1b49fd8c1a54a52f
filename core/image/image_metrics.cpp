#include "image/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dp {

ImageError image_error(const Image& a, const Image& truth, const std::vector<bool>& mask, float ceiling) {
    if (a.width() != truth.width() || a.height() != truth.height())
        throw std::invalid_argument("image_error: images differ in size");
    if (!mask.empty() && mask.size() != a.size())
        throw std::invalid_argument("image_error: mask size differs from the images");
    double se = 0, sum_truth = 0;
    ImageError e;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!mask.empty() && !mask[i]) continue;
        // NaN survives glm::min (it compares false), so a non-finite pixel still shows.
        const vec3 ai = is_finite(a[i]) ? glm::min(a[i], vec3(ceiling)) : a[i];
        const vec3 ti = glm::min(truth[i], vec3(ceiling));
        const dvec3 d = dvec3(ai) - dvec3(ti);
        se += (d.x * d.x + d.y * d.y + d.z * d.z) / 3.0;
        sum_truth += luminance(dvec3(ti));
        ++e.pixels;
    }
    if (e.pixels == 0) return e;
    e.rmse = std::isfinite(se) ? std::sqrt(se / double(e.pixels)) : std::numeric_limits<double>::infinity();
    const double mean_truth = sum_truth / double(e.pixels);
    e.rel_rmse = mean_truth > 0 ? e.rmse / mean_truth : 0;
    return e;
}

float value_floor(const Image& photo) {
    double mean = 0;
    for (size_t i = 0; i < photo.size(); ++i) mean += std::max(0.0f, luminance(photo[i]));
    return float(0.1 * mean / double(std::max<size_t>(1, photo.size()))) + 1e-12f;
}

std::vector<bool> changed_pixels(const Image& photo, const Image& truth, const Image& alpha,
                                 float threshold, float floor) {
    if (photo.size() != truth.size() || (!alpha.empty() && alpha.size() != truth.size()))
        throw std::invalid_argument("changed_pixels: images differ in size");
    std::vector<bool> mask(truth.size());
    for (size_t i = 0; i < truth.size(); ++i) {
        const float p = luminance(photo[i]);
        const float change = std::abs(luminance(truth[i]) - p);
        mask[i] = change > threshold * std::max(p, floor) || (!alpha.empty() && alpha[i].x > 0);
    }
    return mask;
}

float luminance_quantile(const Image& image, double q) {
    if (image.empty()) return 0;
    std::vector<float> lum(image.size());
    for (size_t i = 0; i < image.size(); ++i) lum[i] = luminance(image[i]);
    const size_t k = std::min(lum.size() - 1, size_t(std::clamp(q, 0.0, 1.0) * double(lum.size())));
    std::nth_element(lum.begin(), lum.begin() + std::ptrdiff_t(k), lum.end());
    return lum[k];
}

Image mean_image(const Image& a, const Image& b) {
    if (a.width() != b.width() || a.height() != b.height())
        throw std::invalid_argument("mean_image: images differ in size");
    Image out(a.width(), a.height());
    for (size_t i = 0; i < a.size(); ++i) out[i] = 0.5f * (a[i] + b[i]);
    return out;
}

}  // namespace dp
