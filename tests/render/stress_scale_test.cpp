// The same scene in millimetres, metres and kilometres. Ray offsets, gather radii and photon
// flux all scale with the scene, so with the same seed the images agree up to float rounding:
// any absolute epsilon left in the renderer shows up as a difference here.
#include <gtest/gtest.h>

#include <cstdio>

#include "render/stress_common.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kW = 96, kH = 72;

Image sun_sky() {
    return make_sun_sky_probe(256, 128, glm::normalize(vec3(1, 1.3f, 0.4f)), vec3(400.0f), 4.0f,
                              vec3(0.2f, 0.35f, 0.8f), vec3(0.7f, 0.8f, 0.9f));
}

/// Ground, a wall, a diffuse sphere, a glass sphere and a mirror box, all scaled by `s`
/// (camera included): every kind of ray offset (diffuse, specular, photon, shadow) is used.
Project scaled_project(float s) {
    Project p = look_at_project(vec3(0, 2.0f, 3.2f) * s, vec3(-0.1f, 0.3f, 0) * s, 45);
    p.real.push_back(ground_plane(vec3(0.5f), 40.0f * s));
    RealProxy wall;
    wall.name = "wall";
    wall.shape.kind = Shape::Kind::Box;
    wall.shape.size = vec3(4.0f, 2.0f, 0.2f) * s;
    wall.transform.translation = vec3(0, 1.0f, -1.2f) * s;
    wall.albedo.rgb = vec3(0.7f, 0.3f, 0.2f);
    p.real.push_back(wall);
    p.objects.push_back(sphere(vec3(-0.7f, 0.45f, 0) * s, 0.45f * s, diffuse(vec3(0.6f, 0.5f, 0.4f))));
    p.objects.push_back(sphere(vec3(0.5f, 0.35f, 0.3f) * s, 0.35f * s, glass(1.5f)));
    VirtualObject box;
    box.name = "mirror box";
    box.shape.kind = Shape::Kind::Box;
    box.shape.size = vec3(0.5f, 0.6f, 0.5f) * s;
    box.transform.translation = vec3(0.3f, 0.3f, -0.6f) * s;
    box.transform.rotation_deg = vec3(0, 30, 0);
    box.material = mirror();
    p.objects.push_back(box);
    return p;
}

/// Differential render of the scene at scale `s` on a photograph shared by all scales.
Image render_at_scale(float s, const Image& photo, const Image& probe, Image* alpha = nullptr) {
    auto scene = build(scaled_project(s), photo, probe);
    ProgressiveRenderer r(scene, settings(100000, 5));
    for (int i = 0; i < 4; ++i) EXPECT_TRUE(r.render_pass());
    EXPECT_EQ(r.stats().non_finite_samples, 0u) << "scale " << s;
    if (alpha) *alpha = r.alpha_layer();
    return r.image();
}

Image reference_at_scale(float s, const Image& probe, bool include_virtual) {
    SceneAssets a;
    a.photo = Image(kW, kH);
    a.probe_latlong = probe;
    RenderScene scene(scaled_project(s), a);
    ReferenceOptions o;
    o.samples_per_pixel = 16;
    o.include_virtual = include_virtual;
    o.seed = 9;
    return render_reference(scene, o);
}

}  // namespace

TEST(ScaleInvariance, MillimetreAndKilometreScenesRenderAsTheMetreSceneWithinOnePercent) {
    const Image probe = sun_sky();
    const Image photo = reference_at_scale(1.0f, probe, false);
    Image alpha;
    const Image metre = render_at_scale(1.0f, photo, probe, &alpha);
    // Check: the pixels the objects change (or cover) at 1 m agree within 1% relative RMSE,
    // and no pixel at any scale is NaN/Inf.
    auto changed = [&](size_t i) { return alpha[i].x > 0 || metre[i] != photo[i]; };
    size_t n_changed = 0;
    for (size_t i = 0; i < photo.size(); ++i) n_changed += changed(i);
    ASSERT_GT(n_changed, photo.size() / 4);
    EXPECT_EQ(count_non_finite(metre), 0u);
    for (float s : {1e-3f, 1e4f}) {
        Image other = render_at_scale(s, photo, probe);
        EXPECT_EQ(count_non_finite(other), 0u) << "scale " << s;
        double e = relative_rmse(other, metre, changed);
        std::printf("scale %g: relative RMSE against 1 m over %zu changed pixels: %.2e\n", s, n_changed, e);
        EXPECT_LT(e, 0.01) << "scale " << s;
    }
}

TEST(ScaleInvariance, ThePathTracedTruthAtMillimetreAndKilometreScaleMatchesTheMetreOne) {
    const Image probe = sun_sky();
    const Image metre = reference_at_scale(1.0f, probe, true);
    // Check: whole-image relative RMSE below 1% (same seed: only rounding differs), all finite.
    EXPECT_EQ(count_non_finite(metre), 0u);
    for (float s : {1e-3f, 1e4f}) {
        Image other = reference_at_scale(s, probe, true);
        EXPECT_EQ(count_non_finite(other), 0u) << "scale " << s;
        double e = relative_rmse(other, metre);
        std::printf("scale %g: reference relative RMSE against 1 m: %.2e\n", s, e);
        EXPECT_LT(e, 0.01) << "scale " << s;
    }
}

TEST(ScaleInvariance, APathTracedGroundAloneIsLitWithoutSelfShadowingSpecklesAtEveryScale) {
    // No virtual object at all: the scene's size must come from something else than the objects.
    // Check: no ground pixel 10% darker than the analytic rho/pi E cos (a single-pixel sun: the
    // next-event estimate varies by ~1% within the pixel; one self-shadowed sample of four
    // takes 25% off).
    SunProbe sun;
    sun.py = 200;  // about 20 degrees above the horizon: grazing enough to expose bad offsets
    const vec3 albedo(0.5f);
    for (float s : {1e-3f, 1.0f, 1e4f}) {
        Project p = look_at_project(vec3(0, 2.0f, 3.2f) * s, vec3(0, 0, 0), 60);
        p.real.push_back(ground_plane(albedo, 40.0f * s));
        SceneAssets a;
        a.photo = Image(kW, kH);
        a.probe_latlong = sun.image();
        RenderScene scene(p, a);
        ReferenceOptions o;
        o.samples_per_pixel = 4;
        o.include_virtual = false;
        Image img = render_reference(scene, o);
        Image expected = analytic_ground_photo(p, kW, kH, sun, albedo);
        size_t dark = 0, checked = 0;
        const Camera& cam = scene.camera();
        for (size_t i = 0; i < img.size(); ++i) {
            if (expected[i].x <= 0) continue;
            // Only pixels whose whole footprint lands well inside the plane.
            Ray r = cam.generate_ray(float(i % kW), float(i / kW));
            vec3 x = r.org + r.dir * (-r.org.y / r.dir.y);
            if (std::max(std::abs(x.x), std::abs(x.z)) > 15.0f * s) continue;
            if (img[i].x < 0.9f * expected[i].x) ++dark;
            ++checked;
        }
        ASSERT_GT(checked, img.size() / 2);
        EXPECT_LT(dark, checked / 200) << "scale " << s << ": " << dark << " of " << checked
                                       << " ground pixels darker than the analytic value";
    }
}
