#include "render/frame_plan.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "image/image_metrics.h"
#include "render/direct_change.h"
#include "assets/real_gloss.h"
#include "assets/scattering.h"

namespace dp {

double FramePlan::expected_direct_pixels() const {
    double sum = 0;
    for (float p : direct_probability) sum += p;
    return sum;
}

double pixels_per_area(const Camera& camera, const vec3& p, const vec3& n) {
    const Frame f(n);
    const float delta = 1e-3f * std::max(glm::length(p - camera.position()), 1e-30f);
    vec2 a, b, c;
    if (!camera.project(p, a) || !camera.project(p + delta * f.t, b) || !camera.project(p + delta * f.b, c)) return 0;
    const vec2 u = b - a, v = c - a;
    return std::abs(double(u.x) * v.y - double(u.y) * v.x) / (double(delta) * delta);
}

FramePlan build_frame_plan(const RenderScene& s, bool direct_by_rays, const std::atomic<bool>* cancel,
                           const PixelWindow* window) {
    FramePlan plan;
    const int W = s.photo().width(), H = s.photo().height();
    const size_t n = size_t(W) * H;
    plan.width = W;
    plan.height = H;
    plan.tiles_x = (W + FramePlan::kTile - 1) / FramePlan::kTile;
    plan.tiles_y = (H + FramePlan::kTile - 1) / FramePlan::kTile;
    const size_t tiles = size_t(plan.tiles_x) * plan.tiles_y;
    plan.kind.assign(n, FramePlan::PixelKind::Nothing);
    plan.direct_probability.assign(n, 0.0f);
    plan.splat_radius.assign(n, 0.0f);
    plan.tile_direct_max.assign(tiles, 0.0f);
    plan.tile_splat_min.assign(tiles, INFINITY);
    plan.tile_has_object.assign(tiles, 0);
    const Image& photo = s.photo();
    plan.value_floor = value_floor(photo);
    const float floor = plan.value_floor;
    if (!s.has_change()) return plan;

    // What a real surface behind an object could send, for the bound: the bright end of the
    // real surfaces in the photo, from every fourth pixel (the sky in the photo's background
    // belongs to the probe, bounded apart).
    float real_max = floor;
    if (direct_by_rays) {
        std::vector<float> values;
        for (int y = 0; y < H; y += 4)
            for (int x = 0; x < W; x += 4) {
                const Hit hit = s.intersect(s.camera_ray(float(x), float(y)));
                if (hit && !hit.surface->is_virtual) values.push_back(luminance(photo.at(x, y)));
            }
        if (!values.empty()) {
            const size_t q = std::min(values.size() - 1, size_t(0.99 * double(values.size())));
            std::nth_element(values.begin(), values.begin() + ptrdiff_t(q), values.end());
            real_max = std::max(real_max, values[q]);
        }
    }
    const DirectChange direct(s, real_max);
    const LightSet& lights = s.lights();
    std::vector<uint8_t> sees_virtual(n, 0);
    // A row at a time, so that an edit arriving meanwhile (a viewer's) does not wait for it all.
    auto cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
    tbb::parallel_for(0, H, [&](int y) {
        if (cancelled()) return;
        for (int x = 0; x < W; ++x) {
            if (window && !window->contains(x, y)) continue;
            const size_t i = size_t(y) * W + x;
            const Ray ray = s.camera_ray(float(x), float(y));
            const Hit hit = s.intersect(ray);
            // A holdout's occluder hides what lies beyond it (CameraGather::shade_camera).
            const float t_hold = s.holdout_t(ray);
            // An area light's face is drawn like an object.
            if (!lights.empty() && lights.emitted(ray, std::min(hit ? hit.t : INFINITY, t_hold)) != vec3(0)) {
                sees_virtual[i] = 1;
                continue;
            }
            if (!hit || hit.t > t_hold) continue;
            if (hit.surface->is_virtual) {
                sees_virtual[i] = 1;
                continue;
            }
            plan.kind[i] = FramePlan::PixelKind::Real;
            const vec3 n_facing = facing_normal(hit.ng, ray.dir);
            const double density = pixels_per_area(s.camera(), hit.p, n_facing);
            if (density > 0) plan.splat_radius[i] = float(std::sqrt(1.0 / (double(kPi) * density)));
            // A pixel a light can reach takes its light every pass, whatever the estimator.
            if (!lights.empty() && lights.irradiance_bound(hit.p, n_facing) > 0) {
                plan.direct_probability[i] = 1;
                continue;
            }
            // A glossy surface that may reflect an object takes the change of its reflection.
            if (hit.surface->gloss_f0 > 0) {
                const GlossLobe lobe(hit, ray.dir);
                bool reflects = false;
                for (const EmissionCluster& c : s.clusters()) reflects |= gloss_may_reflect(lobe, hit.p, c.center, c.radius);
                if (reflects) {
                    plan.direct_probability[i] = 1;
                    continue;
                }
            }
            if (!direct_by_rays) continue;
            const double bound = direct.bound(hit.p, n_facing);
            if (bound <= 0) continue;
            const double change = double(luminance(hit.surface->reflectance_at(hit.uv))) * kInvPi * bound;
            const double value = std::max(luminance(photo[i]), floor);
            plan.direct_probability[i] = float(std::min(1.0, change / (double(kDirectRouletteLevel) * value)));
        }
    });
    if (cancelled()) return FramePlan{};
    // Jittered samples may cross an object's edge within one pixel of a centre that sees it.
    tbb::parallel_for(0, H, [&](int y) {
        for (int x = 0; x < W; ++x) {
            bool near = false;
            for (int dy = -1; dy <= 1 && !near; ++dy)
                for (int dx = -1; dx <= 1 && !near; ++dx) {
                    const int xx = x + dx, yy = y + dy;
                    if (xx >= 0 && yy >= 0 && xx < W && yy < H) near = sees_virtual[size_t(yy) * W + xx];
                }
            if (near) plan.kind[size_t(y) * W + x] = FramePlan::PixelKind::NearVirtual;
        }
    });
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t i = size_t(y) * W + x;
            const int t = plan.tile_of(x, y);
            if (plan.kind[i] == FramePlan::PixelKind::NearVirtual) {
                plan.tile_has_object[t] = 1;
                plan.direct_probability[i] = 1;  // shaded in full every pass anyway
            }
            plan.tile_direct_max[t] = std::max(plan.tile_direct_max[t], plan.direct_probability[i]);
            if (plan.kind[i] == FramePlan::PixelKind::Real)
                plan.tile_splat_min[t] = std::min(plan.tile_splat_min[t], plan.splat_radius[i]);
        }
    for (size_t t = 0; t < tiles; ++t)
        if (plan.tile_direct_max[t] > 0) plan.direct_tiles.push_back(uint32_t(t));
    return plan;
}

}  // namespace dp
