#pragma once
// Shared checks of the numerical stress tests: finiteness, image differences, and a path-traced
// photograph and truth for a project.
#include <cmath>
#include <cstddef>
#include <memory>

#include "common/test_scenes.h"
#include "reference/path_tracer.h"
#include "render/progressive.h"

namespace dp::test {

/// Number of pixels with a NaN or infinite channel.
inline size_t count_non_finite(const Image& img) {
    size_t n = 0;
    for (size_t i = 0; i < img.size(); ++i) n += !is_finite(img[i]);
    return n;
}

/// RMSE of `a - b` over the pixels where `mask` is true (all when `mask` is empty), divided by
/// the mean luminance of `b` there. Returns 0 when no pixel is selected.
template <typename Mask>
double relative_rmse(const Image& a, const Image& b, Mask mask) {
    double se = 0, sum_b = 0;
    size_t n = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!mask(i)) continue;
        vec3 d = a[i] - b[i];
        se += double(glm::dot(d, d)) / 3.0;
        sum_b += luminance(b[i]);
        ++n;
    }
    if (n == 0) return 0;
    return std::sqrt(se / double(n)) / std::max(sum_b / double(n), 1e-300);
}

inline double relative_rmse(const Image& a, const Image& b) {
    return relative_rmse(a, b, [](size_t) { return true; });
}

/// A photograph (real proxies only) and a truth (with the virtual objects) from the reference
/// path tracer, and the differential renderer's output on that photograph.
struct TruthAndRender {
    Image photo, truth, render, alpha;
    size_t non_finite_samples = 0;
    std::shared_ptr<RenderScene> scene;
};

inline TruthAndRender render_against_truth(const Project& p, const Image& probe, int w, int h, int spp, int passes,
                                           int64_t photons, uint64_t seed = 3) {
    TruthAndRender out;
    SceneAssets assets;
    assets.photo = Image(w, h);
    assets.probe_latlong = probe;
    RenderScene tmp(p, assets);
    ReferenceOptions real_only;
    real_only.samples_per_pixel = spp;
    real_only.include_virtual = false;
    real_only.seed = 11;
    out.photo = render_reference(tmp, real_only);
    ReferenceOptions with_virtual = real_only;
    with_virtual.include_virtual = true;
    with_virtual.seed = 12;
    out.truth = render_reference(tmp, with_virtual);
    out.scene = build(p, out.photo, probe);
    ProgressiveRenderer r(out.scene, settings(photons, seed));
    for (int i = 0; i < passes; ++i) r.render_pass();
    out.render = r.image();
    out.alpha = r.alpha_layer();
    out.non_finite_samples = r.stats().non_finite_samples;
    return out;
}

/// Pixels whose truth differs from the photo by more than 1%, or that see a virtual object.
inline std::vector<bool> changed_pixels(const TruthAndRender& t) {
    std::vector<bool> m(t.photo.size());
    for (size_t i = 0; i < m.size(); ++i) {
        float change = std::abs(luminance(t.truth[i]) - luminance(t.photo[i]));
        m[i] = change > 0.01f * std::max(luminance(t.photo[i]), 1e-3f) || t.alpha[i].x > 0;
    }
    return m;
}

}  // namespace dp::test
