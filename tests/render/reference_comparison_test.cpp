// The differential engine against the reference path tracer: the photograph is the path
// tracer's image of the real proxies, the truth its image with the virtual object.
#include <gtest/gtest.h>

#include <cmath>

#include "reference/path_tracer.h"
#include "render/progressive.h"
#include "common/test_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {

struct Comparison {
    double rel_rmse_changed = 0;  ///< over pixels the object changes by more than 1%
    size_t changed = 0;
};

Comparison compare(const Project& p, const Image& probe, int w, int h, int spp, int passes, int64_t photons) {
    SceneAssets assets;
    assets.photo = Image(w, h);
    assets.probe_latlong = probe;
    auto tmp = std::make_shared<RenderScene>(p, assets);
    ReferenceOptions real_only;
    real_only.samples_per_pixel = spp;
    real_only.include_virtual = false;
    real_only.seed = 11;
    Image photo = render_reference(*tmp, real_only);
    ReferenceOptions with_virtual = real_only;
    with_virtual.include_virtual = true;
    with_virtual.seed = 12;
    Image truth = render_reference(*tmp, with_virtual);

    auto scene = build(p, photo, probe);
    ProgressiveRenderer r(scene, settings(photons, 3));
    for (int i = 0; i < passes; ++i) r.render_pass();
    Image out = r.image();
    Comparison c;
    double se = 0, sum_truth = 0;
    for (size_t i = 0; i < out.size(); ++i) {
        float change = std::abs(luminance(truth[i]) - luminance(photo[i]));
        if (change <= 0.01f * std::max(luminance(photo[i]), 1e-3f) && r.alpha_layer()[i].x == 0) continue;
        vec3 d = out[i] - truth[i];
        se += glm::dot(d, d) / 3.0;
        sum_truth += luminance(truth[i]);
        ++c.changed;
    }
    c.rel_rmse_changed = std::sqrt(se / c.changed) / (sum_truth / c.changed);
    return c;
}

Project base(Material m) {
    Project p = look_at_project(vec3(0, 2.0f, 3.2f), vec3(-0.3f, 0.3f, 0), 40);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(vec3(0, 0.55f, 0), 0.5f, m));
    return p;
}

}  // namespace

TEST(AgainstReference, ADiffuseSphereShadowMatchesThePathTracer) {
    Image probe = make_sun_sky_probe(256, 128, glm::normalize(vec3(1, 1.3f, 0.4f)), vec3(600.0f), 4.0f,
                                     vec3(0.2f, 0.35f, 0.8f), vec3(0.7f, 0.8f, 0.9f));
    Comparison c = compare(base(diffuse(vec3(0.6f, 0.5f, 0.4f))), probe, 64, 48, 512, 24, 200000);
    std::printf("diffuse: relative RMSE over %zu changed pixels: %.4f\n", c.changed, c.rel_rmse_changed);
    EXPECT_GT(c.changed, 300u);
    EXPECT_LT(c.rel_rmse_changed, 0.08);
}

TEST(AgainstReference, AGlassSphereCausticMatchesThePathTracer) {
    // A large sun so the path tracer can find the caustic by chance.
    Image probe = make_sun_sky_probe(256, 128, glm::normalize(vec3(1, 1.3f, 0.4f)), vec3(100.0f), 8.0f,
                                     vec3(0.2f, 0.35f, 0.8f), vec3(0.7f, 0.8f, 0.9f));
    Comparison c = compare(base(glass(1.5f)), probe, 64, 48, 2048, 24, 200000);
    std::printf("glass: relative RMSE over %zu changed pixels: %.4f\n", c.changed, c.rel_rmse_changed);
    EXPECT_GT(c.changed, 300u);
    EXPECT_LT(c.rel_rmse_changed, 0.15);
}
