#include "render/progressive.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "base/rng.h"
#include "base/sobol.h"
#include "image/image_metrics.h"
#include "render/render_limits.h"

namespace dp {

namespace {

constexpr int kTile = FramePlan::kTile;
constexpr size_t kTilePixels = size_t(kTile) * kTile;
/// Adaptive sampling looks at the tiles every this many passes.
constexpr int kConvergenceInterval = 4;

double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// A uniform number in [0, 1) from three integers: the roulette of one pixel in one pass.
float hash_uniform(uint64_t seed, uint64_t pass, uint64_t pixel) {
    return fixed_to_unit(uint32_t(hash_combine(hash_combine(seed ^ 0x726f756c65747465ull, pass), pixel) >> 32));
}

/// Calls f(pixel index, x, y, tile-local index) for the image pixels of tile t.
template <class F>
void for_tile_pixels(const FramePlan& plan, uint32_t t, F&& f) {
    const int x0 = int(t % uint32_t(plan.tiles_x)) * kTile, y0 = int(t / uint32_t(plan.tiles_x)) * kTile;
    const int x1 = std::min(x0 + kTile, plan.width), y1 = std::min(y0 + kTile, plan.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) f(size_t(y) * plan.width + x, x, y, size_t(y - y0) * kTile + (x - x0));
}

}  // namespace

ProgressiveRenderer::ProgressiveRenderer(std::shared_ptr<const RenderScene> scene, const RenderSettings& settings)
    : scene_(std::move(scene)), settings_(settings),
      photons_per_pass_(std::max<int64_t>(1, settings.photons_per_pass)), seed_(settings.seed) {
    const RenderSettings& rs = settings_;
    check_render_limits(*scene_, rs);  // before any allocation the settings size
    alpha_ = rs.alpha;
    split_ = rs.estimator == Estimator::Split;
    low_discrepancy_ = rs.low_discrepancy;
    if (rs.initial_radius && *rs.initial_radius > 0) {
        r1_ = *rs.initial_radius;
    } else {
        // About a hundred photons of a sunlit shadow inside the first gather disk.
        float rmax = 0;
        for (const EmissionCluster& c : scene_->clusters()) rmax = std::max(rmax, c.radius);
        // Lights alone: what they light lies about as far from the camera as they do. The scene's
        // scale here comes from the real proxies (a 40 m floor gave 1.1 m disks after 24 passes,
        // and the bounce light on a wall came out 10% short against the path tracer).
        if (rmax <= 0 && !scene_->lights().empty()) {
            const vec3 eye = scene_->camera().position();
            for (const PlacedLight& l : scene_->lights().lights())
                rmax = std::max(rmax, glm::length(l.position - eye));
            rmax = std::min(rmax, scene_->scale());
        }
        if (rmax <= 0) rmax = scene_->scale();
        r1_ = rmax * std::clamp(std::sqrt(100.0f / float(photons_per_pass_)), 0.004f, 0.2f);
    }
    if (scene_->has_virtual()) direct_.emplace(*scene_);
    ceiling_ = kErrorCeilingFactor * luminance_quantile(scene_->photo(), 0.999);
}

bool ProgressiveRenderer::ensure_plan(const std::atomic<bool>* cancel) {
    if (planned_) return true;
    // Built with the first pass, not in the constructor: it traces a ray per pixel, and a
    // viewer's edit must be able to stop it like any pass.
    FramePlan plan = build_frame_plan(*scene_, split_, cancel, window_ ? &*window_ : nullptr);
    if (plan.width == 0) return false;
    plan_ = std::move(plan);
    sums_ = TileAccumulator(plan_.width, plan_.height, kTile);
    const RenderSettings& rs = settings_;
    if (rs.balance_photons && split_ && rs.adaptive_threshold > 0) {
        const int64_t n = photons_per_pass_;
        // Not below a quarter: a few passes' variances miss a photon's rare paths (a 64th cost
        // the five-objects benchmark scene a third more error at equal time, an eighth 5-10%
        // on four scenes after 10 s).
        balance_.emplace(n, std::max(n / 4, std::min<int64_t>(n, 2000)), n, size_t(plan_.width) * plan_.height);
    }
    stats_.pixels_total = size_t(plan_.width) * plan_.height;
    stats_.tiles_total = plan_.tiles();
    size_t near = 0;
    for (FramePlan::PixelKind k : plan_.kind) near += k == FramePlan::PixelKind::NearVirtual;
    diffuse_samples_ = dp::camera_diffuse_samples(photons_per_pass_, near);
    planned_ = true;
    return true;
}

void ProgressiveRenderer::start_at_pass(int first) {
    if (first < 1) throw std::logic_error("start_at_pass: passes count from 1");
    if (settings_.adaptive_threshold > 0)
        throw std::logic_error("start_at_pass: adaptive sampling makes a pass depend on the passes before");
    if (stats_.passes > 0) throw std::logic_error("start_at_pass: passes were already rendered");
    first_pass_ = first;
}

float ProgressiveRenderer::radius_for_pass(int pass) const {
    double r2 = double(r1_) * r1_;
    for (int k = 1; k < pass; ++k) r2 *= (k + double(alpha_)) / (k + 1.0);
    return float(std::sqrt(r2));
}

PhotonStats ProgressiveRenderer::build_pass_maps(int pass, PassMaps& maps, const std::atomic<bool>* cancel,
                                                 RenderStats* timing) const {
    PhotonPassOptions options;
    options.max_depth = settings_.max_depth;
    options.direct_by_rays = split_;
    options.direct = direct_ ? &*direct_ : nullptr;
    options.emitter_radius = radius_for_pass(pass);
    auto t = std::chrono::steady_clock::now();
    PhotonPass photons = trace_photons(*scene_, seed_, uint64_t(pass), photons_per_pass_, cancel, options);
    if (timing) timing->trace_s = seconds_since(t);
    t = std::chrono::steady_clock::now();
    maps.radius = radius_for_pass(pass);
    maps.real.build(std::move(photons.real), maps.radius);
    maps.caustic.build(std::move(photons.caustic), maps.radius);
    if (timing) timing->maps_s = seconds_since(t);
    return photons.stats;
}

void ProgressiveRenderer::mark_photon_pixels(const PassMaps& maps, PassWork& work,
                                             std::vector<uint8_t>& photon_tile) const {
    const int W = plan_.width, H = plan_.height;
    work.photon_pixel.assign(size_t(W) * H, 0);
    photon_tile.assign(plan_.tiles(), 0);
    if (maps.real.empty()) return;
    std::vector<vec3> centres;
    maps.real.for_each_cell([&](const vec3& c) { centres.push_back(c); });
    const Camera& cam = scene_->camera();
    // A pixel can gather a photon of a cell when the point it sees lies within this of the
    // cell's centre: the cell's half diagonal plus the gather radius.
    const float reach = float(0.5 * std::sqrt(3.0) * maps.real.cell_size()) + maps.radius;
    const float focal = std::max(cam.fx(), cam.fy());
    std::atomic<bool> everything{false};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, centres.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
            const vec3& c = centres[k];
            const float z = (cam.rotation() * c + cam.translation()).z;
            if (z <= 2 * reach) {
                // At the lens its footprint is unbounded: mark the frame. Elsewhere near the
                // camera's plane it projects far outside the frame.
                if (glm::length(c - cam.position()) < 4 * reach) everything.store(true, std::memory_order_relaxed);
                continue;
            }
            vec2 px;
            if (!cam.project(c, px)) continue;
            // Margin for the sub-pixel jitter and for lens distortion's local magnification.
            const float rho = 1.25f * reach * focal / (z - reach) + 1.5f;
            // Clamped in float first: a cell far off the frame projects beyond int's range.
            auto to_int = [](float v) { return v == v ? int(std::clamp(v, -1e9f, 1e9f)) : 0; };
            const int x0 = std::max(0, to_int(std::floor(px.x - rho))), x1 = std::min(W - 1, to_int(std::ceil(px.x + rho)));
            const int y0 = std::max(0, to_int(std::floor(px.y - rho))), y1 = std::min(H - 1, to_int(std::ceil(px.y + rho)));
            for (int ty = y0 / kTile; ty <= y1 / kTile; ++ty)
                for (int tx = x0 / kTile; tx <= x1 / kTile; ++tx) {
                    const size_t t = size_t(ty) * plan_.tiles_x + tx;
                    // A tile whose real pixels all splat gathers nothing.
                    if (plan_.tile_splat_min[t] > maps.radius) continue;
                    std::atomic_ref<uint8_t>(photon_tile[t]).store(1, std::memory_order_relaxed);
                    for (int y = std::max(y0, ty * kTile); y <= std::min(y1, ty * kTile + kTile - 1); ++y)
                        for (int x = std::max(x0, tx * kTile); x <= std::min(x1, tx * kTile + kTile - 1); ++x) {
                            const size_t i = size_t(y) * W + x;
                            if (plan_.splat_radius[i] > maps.radius) continue;  // its photons are splatted
                            std::atomic_ref<uint8_t>(work.photon_pixel[i]).store(1, std::memory_order_relaxed);
                        }
                }
        }
    });
    if (everything.load())
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const size_t i = size_t(y) * W + x;
                if (plan_.splat_radius[i] > maps.radius) continue;
                work.photon_pixel[i] = 1;
                photon_tile[size_t(plan_.tile_of(x, y))] = 1;
            }
}

std::vector<ProgressiveRenderer::Splat> ProgressiveRenderer::splat_photons(const PassMaps& maps) const {
    const std::vector<Photon>& photons = maps.real.photons();
    if (photons.empty()) return {};
    const RenderScene& s = *scene_;
    const Camera& cam = s.camera();
    const int W = plan_.width, H = plan_.height;
    constexpr size_t kChunk = 4096;
    const size_t chunks = (photons.size() + kChunk - 1) / kChunk;
    std::vector<std::vector<Splat>> out(chunks);
    tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
        for (size_t k = c * kChunk; k < std::min(photons.size(), (c + 1) * kChunk); ++k) {
            const Photon& ph = photons[k];
            vec2 px;
            if (!cam.project(ph.position, px)) continue;
            const int x = int(std::lround(px.x)), y = int(std::lround(px.y));
            if (x < 0 || y < 0 || x >= W || y >= H) continue;
            const size_t i = size_t(y) * W + x;
            if (plan_.kind[i] != FramePlan::PixelKind::Real || plan_.splat_radius[i] <= maps.radius) continue;
            const vec3 to = ph.position - cam.position();
            const float dist = glm::length(to);
            const vec3 dir = to / dist;
            if (glm::dot(ph.normal, dir) >= 0) continue;  // the photon is on the far side of its surface
            // Seen from the camera: the first surface along the ray is the photon's.
            const Hit hit = s.intersect(Ray{cam.position(), dir}, dist * (1 + 1e-3f) + s.ray_epsilon());
            if (!hit || hit.surface->is_virtual || hit.t < dist * (1 - 1e-3f) - s.ray_epsilon()) continue;
            const double density = pixels_per_area(cam, ph.position, ph.normal);
            if (!(density > 0) || !std::isfinite(density)) continue;
            const dvec3 value = dvec3(ph.flux) * dvec3(hit.surface->reflectance_at(hit.uv)) * (double(kInvPi) * density);
            const uint32_t key = uint32_t(plan_.tile_of(x, y)) * uint32_t(kTilePixels) +
                                 uint32_t((y % kTile) * kTile + x % kTile);
            out[c].push_back({key, value});
        }
    });
    std::vector<Splat> all;
    for (const auto& v : out) all.insert(all.end(), v.begin(), v.end());
    // Stable: within a pixel the photons keep their order, so the sums do not depend on threads.
    std::stable_sort(all.begin(), all.end(), [](const Splat& a, const Splat& b) { return a.key < b.key; });
    std::vector<Splat> summed;
    for (const Splat& e : all) {
        if (!summed.empty() && summed.back().key == e.key)
            summed.back().value += e.value;
        else
            summed.push_back(e);
    }
    return summed;
}

ProgressiveRenderer::PassWork ProgressiveRenderer::plan_pass(int pass, const PassMaps& maps,
                                                             bool respect_stopped) const {
    PassWork work;
    std::vector<uint8_t> photon_tile;
    mark_photon_pixels(maps, work, photon_tile);
    work.splats = splat_photons(maps);
    for (const Splat& e : work.splats) photon_tile[e.key / kTilePixels] = 1;
    for (uint32_t t = 0; t < plan_.tiles(); ++t) {
        if (respect_stopped && !sums_.live(t)) continue;
        if (window_ && !window_->meets_tile(int(t % uint32_t(plan_.tiles_x)), int(t / uint32_t(plan_.tiles_x)), kTile))
            continue;
        // Roulette on the tile's largest probability; its pixels then keep their share of it.
        const float p = plan_.tile_direct_max[t];
        // Under the all-photon estimator only lights and gloss give a real pixel a probability.
        const bool direct = p > 0 &&
                            (p >= 1 || sobol_owen_2d(uint32_t(pass - 1), hash_combine(seed_ ^ 0x74696c65ull, t)).x < p);
        if (plan_.tile_has_object[t] || photon_tile[t] || direct) {
            work.tiles.push_back(t);
            work.direct_tile.push_back(direct);
        }
    }
    // Each work tile's run of splats (both lists are in tile order).
    work.splat_begin.resize(work.tiles.size() + 1);
    size_t e = 0;
    for (size_t k = 0; k < work.tiles.size(); ++k) {
        while (e < work.splats.size() && work.splats[e].key / kTilePixels < work.tiles[k]) ++e;
        work.splat_begin[k] = uint32_t(e);
    }
    work.splat_begin[work.tiles.size()] = uint32_t(work.splats.size());
    return work;
}

bool ProgressiveRenderer::shade_tiles(int pass, const PassMaps& maps, const PassWork& work,
                                      std::vector<SampleResult>& out, const std::atomic<bool>* cancel,
                                      size_t& shaded, size_t& direct) const {
    out.assign(work.tiles.size() * kTilePixels, SampleResult{});
    std::atomic<size_t> count{0}, direct_count{0};
    const CameraGather gather(*scene_, maps, diffuse_samples_, split_ && direct_ ? &*direct_ : nullptr, settings_.max_depth);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, work.tiles.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return;
        size_t local = 0, local_direct = 0;
        for (size_t k = r.begin(); k < r.end(); ++k) {
            const uint32_t t = work.tiles[k];
            const float tile_p = plan_.tile_direct_max[t];
            SampleResult* tile_out = &out[k * kTilePixels];
            for (uint32_t e = work.splat_begin[k]; e < work.splat_begin[k + 1]; ++e) {
                SampleResult& r0 = tile_out[work.splats[e].key % kTilePixels];
                r0.dL = r0.pixel_change = vec3(work.splats[e].value);
                r0.photon = float(luminance(work.splats[e].value));
            }
            for_tile_pixels(plan_, t, [&](size_t i, int x, int y, size_t slot) {
                const FramePlan::PixelKind kind = plan_.kind[i];
                if (kind == FramePlan::PixelKind::Nothing) return;
                CameraWork w;
                if (kind == FramePlan::PixelKind::Real) {
                    w.gather = work.photon_pixel[i] != 0;
                    const float p = plan_.direct_probability[i];
                    const bool picked = work.direct_tile[k] && p > 0 && hash_uniform(seed_, uint64_t(pass), i) * tile_p < p;
                    w.direct_weight = picked ? 1.0 / double(p) : 0.0;
                    if (!w.gather && !picked) return;  // the splat, if any, is the whole sample
                    local_direct += picked;
                }
                PixelSampler sampler = PixelSampler::for_pass(seed_, i, pass, low_discrepancy_);
                const vec2 j = sampler.next2d() - vec2(0.5f);
                Rng rng = rng_stream::camera(seed_, uint64_t(pass), i);
                const SampleResult splat = tile_out[slot];
                SampleResult r1 = gather.shade_camera(x, y, float(x) + j.x, float(y) + j.y, sampler, rng, w);
                r1.dL += splat.dL;
                r1.pixel_change += splat.pixel_change;
                r1.photon += splat.photon;
                tile_out[slot] = r1;
                ++local;
            });
        }
        count += local;
        direct_count += local_direct;
    });
    shaded = count.load();
    direct = direct_count.load();
    return !(cancel && cancel->load());
}

bool ProgressiveRenderer::render_pass(const std::atomic<bool>* cancel) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!ensure_plan(cancel)) return false;
    const int pass = first_pass_ + stats_.passes;
    RenderStats st = stats_;
    PassMaps maps;
    const PhotonStats photon_stats = build_pass_maps(pass, maps, cancel, &st);
    if (cancel && cancel->load()) return false;
    auto t = std::chrono::steady_clock::now();
    const PassWork work = plan_pass(pass, maps, true);
    st.mark_s = seconds_since(t);
    std::vector<SampleResult> samples;
    size_t shaded = 0, direct = 0;
    t = std::chrono::steady_clock::now();
    if (!shade_tiles(pass, maps, work, samples, cancel, shaded, direct)) return false;
    st.shade_s = seconds_since(t);
    t = std::chrono::steady_clock::now();
    std::atomic<size_t> bad{0};
    tbb::parallel_for(size_t(0), work.tiles.size(), [&](size_t k) {
        bad += sums_.add_tile(work.tiles[k], pass % 2 == 1, &samples[k * kTilePixels]);
    });
    sums_.finish_pass();
    update_convergence();
    st.photons_per_pass = photons_per_pass_;
    if (balance_) balance_photons(work, samples, photon_stats.rays, shaded);
    st.accumulate_s = seconds_since(t);
    st.passes = stats_.passes + 1;  // passes rendered here (pass - first_pass_ + 1)
    st.seconds += seconds_since(t0);
    st.photons_emitted += photon_stats.emitted;
    st.photons_stored += photon_stats.stored_real + photon_stats.stored_caustic;
    st.rays += photon_stats.rays;
    st.photons_per_second = st.seconds > 0 ? double(st.photons_emitted) / st.seconds : 0;
    st.pixels_gathered = shaded;
    st.direct_estimates = direct;
    st.tiles_shaded = work.tiles.size();
    st.radius = maps.radius;
    st.non_finite_samples += bad.load();
    st.estimated_rel_error = stats_.estimated_rel_error;
    st.mean_changed_value = stats_.mean_changed_value;
    st.tiles_stopped = stats_.tiles_stopped;
    st.photon_variance_share = balance_ ? balance_->photon_share() : -1.0;
    stats_ = st;
    return true;
}

bool ProgressiveRenderer::changed_pixel(size_t i, const dvec3& change, double before) const {
    return sums_.mean_alpha(i) > 0 || std::abs(luminance(change)) > 0.01 * std::max(before, double(plan_.value_floor));
}

void ProgressiveRenderer::balance_photons(const PassWork& work, const std::vector<SampleResult>& samples,
                                          uint64_t photon_rays, size_t shaded) {
    tbb::parallel_for(size_t(0), work.tiles.size(), [&](size_t k) {
        const SampleResult* tile = &samples[k * kTilePixels];
        for_tile_pixels(plan_, work.tiles[k], [&](size_t i, int, int, size_t slot) {
            const SampleResult& r = tile[slot];
            if (is_finite(r.pixel_change) && std::isfinite(r.photon))
                balance_->add(i, r.photon, luminance(r.pixel_change) - r.photon);
        });
    });
    if (!balance_->end_pass(photon_rays, shaded)) return;
    // Stopped tiles take no samples, which would read as noise: only live tiles count.
    photons_per_pass_ = balance_->decide([&](size_t i) {
        const int x = int(i % size_t(plan_.width)), y = int(i / size_t(plan_.width));
        return sums_.live(uint32_t((y / kTile) * plan_.tiles_x + x / kTile)) &&
               changed_pixel(i, sums_.mean_pixel_change(i), luminance(scene_->photo()[i]));
    });
}

double judged_value(double before, double change, double floor, double ceiling) {
    return std::min(std::max(before + change, floor), std::max(ceiling, floor));
}

void ProgressiveRenderer::update_convergence() {
    const RenderSettings& rs = settings_;
    const Image& photo = scene_->photo();
    const int passes = sums_.passes();
    const bool judge = rs.adaptive_threshold > 0 && passes >= rs.adaptive_min_passes &&
                       passes % kConvergenceInterval == 0;
    double e2_changed = 0, value_changed = 0;
    size_t changed = 0, stopped = 0;
    const float floor = plan_.value_floor;
    for (uint32_t t = 0; t < sums_.tiles(); ++t) {
        if (!sums_.touched(t)) continue;  // only touched tiles are ever stopped
        stopped += !sums_.live(t);
        double tile_e2 = 0, tile_value = 0;
        int n = 0;
        for_tile_pixels(plan_, t, [&](size_t i, int, int, size_t) {
            const dvec3 d = sums_.mean_pixel_change(i);
            const double before = luminance(photo[i]);
            const double value = judged_value(before, luminance(d), floor, ceiling_);
            const double e2 = passes >= 2 ? sums_.error2(i, before, ceiling_) : 0.0;
            tile_e2 += e2;
            tile_value += value;
            ++n;
            if (changed_pixel(i, d, before)) {
                e2_changed += e2;
                value_changed += value;
                ++changed;
            }
        });
        if (judge && sums_.live(t) && n > 0 && std::sqrt(tile_e2 / n) < rs.adaptive_threshold * (tile_value / n)) {
            sums_.stop(t);
            ++stopped;
        }
    }
    stats_.tiles_stopped = stopped;
    stats_.estimated_rel_error = passes < 2 ? -1.0 : changed ? std::sqrt(e2_changed / changed) / (value_changed / changed) : 0.0;
    stats_.mean_changed_value = changed ? value_changed / double(changed) : 0.0;
}

void ProgressiveRenderer::render_single_pass(int pass, Image& pixel_change, Image& dL, Image& alpha) {
    ensure_plan(nullptr);
    PassMaps maps;
    build_pass_maps(pass, maps, nullptr);
    const PassWork work = plan_pass(pass, maps, false);
    std::vector<SampleResult> samples;
    size_t shaded = 0, direct = 0;
    shade_tiles(pass, maps, work, samples, nullptr, shaded, direct);
    pixel_change = Image(plan_.width, plan_.height);
    dL = Image(plan_.width, plan_.height);
    alpha = Image(plan_.width, plan_.height);
    for (size_t k = 0; k < work.tiles.size(); ++k)
        for_tile_pixels(plan_, work.tiles[k], [&](size_t i, int, int, size_t slot) {
            const SampleResult& r = samples[k * kTilePixels + slot];
            pixel_change[i] = r.pixel_change;
            dL[i] = r.dL;
            alpha[i] = vec3(r.alpha);
        });
}

// Before the first pass there is no accumulator (its size comes with the frame plan): the photo
// and zero layers of the photo's size.
Image ProgressiveRenderer::image() const {
    return planned_ ? accumulated_image(scene_->photo(), sums_) : scene_->photo();
}

Image ProgressiveRenderer::dL_layer() const {
    return planned_ ? accumulated_dL(sums_) : Image(scene_->photo().width(), scene_->photo().height());
}

Image ProgressiveRenderer::alpha_layer() const {
    return planned_ ? accumulated_alpha(sums_) : Image(scene_->photo().width(), scene_->photo().height());
}

Image ProgressiveRenderer::variance_layer() const {
    if (!planned_ || sums_.passes() < 2) return {};
    const Image& photo = scene_->photo();
    Image out(photo.width(), photo.height());
    for (size_t i = 0; i < out.size(); ++i) out[i] = vec3(float(sums_.error2(i, luminance(photo[i]), ceiling_)));
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
