#include "reference/standard_differential.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "base/rng.h"
#include "image/image_metrics.h"

namespace dp {

namespace {
constexpr uint64_t kIndependentSeed = 0x9e3779b97f4a7c15ull;
}  // namespace

StandardDifferentialRenderer::StandardDifferentialRenderer(std::shared_ptr<const RenderScene> scene,
                                                           const RenderSettings& rs, Sampling sampling,
                                                           int samples_per_pass)
    : scene_(std::move(scene)), sampling_(sampling), samples_per_pass_(std::max(1, samples_per_pass)) {
    with_virtual_.max_depth = rs.max_depth;
    with_virtual_.seed = rs.seed;
    with_virtual_.include_virtual = true;
    with_virtual_.show_probe = true;
    real_only_ = with_virtual_;
    real_only_.include_virtual = false;
    if (sampling_ == Sampling::Independent) real_only_.seed = rs.seed ^ kIndependentSeed;
    const size_t n = size_t(scene_->camera().width()) * scene_->camera().height();
    sum_delta_.assign(n, dvec3(0));
    sum_virtual_.assign(n, dvec3(0));
    virtual_count_.assign(n, 0);
    samples_.assign(n, 0);
    stats_.pixels_total = n;
}

void StandardDifferentialRenderer::build_focus() {
    const Image& photo = scene_->photo();
    const int W = photo.width(), H = photo.height();
    const double floor = value_floor(photo);
    std::vector<uint8_t> changed(photo.size(), 0);
    for (size_t i = 0; i < photo.size(); ++i) {
        const double n = std::max<uint32_t>(1, samples_[i]);
        const double d = luminance((sum_delta_[i] + sum_virtual_[i]) / n) - luminance(photo[i]) * virtual_count_[i] / n;
        changed[i] = virtual_count_[i] > 0 || std::abs(d) > 0.006 * std::max(double(luminance(photo[i])), floor);
    }
    std::vector<uint8_t> grown(photo.size(), 0);
    constexpr int kGrow = 2;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (!changed[size_t(y) * W + x]) continue;
            for (int yy = std::max(0, y - kGrow); yy <= std::min(H - 1, y + kGrow); ++yy)
                for (int xx = std::max(0, x - kGrow); xx <= std::min(W - 1, x + kGrow); ++xx)
                    grown[size_t(yy) * W + xx] = 1;
        }
    focus_.clear();
    for (size_t i = 0; i < grown.size(); ++i)
        if (grown[i]) focus_.push_back(uint32_t(i));
    if (focus_.empty()) focus_.push_back(0);  // nothing changes: keep sampling one pixel, not all
}

bool StandardDifferentialRenderer::render_pass(const std::atomic<bool>* cancel) {
    const auto t0 = std::chrono::steady_clock::now();
    const RenderScene& s = *scene_;
    const int W = s.camera().width();
    if (focus_after_ > 0 && stats_.passes == focus_after_ && focus_.empty()) build_focus();
    const uint64_t first = stats_.samples_per_pixel, last = first + uint64_t(samples_per_pass_);
    const size_t count = focus_.empty() ? sum_delta_.size() : focus_.size();
    auto pixel_at = [&](size_t k) { return focus_.empty() ? k : size_t(focus_[k]); };
    // Accumulated into pass-local sums first, so a cancelled pass leaves no partial samples.
    std::vector<dvec3> delta(count, dvec3(0)), virt(count, dvec3(0));
    std::vector<uint32_t> vcount(count, 0);
    std::atomic<size_t> bad{0};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 64), [&](const tbb::blocked_range<size_t>& r) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return;
        size_t local_bad = 0;
        for (size_t k = r.begin(); k < r.end(); ++k) {
            const uint64_t pixel = pixel_at(k);
            const int x = int(pixel % uint64_t(W)), y = int(pixel / uint64_t(W));
            for (uint64_t smp = first; smp < last; ++smp) {
                // Same camera jitter as the reference path tracer.
                const Ray ray = reference_camera_ray(s, with_virtual_.seed, x, y, smp);
                Hit first_hit = s.intersect(ray);
                // Held out: the photo, which shows the occluder, stands (no change).
                const float t_hold = s.holdout_t(ray);
                // A lamp's face in front of the occluder still shows.
                if (t_hold < INFINITY && (!first_hit || first_hit.t > t_hold) &&
                    (s.lights().empty() || s.lights().emitted(ray, t_hold) == vec3(0)))
                    continue;
                vec3 L_new = reference_radiance(s, with_virtual_, ray, pixel, int(smp));
                // An area light's face in front counts as a virtual object: it replaces the photo.
                const bool sees_light = !s.lights().empty() &&
                                        s.lights().emitted(ray, first_hit ? first_hit.t : INFINITY) != vec3(0);
                if (sees_light || (first_hit && first_hit.surface->is_virtual)) {
                    if (!is_finite(L_new)) { ++local_bad; continue; }
                    virt[k] += dvec3(L_new);
                    ++vcount[k];
                    continue;
                }
                const Ray old_ray = sampling_ == Sampling::Correlated
                                        ? ray
                                        : reference_camera_ray(s, real_only_.seed, x, y, smp);
                vec3 L_old = reference_radiance(s, real_only_, old_ray, pixel, int(smp));
                vec3 d = L_new - L_old;
                if (!is_finite(d)) { ++local_bad; continue; }
                delta[k] += dvec3(d);
            }
        }
        bad += local_bad;
    });
    if (cancel && cancel->load()) return false;
    for (size_t k = 0; k < count; ++k) {
        const size_t i = pixel_at(k);
        sum_delta_[i] += delta[k];
        sum_virtual_[i] += virt[k];
        virtual_count_[i] += vcount[k];
        samples_[i] += uint32_t(samples_per_pass_);
    }
    stats_.passes += 1;
    stats_.samples_per_pixel = last;
    stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats_.pixels_gathered = count;
    stats_.non_finite_samples += bad.load();
    return true;
}

Image StandardDifferentialRenderer::image() const {
    const Image& photo = scene_->photo();
    Image out = photo;
    for (size_t i = 0; i < out.size(); ++i) {
        const double n = double(samples_[i]);
        if (n == 0) continue;
        const double a = virtual_count_[i] / n;
        out[i] = vec3(dvec3(photo[i]) * (1.0 - a) + (sum_delta_[i] + sum_virtual_[i]) / n);
    }
    return out;
}

Image StandardDifferentialRenderer::dL_layer() const {
    Image out(scene_->camera().width(), scene_->camera().height());
    for (size_t i = 0; i < out.size(); ++i) out[i] = vec3(sum_delta_[i] / double(std::max<uint32_t>(1, samples_[i])));
    return out;
}

Image StandardDifferentialRenderer::alpha_layer() const {
    Image out(scene_->camera().width(), scene_->camera().height());
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = vec3(float(virtual_count_[i] / double(std::max<uint32_t>(1, samples_[i]))));
    return out;
}

}  // namespace dp
