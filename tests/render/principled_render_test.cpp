// The principled material in every renderer: its limits against the materials it generalises
// (a smooth metal is the mirror, a plain base the diffuse material), and a rough metal ball's
// differential render against the reference path tracer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/test_scenes.h"
#include "reference/path_tracer.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kW = 48, kH = 36;

Image sun_sky(float sun = 300.0f, float size_deg = 6.0f) {
    return make_sun_sky_probe(128, 64, glm::normalize(vec3(1, 1.3f, 0.4f)), vec3(sun), size_deg,
                              vec3(0.2f, 0.35f, 0.8f), vec3(0.7f, 0.8f, 0.9f));
}

Project ball_on_floor(const Material& m) {
    Project p = look_at_project(vec3(0, 2.0f, 3.2f), vec3(-0.3f, 0.3f, 0), 40);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(vec3(0, 0.55f, 0), 0.5f, m));
    return p;
}

/// The path tracer's image of the real floor alone: the photograph.
Image photograph(const Project& p, const Image& probe, int spp) {
    SceneAssets assets;
    assets.photo = Image(kW, kH);
    assets.probe_latlong = probe;
    const RenderScene scene(p, assets);
    ReferenceOptions o;
    o.samples_per_pixel = spp;
    o.include_virtual = false;
    o.seed = 11;
    return render_reference(scene, o);
}

/// The differential renderer's composite of `p` over `photo`, and its alpha layer.
Image differential(const Project& p, const Image& photo, const Image& probe, int passes, Image* alpha = nullptr,
                   uint64_t seed = 3) {
    ProgressiveRenderer r(build(p, photo, probe), settings(60000, seed));
    for (int i = 0; i < passes; ++i) r.render_pass();
    if (alpha) *alpha = r.alpha_layer();
    return r.image();
}

/// RMS of the difference over pixels where either image differs from the photo by more than
/// 1% or the object covers, relative to the mean of `truth` there.
double relative_rmse(const Image& out, const Image& truth, const Image& photo, const Image& alpha, size_t* n) {
    double se = 0, sum = 0;
    *n = 0;
    for (size_t i = 0; i < out.size(); ++i) {
        const float change = std::abs(luminance(truth[i]) - luminance(photo[i]));
        if (change <= 0.01f * std::max(luminance(photo[i]), 1e-3f) && alpha[i].x == 0) continue;
        const vec3 d = out[i] - truth[i];
        se += glm::dot(d, d) / 3.0;
        sum += luminance(truth[i]);
        ++*n;
    }
    return *n ? std::sqrt(se / double(*n)) / (sum / double(*n)) : 1e9;
}

/// Mean squared difference per channel.
double mse(const Image& a, const Image& b) {
    double se = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const vec3 d = a[i] - b[i];
        se += glm::dot(d, d) / 3.0;
    }
    return se / double(a.size());
}

/// Two renders of each material with independent seeds: the squared difference between the
/// materials over what their own noise explains (about 1 when both estimate the same image,
/// above where one is biased).
double difference_over_noise(const Image& a1, const Image& a2, const Image& b1, const Image& b2) {
    return mse(a1, b1) / (0.5 * (mse(a1, a2) + mse(b1, b2)));
}

/// The mean luminance over the object's pixels.
double object_mean(const Image& img, const Image& alpha) {
    double sum = 0;
    size_t n = 0;
    for (size_t i = 0; i < img.size(); ++i)
        if (alpha[i].x > 0.5f) sum += luminance(img[i]), ++n;
    return n ? sum / double(n) : 0;
}

}  // namespace

namespace {

/// `principled` against the material it should render as (`same`), each rendered twice with
/// other seeds: their difference within 1.5 times what their own noise explains, and the
/// object's mean within `ratio_tolerance`.
void expect_renders_as(const char* what, const Material& same, const Material& principled, const Image& probe,
                       int photo_samples, int passes, double ratio_tolerance) {
    const Project ps = ball_on_floor(same), pp = ball_on_floor(principled);
    const Image photo = photograph(ps, probe, photo_samples);
    Image alpha;
    const Image s1 = differential(ps, photo, probe, passes, &alpha, 3), s2 = differential(ps, photo, probe, passes, nullptr, 4);
    const Image p1 = differential(pp, photo, probe, passes, nullptr, 5), p2 = differential(pp, photo, probe, passes, nullptr, 6);
    const double excess = difference_over_noise(p1, p2, s1, s2);
    const double ratio = object_mean(p1, alpha) / object_mean(s1, alpha);
    std::printf("%s: difference / noise %.3f, object mean ratio %.4f\n", what, excess, ratio);
    EXPECT_LT(excess, 1.5) << what;
    EXPECT_NEAR(ratio, 1.0, ratio_tolerance) << what;
}

}  // namespace

TEST(PrincipledRender, ASmoothMetalRendersAsTheMirror) {
    // A wide, dim sun: a mirror's image of a small bright one is a few pixels' lottery.
    // Schlick's Fresnel brightens the rim a little where the mirror keeps 0.9: 4%.
    expect_renders_as("smooth metal against the mirror", mirror(vec3(0.9f)), principled(vec3(0.9f), 1.0f, 0.01f),
                      sun_sky(10.0f, 20.0f), 64, 16, 0.04);
}

TEST(PrincipledRender, ABaseWithoutSpecularRendersAsTheDiffuseMaterial) {
    const vec3 albedo(0.6f, 0.5f, 0.4f);
    expect_renders_as("plain base against diffuse", diffuse(albedo), principled(albedo, 0.0f, 0.5f, 0.0f), sun_sky(),
                      64, 8, 0.03);
}

namespace {

/// The differential render of `p` (its photograph rendered first) against the reference path
/// tracer over the object and the real pixels it changes: relative RMSE and the object's mean
/// ratio within the given bounds.
void expect_matches_path_tracer(const char* what, const Project& p, const Image& probe, int samples, int passes,
                                double max_rmse, double ratio_tolerance) {
    const Image photo = photograph(p, probe, 256);
    SceneAssets assets;
    assets.photo = Image(kW, kH);
    assets.probe_latlong = probe;
    const RenderScene scene(p, assets);
    EXPECT_EQ(scene.has_transmissive(), p.objects[0].material.principled.transmission > 0) << what;
    ReferenceOptions o;
    o.samples_per_pixel = samples;
    o.seed = 12;
    const Image truth = render_reference(scene, o);
    Image alpha;
    const Image out = differential(p, photo, probe, passes, &alpha);
    size_t n = 0;
    const double rmse = relative_rmse(out, truth, photo, alpha, &n);
    const double ratio = object_mean(out, alpha) / object_mean(truth, alpha);
    std::printf("%s against the path tracer: %zu pixels, relative RMSE %.4f, object mean ratio %.4f\n", what, n,
                rmse, ratio);
    EXPECT_GT(n, 200u) << what;
    EXPECT_NEAR(ratio, 1.0, ratio_tolerance) << what;
    EXPECT_LT(rmse, max_rmse) << what;
}

}  // namespace

TEST(PrincipledRender, ARoughMetalBallMatchesThePathTracer) {
    // 0.08: the diffuse ball's figure in AgainstReference.
    expect_matches_path_tracer("rough metal", ball_on_floor(principled(vec3(0.9f, 0.7f, 0.4f), 1.0f, 0.4f)),
                               sun_sky(), 256, 16, 0.08, 0.04);
}

TEST(PrincipledRender, ARoughGlassBallMatchesThePathTracer) {
    // Light through the object: its shadow and caustic go to photons (Surface::transmits). A
    // large sun so that the path tracer finds the rough caustic by chance; 0.15: the glass
    // ball's figure in AgainstReference.
    Material m = principled(vec3(0.95f), 0.0f, 0.2f);
    m.principled.transmission = 1.0f;
    expect_matches_path_tracer("rough glass", ball_on_floor(m), sun_sky(100.0f, 8.0f), 2048, 32, 0.15, 0.05);
}

TEST(PrincipledRender, TheCameraSeesTheEmission) {
    // No reflection at all (black base, no specular): the object shows its emission exactly,
    // in the differential render and in the path tracer.
    Material m = principled(vec3(0.0f), 0.0f, 0.5f, 0.0f);
    m.principled.emission = vec3(1.0f, 2.0f, 3.0f);
    const Image probe = sun_sky();
    const Project p = ball_on_floor(m);
    const Image photo = photograph(p, probe, 16);
    Image alpha;
    const Image out = differential(p, photo, probe, 2, &alpha);
    SceneAssets assets;
    assets.photo = Image(kW, kH);
    assets.probe_latlong = probe;
    ReferenceOptions o;
    o.samples_per_pixel = 4;
    const Image truth = render_reference(RenderScene(p, assets), o);
    const double want = luminance(m.principled.emission);
    std::printf("emission: differential %.5f, path tracer %.5f, emitted %.5f\n", object_mean(out, alpha),
                object_mean(truth, alpha), want);
    EXPECT_NEAR(object_mean(out, alpha), want, 1e-3 * want);
    EXPECT_NEAR(object_mean(truth, alpha), want, 2e-2 * want);  // edge pixels see some floor
}

