#include "render/progressive.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "base/rng.h"
#include "base/sampling.h"
#include "render/shading.h"

namespace dp {

ProgressiveRenderer::ProgressiveRenderer(std::shared_ptr<const RenderScene> scene, int64_t photons_per_pass,
                                         uint64_t seed)
    : scene_(std::move(scene)), photons_per_pass_(std::max<int64_t>(1, photons_per_pass)), seed_(seed) {
    const RenderSettings& rs = scene_->project().render;
    alpha_ = rs.alpha;
    if (rs.initial_radius && *rs.initial_radius > 0) {
        r1_ = *rs.initial_radius;
    } else {
        // About a hundred photons of a sunlit shadow inside the first gather disk.
        float rmax = 0;
        for (const EmissionCluster& c : scene_->clusters()) rmax = std::max(rmax, c.radius);
        if (rmax <= 0) rmax = scene_->scale();
        r1_ = rmax * std::clamp(std::sqrt(100.0f / float(photons_per_pass_)), 0.004f, 0.2f);
    }
    const size_t n = size_t(scene_->photo().width()) * scene_->photo().height();
    sums_ = PassAccumulator(n);
    stats_.pixels_total = n;
    cache_ = build_pixel_cache(*scene_);
    const size_t near = size_t(std::count(cache_.near_virtual.begin(), cache_.near_virtual.end(), uint8_t(1)));
    diffuse_samples_ = dp::camera_diffuse_samples(photons_per_pass_, near);
}

vec2 camera_jitter(uint64_t seed, int pass, size_t pixel) {
    Rng shift_rng = Rng::keyed(seed, ~uint64_t(0), pixel);
    const vec2 shift(shift_rng.uniform(), shift_rng.uniform());
    return r2_point(uint64_t(pass), shift) - vec2(0.5f);
}

float ProgressiveRenderer::radius_for_pass(int pass) const {
    double r2 = double(r1_) * r1_;
    for (int k = 1; k < pass; ++k) r2 *= (k + double(alpha_)) / (k + 1.0);
    return float(std::sqrt(r2));
}

void ProgressiveRenderer::shade_pass(int pass, const PassMaps& maps, std::vector<SampleResult>& out,
                                     const std::atomic<bool>* cancel, size_t& gathered) {
    const RenderScene& s = *scene_;
    const int W = s.photo().width(), H = s.photo().height();
    // Reused across passes: a fresh 2M-pixel buffer each pass costs page faults.
    out.resize(size_t(W) * H);
    std::fill(out.begin(), out.end(), SampleResult{});
    std::atomic<size_t> count{0};
    if (!s.has_virtual()) {
        gathered = 0;
        return;
    }
    Shader shader(s, maps, diffuse_samples_);
    tbb::parallel_for(tbb::blocked_range<int>(0, H, 4), [&](const tbb::blocked_range<int>& rows) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return;
        size_t local = 0;
        glm::i64vec3 last_cell(INT64_MIN);
        bool last_reaches = false;
        auto reaches = [&](const vec3& p) {
            glm::i64vec3 c = maps.real.cell_of(p);
            if (c != last_cell) last_cell = c, last_reaches = maps.real.reaches_cell(c);
            return last_reaches;
        };
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < W; ++x) {
                size_t i = size_t(y) * W + x;
                // Pixels no photon cell can reach keep the photo: no ray, no gather.
                if (!cache_.near_virtual[i] && !(cache_.has_real[i] && reaches(cache_.real_point[i]))) continue;
                Rng rng = Rng::keyed(seed_, uint64_t(pass) * 2 + 1, i);
                const vec2 j = camera_jitter(seed_, pass, i);
                const float jx = j.x, jy = j.y;
                out[i] = shader.shade_camera(x, y, float(x) + jx, float(y) + jy, rng);
                ++local;
            }
        count += local;
    });
    gathered = count.load();
}

PhotonStats ProgressiveRenderer::build_pass_maps(int pass, PassMaps& maps, const std::atomic<bool>* cancel) const {
    PhotonPass photons = trace_photons(*scene_, seed_, uint64_t(pass), photons_per_pass_, cancel);
    maps.radius = radius_for_pass(pass);
    maps.real.build(std::move(photons.real), maps.radius);
    maps.caustic.build(std::move(photons.caustic), maps.radius);
    return photons.stats;
}

bool ProgressiveRenderer::render_pass(const std::atomic<bool>* cancel) {
    auto t0 = std::chrono::steady_clock::now();
    const int pass = stats_.passes + 1;
    PassMaps maps;
    PhotonStats photon_stats = build_pass_maps(pass, maps, cancel);
    if (cancel && cancel->load()) return false;
    std::vector<SampleResult>& samples = samples_;
    size_t gathered = 0;
    shade_pass(pass, maps, samples, cancel, gathered);
    if (cancel && cancel->load()) return false;
    const size_t bad = sums_.add(samples);
    double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats_.passes = pass;
    stats_.seconds += dt;
    stats_.photons_emitted += photon_stats.emitted;
    stats_.photons_stored += photon_stats.stored_real + photon_stats.stored_caustic;
    stats_.rays += photon_stats.rays;
    stats_.photons_per_second = stats_.seconds > 0 ? double(stats_.photons_emitted) / stats_.seconds : 0;
    stats_.pixels_gathered = gathered;
    stats_.radius = maps.radius;
    stats_.non_finite_samples += bad;
    return true;
}

void ProgressiveRenderer::render_single_pass(int pass, Image& delta, Image& dL, Image& alpha) {
    PassMaps maps;
    build_pass_maps(pass, maps, nullptr);
    std::vector<SampleResult> samples;
    size_t gathered = 0;
    shade_pass(pass, maps, samples, nullptr, gathered);
    const int W = scene_->photo().width(), H = scene_->photo().height();
    delta = Image(W, H);
    dL = Image(W, H);
    alpha = Image(W, H);
    for (size_t i = 0; i < samples.size(); ++i) {
        delta[i] = samples[i].delta;
        dL[i] = samples[i].dL;
        alpha[i] = vec3(samples[i].alpha);
    }
}

Image ProgressiveRenderer::image() const {
    Image out = scene_->photo();
    if (stats_.passes == 0) return out;
    for (size_t i = 0; i < out.size(); ++i) {
        if (sums_.untouched(i)) continue;  // untouched pixels stay bit-exact
        vec3 v = out[i] + vec3(sums_.mean_delta(i));
        out[i] = is_finite(v) ? v : out[i];
    }
    return out;
}

Image ProgressiveRenderer::delta_layer() const {
    Image out(scene_->photo().width(), scene_->photo().height());
    if (stats_.passes == 0) return out;
    for (size_t i = 0; i < out.size(); ++i) out[i] = vec3(sums_.mean_dL(i));
    return out;
}

Image ProgressiveRenderer::alpha_layer() const {
    Image out(scene_->photo().width(), scene_->photo().height());
    if (stats_.passes == 0) return out;
    for (size_t i = 0; i < out.size(); ++i) out[i] = vec3(float(sums_.mean_alpha(i)));
    return out;
}

Image shadow_matte(const Image& photo, const Image& dL) {
    Image out(photo.width(), photo.height());
    for (size_t i = 0; i < out.size(); ++i) {
        double lp = luminance(photo[i]), dl = luminance(dL[i]);
        double m = (dl < 0 && lp > 0) ? std::min(1.0, -dl / lp) : 0.0;
        out[i] = vec3(std::isfinite(m) ? float(m) : 0.0f);
    }
    return out;
}

double ProgressiveRenderer::skipped_fraction() const {
    if (stats_.pixels_total == 0) return 0;
    return 1.0 - double(stats_.pixels_gathered) / double(stats_.pixels_total);
}

}  // namespace dp
