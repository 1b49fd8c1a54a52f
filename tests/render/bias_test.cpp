// No bias left: against a path-traced truth of the same scene, the render's error smoothed over
// a few pixels (which keeps a bias and averages noise away) keeps falling as passes grow, down
// to the truth's own smoothed noise. The scene is one where errors used to stop falling: an
// object close to a wall, which hides light of other real surfaces from the wall and the
// floor, and whose own light on them depends on how much the wall behind it is darkened. (A
// glass ball's caustic is beyond what a path-traced truth resolves in a test's time; the
// benchmark's focused truths judge it.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/test_scenes.h"
#include "probe/synthetic_probe.h"
#include "reference/path_tracer.h"
#include "reference/standard_differential.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kW = 64, kH = 40;

/// Box-filters the luminance of a - b over (2k+1)^2 pixels.
std::vector<double> smoothed_difference(const Image& a, const Image& b, int k) {
    std::vector<double> d(a.size()), out(a.size());
    for (size_t i = 0; i < a.size(); ++i) d[i] = luminance(a[i]) - luminance(b[i]);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            double s = 0;
            int n = 0;
            for (int yy = std::max(0, y - k); yy <= std::min(kH - 1, y + k); ++yy)
                for (int xx = std::max(0, x - k); xx <= std::min(kW - 1, x + k); ++xx) s += d[size_t(yy) * kW + xx], ++n;
            out[size_t(y) * kW + x] = s / n;
        }
    return out;
}

double rms_over(const std::vector<double>& v, const std::vector<bool>& mask) {
    double s = 0;
    size_t n = 0;
    for (size_t i = 0; i < v.size(); ++i)
        if (mask[i]) s += v[i] * v[i], ++n;
    return n ? std::sqrt(s / double(n)) : 0.0;
}

struct Scene {
    std::shared_ptr<RenderScene> scene;
    RenderSettings settings;  ///< the project's
    Image truth_a, truth_b, truth;
    std::vector<bool> changed;
    double mean = 0;  ///< mean luminance of the truth over the changed pixels
};

/// The real-only photograph, then a truth in two independent halves: standard differential
/// rendering with correlated sampling, its samples focused on the changed pixels.
Scene make_scene(const Project& p, const Image& probe, int half_passes) {
    Scene s;
    s.settings = p.render;
    SceneAssets a;
    a.photo = Image(kW, kH);
    a.probe_latlong = probe;
    RenderScene tmp(p, a);
    ReferenceOptions real_only;
    real_only.samples_per_pixel = 1024;
    real_only.include_virtual = false;
    real_only.seed = 5;
    s.scene = build(p, render_reference(tmp, real_only), probe);
    auto half = [&](uint64_t seed) {
        auto scene = build(p, s.scene->photo(), probe);
        StandardDifferentialRenderer r(scene, settings(1, seed, p.render), StandardDifferentialRenderer::Sampling::Correlated, 16);
        r.focus_after(16);
        for (int i = 0; i < half_passes; ++i) r.render_pass();
        return std::pair{r.image(), r.alpha_layer()};
    };
    auto [ta, alpha_a] = half(101);
    auto [tb, alpha_b] = half(202);
    s.truth_a = ta;
    s.truth_b = tb;
    s.truth = Image(kW, kH);
    s.changed.resize(s.truth.size());
    size_t n = 0;
    for (size_t i = 0; i < s.truth.size(); ++i) {
        s.truth[i] = 0.5f * (ta[i] + tb[i]);
        const float photo = luminance(s.scene->photo()[i]);
        s.changed[i] = alpha_a[i].x + alpha_b[i].x > 0 ||
                       std::abs(luminance(s.truth[i]) - photo) > 0.01f * std::max(photo, 1e-3f);
        if (s.changed[i]) s.mean += luminance(s.truth[i]), ++n;
    }
    s.mean /= double(std::max<size_t>(1, n));
    return s;
}

/// Renders 64 passes and checks that the 5x5-smoothed error falls from 8 to 64 passes by at
/// least a third, unless it is already within 1.5 times the truth's own smoothed noise; and
/// that the mean signed error over the changed real pixels stays under 1%.
void expect_no_bias(const std::string& name, const Scene& s) {
    const double truth_noise = rms_over(smoothed_difference(s.truth_a, s.truth_b, 2), s.changed) / 2 / s.mean;
    ProgressiveRenderer r(s.scene, settings(60000, 9, s.settings));
    double at8 = 0, at64 = 0;
    for (int pass = 1; pass <= 64; ++pass) {
        ASSERT_TRUE(r.render_pass());
        if (pass != 8 && pass != 64) continue;
        const Image img = r.image();
        const double e = rms_over(smoothed_difference(img, s.truth, 2), s.changed) / s.mean;
        (pass == 8 ? at8 : at64) = e;
        if (pass == 64) {
            double signed_sum = 0;
            size_t n = 0;
            const Image alpha = r.alpha_layer();
            for (size_t i = 0; i < img.size(); ++i)
                if (s.changed[i] && alpha[i].x == 0)
                    signed_sum += luminance(img[i]) - luminance(s.truth[i]), ++n;
            const double mean_bias = signed_sum / double(std::max<size_t>(1, n)) / s.mean;
            std::printf("%s: smoothed error %.4f (8 passes) %.4f (64), truth's smoothed noise %.4f, mean "
                        "signed error over real changed pixels %+.4f\n",
                        name.c_str(), at8, at64, truth_noise, mean_bias);
            EXPECT_LT(std::abs(mean_bias), 0.01) << name;
        }
    }
    EXPECT_TRUE(at64 < 0.67 * at8 || at64 < 1.5 * truth_noise) << name;
}

Image sun_sky() {
    return make_sun_sky_probe(512, 256, glm::normalize(vec3(0.5f, 0.75f, 0.45f)), vec3(2000.0f), 2.0f,
                              vec3(0.12f, 0.2f, 0.45f), vec3(0.35f, 0.4f, 0.5f));
}

Project wall_scene(vec3 eye, vec3 target) {
    Project p = look_at_project(eye, target, 45);
    p.real.push_back(ground_plane(vec3(0.45f)));
    p.real.push_back(wall_proxy(-0.75f, vec3(0.75f)));
    p.render.adaptive_threshold = 0;
    return p;
}

}  // namespace

TEST(NoBias, ABoxCloseToAWallConvergesToThePathTracedTruth) {
    Project p = wall_scene(vec3(0.4f, 1.1f, 2.8f), vec3(0, 0.4f, -0.4f));
    VirtualObject box = sphere(vec3(0, 0.3f, -0.45f), 0.3f, diffuse(vec3(0.6f)));
    box.shape.kind = Shape::Kind::Box;
    box.shape.size = vec3(0.7f, 0.6f, 0.4f);
    p.objects.push_back(box);
    expect_no_bias("box by a wall", make_scene(p, sun_sky(), 160));
}
