// The path tracer's depth limit cuts paths, never the light of the last vertex it shades.
#include <gtest/gtest.h>

#include "common/test_scenes.h"
#include "reference/path_tracer.h"

using namespace dp;
using namespace dp::test;

TEST(ReferenceDepth, WithOneBounceAGroundUnderAUniformSkyGetsAllItsDirectLight) {
    // A large plane under a sky of radiance L everywhere above the horizon: E = pi L, so the
    // plane's radiance is rho L. With max_depth 1 that is all direct light at the first vertex,
    // which must not lose the share that multiple importance sampling leaves to a bounce ray
    // that is never traced.
    const vec3 L(2.0f), rho(0.5f);
    Image sky(64, 32);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 64; ++x) sky.at(x, y) = L;
    Project p = look_at_project(vec3(0, 1, 0), vec3(0, 0, -0.5f), 30);
    p.real.push_back(ground_plane(rho, 2000.0f));
    auto scene = build(p, Image(32, 24), sky);
    for (int depth : {1, 2, 8}) {
        ReferenceOptions o;
        o.samples_per_pixel = 64;
        o.max_depth = depth;
        o.include_virtual = false;
        Image img = render_reference(*scene, o);
        double sum = 0;
        for (size_t i = 0; i < img.size(); ++i) sum += img[i].x;
        // Check: the image mean is rho L within 1% (the horizon is far outside the view).
        EXPECT_NEAR(sum / img.size(), rho.x * L.x, 0.01 * rho.x * L.x) << "max_depth " << depth;
    }
}
