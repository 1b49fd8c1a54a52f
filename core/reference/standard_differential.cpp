#include "reference/standard_differential.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>

#include "base/rng.h"

namespace dp {

namespace {
constexpr uint64_t kCameraStream = 0x7265665f7074ull;  // the reference path tracer's
constexpr uint64_t kIndependentSeed = 0x9e3779b97f4a7c15ull;

Ray camera_ray(const RenderScene& s, uint64_t seed, int x, int y, uint64_t pixel, uint64_t sample) {
    Rng rng = Rng::keyed(seed ^ kCameraStream, pixel, sample * 2);
    return s.camera().generate_ray(x + rng.uniform() - 0.5f, y + rng.uniform() - 0.5f);
}
}  // namespace

StandardDifferentialRenderer::StandardDifferentialRenderer(std::shared_ptr<const RenderScene> scene,
                                                           Sampling sampling, int samples_per_pass)
    : scene_(std::move(scene)), sampling_(sampling), samples_per_pass_(std::max(1, samples_per_pass)) {
    const RenderSettings& rs = scene_->project().render;
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
    stats_.pixels_total = n;
}

bool StandardDifferentialRenderer::render_pass(const std::atomic<bool>* cancel) {
    const auto t0 = std::chrono::steady_clock::now();
    const RenderScene& s = *scene_;
    const int W = s.camera().width(), H = s.camera().height();
    const uint64_t first = stats_.samples_per_pixel, last = first + uint64_t(samples_per_pass_);
    // Accumulated into pass-local sums first, so a cancelled pass leaves no partial samples.
    std::vector<dvec3> delta(sum_delta_.size(), dvec3(0)), virt(sum_virtual_.size(), dvec3(0));
    std::vector<uint32_t> vcount(virtual_count_.size(), 0);
    std::atomic<size_t> bad{0};
    tbb::parallel_for(tbb::blocked_range<int>(0, H, 1), [&](const tbb::blocked_range<int>& rows) {
        size_t local_bad = 0;
        for (int y = rows.begin(); y < rows.end(); ++y) {
            if (cancel && cancel->load(std::memory_order_relaxed)) return;
            for (int x = 0; x < W; ++x) {
                const uint64_t pixel = uint64_t(y) * W + x;
                for (uint64_t smp = first; smp < last; ++smp) {
                    // Same camera jitter as the reference path tracer.
                    const Ray ray = camera_ray(s, with_virtual_.seed, x, y, pixel, smp);
                    Hit first_hit = s.intersect(ray);
                    vec3 L_new = reference_radiance(s, with_virtual_, ray, pixel, int(smp));
                    if (first_hit && first_hit.surface->is_virtual) {
                        if (!is_finite(L_new)) { ++local_bad; continue; }
                        virt[pixel] += dvec3(L_new);
                        ++vcount[pixel];
                        continue;
                    }
                    const Ray old_ray = sampling_ == Sampling::Correlated
                                            ? ray
                                            : camera_ray(s, real_only_.seed, x, y, pixel, smp);
                    vec3 L_old = reference_radiance(s, real_only_, old_ray, pixel, int(smp));
                    vec3 d = L_new - L_old;
                    if (!is_finite(d)) { ++local_bad; continue; }
                    delta[pixel] += dvec3(d);
                }
            }
        }
        bad += local_bad;
    });
    if (cancel && cancel->load()) return false;
    for (size_t i = 0; i < delta.size(); ++i) {
        sum_delta_[i] += delta[i];
        sum_virtual_[i] += virt[i];
        virtual_count_[i] += vcount[i];
    }
    stats_.passes += 1;
    stats_.samples_per_pixel = last;
    stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats_.pixels_gathered = stats_.pixels_total;
    stats_.non_finite_samples += bad.load();
    return true;
}

Image StandardDifferentialRenderer::image() const {
    const Image& photo = scene_->photo();
    Image out = photo;
    const double n = double(stats_.samples_per_pixel);
    if (n == 0) return out;
    for (size_t i = 0; i < out.size(); ++i) {
        const double a = virtual_count_[i] / n;
        out[i] = vec3(dvec3(photo[i]) * (1.0 - a) + (sum_delta_[i] + sum_virtual_[i]) / n);
    }
    return out;
}

Image StandardDifferentialRenderer::delta_layer() const {
    Image out(scene_->camera().width(), scene_->camera().height());
    const double n = double(std::max<uint64_t>(1, stats_.samples_per_pixel));
    for (size_t i = 0; i < out.size(); ++i) out[i] = vec3(sum_delta_[i] / n);
    return out;
}

Image StandardDifferentialRenderer::alpha_layer() const {
    Image out(scene_->camera().width(), scene_->camera().height());
    const double n = double(std::max<uint64_t>(1, stats_.samples_per_pixel));
    for (size_t i = 0; i < out.size(); ++i) out[i] = vec3(float(virtual_count_[i] / n));
    return out;
}

}  // namespace dp
