// Extreme light: a sun a million times brighter than the sky, and a sun one degree above the
// horizon (a shadow sixty times longer than the object).
#include <gtest/gtest.h>

#include <cstdio>

#include "render/photon_tracer.h"
#include "render/stress_common.h"

using namespace dp;
using namespace dp::test;

TEST(ExtremeLight, ASunAMillionTimesTheSkyGivesAFiniteImageThatMatchesThePathTracer) {
    // One-pixel sun of radiance 1e6 over a uniform sky of radiance 1: the sun gives ~99% of the
    // ground's irradiance, the sky the soft part of the shadow. Sampling by flux must find both.
    Image probe = make_sun_sky_probe(256, 128, glm::normalize(vec3(1, 1.2f, 0.5f)), vec3(1e6f), 0.1f,
                                     vec3(1.0f), vec3(1.0f));
    Project p = look_at_project(vec3(0, 2.0f, 3.2f), vec3(-0.3f, 0.3f, 0), 40);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(vec3(0, 0.55f, 0), 0.5f, diffuse(vec3(0.6f, 0.5f, 0.4f))));
    TruthAndRender t = render_against_truth(p, probe, 64, 48, 256, 16, 200000);
    // Check 1: nothing non-finite anywhere, no sample discarded.
    EXPECT_EQ(count_non_finite(t.render), 0u);
    EXPECT_EQ(count_non_finite(t.truth), 0u);
    EXPECT_EQ(t.non_finite_samples, 0u);
    // Check 2: over the changed pixels the render is the path-traced truth within 8% RMSE.
    std::vector<bool> changed = changed_pixels(t);
    size_t n = std::count(changed.begin(), changed.end(), true);
    double e = relative_rmse(t.render, t.truth, [&](size_t i) { return changed[i]; });
    std::printf("sun 1e6 x sky: relative RMSE over %zu changed pixels: %.4f\n", n, e);
    EXPECT_GT(n, 300u);
    EXPECT_LT(e, 0.08);
    // Check 3 (energy bound): in the umbra only the sky's ~1% remains, and the photon noise of
    // the removed sunlight is larger than that per pixel, so the bound is on the mean: the
    // shadow removes no more light than there is (mean >= 0) and adds none (mean <= truth).
    // The render may sit below the truth there: light that reaches the sphere after a real
    // bounce is not traced (photons whose first hit is real are dropped, method.md).
    double sum_render = 0, sum_truth = 0, sum_photo = 0;
    size_t umbra = 0;
    for (size_t i = 0; i < t.render.size(); ++i) {
        const float lp = luminance(t.photo[i]);
        if (t.alpha[i].x > 0 || lp <= 0 || luminance(t.truth[i]) > 0.05f * lp) continue;
        sum_render += luminance(t.render[i]);
        sum_truth += luminance(t.truth[i]);
        sum_photo += lp;
        ++umbra;
    }
    std::printf("umbra: %zu pixels, mean photo %.4g, truth %.4g, render %.4g\n", umbra, sum_photo / umbra,
                sum_truth / umbra, sum_render / umbra);
    ASSERT_GT(umbra, 20u);
    EXPECT_GE(sum_render, 0.0);
    EXPECT_LE(sum_render / umbra, sum_truth / umbra + 0.003 * sum_photo / umbra);
}

namespace {

/// A sun 0.97 degrees above the horizon along +X: a 2048 x 1024 probe so the pixel is small.
SunProbe grazing_sun() {
    SunProbe sun;
    sun.width = 2048;
    sun.height = 1024;
    sun.px = 1536;
    sun.py = 506;
    sun.radiance = vec3(2e5f);
    return sun;
}

struct GrazingScene {
    SunProbe sun = grazing_sun();
    vec3 center{0, 0.5f, 0};
    float radius = 0.5f;  // resting on the ground
    int w = 160, h = 120;
    // Looking down on the shadow from 10 m up, about 14 m behind the sphere.
    Project project = look_at_project(vec3(-14, 10, 8), vec3(-14, 0, 0), 60);
    std::shared_ptr<RenderScene> scene;
    GrazingScene() {
        project.real.push_back(ground_plane(vec3(0.5f), 400.0f));  // the shadow is ~60 m long
        // Black: no bounce light, so everything the sphere changes on the ground is its shadow.
        project.objects.push_back(sphere(center, radius, diffuse(vec3(0.0f))));
        // The shadow is stretched 57 times along the ground, so photons are sparse there: a
        // 15 cm gather keeps ~250 photons a pass in the disk while staying inside the umbra.
        project.render.initial_radius = 0.15f;
        scene = build(project, analytic_ground_photo(project, w, h, sun, vec3(0.5f)), sun.image());
    }
    float line_distance(vec3 x) const {
        return distance_to_line(center, x, sun.direction());
    }
};

}  // namespace

TEST(ExtremeLight, ASunOneDegreeAboveTheHorizonCastsTheWholeLongShadowAndNoLeaks) {
    GrazingScene g;
    const float elevation = glm::degrees(std::asin(g.sun.direction().y));
    ASSERT_GT(elevation, 0.9f);
    ASSERT_LT(elevation, 1.05f);
    // Check 1: the negative flux on the ground is the flux through the sphere's cross-section:
    // no shadow photon is lost to an offset or slips through the ground at grazing incidence.
    const int64_t N = 1000000;
    PhotonPass pass = trace_photons(*g.scene, 21, 1, N);
    double negative = 0, photon_flux = 0;
    int64_t n_negative = 0;
    for (const Photon& ph : pass.real)
        if (ph.flux.x < 0 && ph.normal.y > 0.99f) {
            negative += ph.flux.x;
            photon_flux = -ph.flux.x;
            ++n_negative;
        }
    ASSERT_GT(n_negative, 1000);
    const double expected = g.sun.normal_irradiance() * kPi * g.radius * g.radius;
    const double q = double(n_negative) / N;
    const double sigma = photon_flux * std::sqrt(N * q * (1 - q));
    EXPECT_NEAR(-negative, expected, 4 * sigma) << "sigma " << sigma;

    // Check 2: deep in the umbra (tens of metres away) the output is black, so -dL / photo is
    // 1 on average and no pixel keeps more than 15% of the photo (a leak; the photon noise
    // per pixel is ~3%).
    ProgressiveRenderer r(g.scene, settings(200000, 4, g.project.render));
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(r.render_pass());
    Image out = r.image(), dL = r.dL_layer();
    EXPECT_EQ(count_non_finite(out), 0u);
    EXPECT_EQ(r.stats().non_finite_samples, 0u);
    const Camera& cam = g.scene->camera();
    double sum_ratio = 0;
    int count = 0;
    float farthest = 0;
    for (int y = 0; y < g.h; ++y)
        for (int x = 0; x < g.w; ++x) {
            Ray ray = cam.generate_ray(float(x), float(y));
            if (ray.dir.y >= 0) continue;
            vec3 pt = ray.org + ray.dir * (-ray.org.y / ray.dir.y);
            if (g.line_distance(pt) > 0.6f * g.radius || pt.x > -2.0f) continue;
            if (g.scene->intersect_virtual(ray)) continue;
            float photo = g.scene->photo().at(x, y).x;
            ASSERT_GT(photo, 0);
            sum_ratio += -dL.at(x, y).x / photo;
            EXPECT_LT(out.at(x, y).x / photo, 0.15f) << "pixel " << x << "," << y << " at x=" << pt.x;
            farthest = std::min(farthest, pt.x);
            ++count;
        }
    std::printf("grazing sun: %d umbra pixels out to x = %.1f m, mean -dL/photo %.4f\n", count, farthest,
                sum_ratio / std::max(count, 1));
    ASSERT_GT(count, 100);
    EXPECT_LT(farthest, -10.0f);  // the umbra seen stretches tens of radii
    EXPECT_NEAR(sum_ratio / count, 1.0, 0.03);
    // Check 3: lit ground away from the shadow keeps the photo exactly (no stray photons).
    size_t stray = 0;
    for (int y = 0; y < g.h; ++y)
        for (int x = 0; x < g.w; ++x) {
            Ray ray = cam.generate_ray(float(x), float(y));
            if (ray.dir.y >= 0) continue;
            vec3 pt = ray.org + ray.dir * (-ray.org.y / ray.dir.y);
            if (g.line_distance(pt) < 3 * g.radius || glm::length(pt - g.center) < 3 * g.radius) continue;
            stray += out.at(x, y) != g.scene->photo().at(x, y);
        }
    EXPECT_EQ(stray, 0u);
}
