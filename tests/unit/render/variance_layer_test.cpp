// The renderer's own estimate of each pixel's noise (what blend_by_noise weighs the denoiser
// against): unknown before two passes, matching the scatter between two independent renders,
// and falling at least as 1 / passes.
#include <gtest/gtest.h>

#include "common/test_scenes.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

namespace {

std::shared_ptr<RenderScene> shadow_scene() {
    SunProbe sun;
    Project p = look_at_project(vec3(0, 3, 4), vec3(0, 0.5f, 0), 45);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(vec3(0, 0.5f, 0), 0.5f, diffuse(vec3(0.5f))));
    return build(p, Image(64, 48, vec3(0.2f)), sun.image());
}

RenderSettings fixed(uint64_t seed) {
    RenderSettings s = settings(20000, seed);
    s.adaptive_threshold = 0;  // every tile gets every pass
    return s;
}

// Mean over the pixels either render changed of the variance layer, and of the squared
// luminance difference of the two renders' images.
void measure(const ProgressiveRenderer& a, const ProgressiveRenderer& b, double& variance, double& scatter) {
    const Image va = a.variance_layer(), ia = a.image(), ib = b.image();
    const Image& photo = a.scene().photo();
    variance = scatter = 0;
    int n = 0;
    for (size_t i = 0; i < ia.size(); ++i) {
        if (ia[i] == photo[i] && ib[i] == photo[i]) continue;
        const double d = double(luminance(ia[i])) - double(luminance(ib[i]));
        variance += va[i].x;
        scatter += d * d;
        ++n;
    }
    ASSERT_GT(n, 200);
    variance /= n;
    scatter /= n;
}

}  // namespace

TEST(VarianceLayer, IsUnknownBeforeTwoPassesThenMatchesTheScatterOfIndependentRendersAndFalls) {
    auto scene = shadow_scene();
    ProgressiveRenderer a(scene, fixed(1)), b(scene, fixed(2));
    ASSERT_TRUE(a.render_pass());
    ASSERT_TRUE(b.render_pass());
    EXPECT_TRUE(a.variance_layer().empty());
    for (int i = 1; i < 4; ++i) ASSERT_TRUE(a.render_pass() && b.render_pass());
    double v4 = 0, s4 = 0;
    measure(a, b, v4, s4);
    // Two independent means differ by twice each one's variance, on average.
    EXPECT_GT(v4, 0.0);
    EXPECT_NEAR(s4 / (2 * v4), 1.0, 0.5) << "variance " << v4 << " scatter " << s4;
    for (int i = 4; i < 16; ++i) ASSERT_TRUE(a.render_pass() && b.render_pass());
    double v16 = 0, s16 = 0;
    measure(a, b, v16, s16);
    // At least as fast as 1 / passes (the passes' low-discrepancy points do better than that).
    EXPECT_LT(v16 / v4, 0.25 * 1.5);
    EXPECT_GT(v16 / v4, 0.02);
    EXPECT_NEAR(s16 / (2 * v16), 1.0, 0.5) << "variance " << v16 << " scatter " << s16;
}
