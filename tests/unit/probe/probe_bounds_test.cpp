#include <gtest/gtest.h>

#include <cmath>

#include "base/euler.h"
#include "base/rng.h"
#include "base/sampling.h"
#include "probe/probe_bounds.h"
#include "probe/synthetic_probe.h"
#include "probe_test_util.h"

using namespace dp;

TEST(ProbeMaxGrid, NoPixelInsideTheConeIsBrighterThanTheBound) {
    // Random probes, rotations and cones, checked against every pixel whose centre lies inside.
    Rng rng(21, 1);
    for (int trial = 0; trial < 200; ++trial) {
        const int w = 96, h = 48;
        Image img = test::random_probe(w, h, uint64_t(trial), 3, 8.0f, 0.1f);
        Probe probe(img, euler_xyz_deg(vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 360.0f), 1.3f);
        ProbeMaxGrid grid(probe, 16, 8);
        const vec3 axis = sample_uniform_sphere(vec2(rng.uniform(), rng.uniform()));
        const float beta = 0.8f * rng.uniform() * rng.uniform();
        float truth = 0;
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                const vec3 d = probe.to_world(latlong_direction((i + 0.5f) / w, (j + 0.5f) / h));
                if (glm::dot(d, axis) >= std::cos(beta))
                    truth = std::max(truth, luminance(probe.pixel_radiance(size_t(j) * w + i)));
            }
        // Any direction in the cone reads its nearest pixel, whose centre may lie just outside.
        const Frame f(axis);
        for (int k = 0; k < 2000; ++k) {
            const float c = 1 - rng.uniform() * (1 - std::cos(beta)), s = std::sqrt(std::max(0.0f, 1 - c * c));
            const float a = 2 * kPi * rng.uniform();
            truth = std::max(truth, luminance(probe.radiance(f.to_world(vec3(s * std::cos(a), s * std::sin(a), c)))));
        }
        ASSERT_GE(grid.max_in_cone(axis, beta), truth) << "trial " << trial << " beta " << beta;
        ASSERT_LE(grid.max_in_cone(axis, beta), grid.global_max());
    }
}

TEST(ProbeMaxGrid, ASmallConeAwayFromTheSunIgnoresTheSun) {
    const int w = 512, h = 256;
    const vec3 sun = glm::normalize(vec3(0.3f, 0.8f, -0.5f));
    Image img = make_sun_sky_probe(w, h, sun, vec3(1e5f), 0.5f, vec3(0.2f), vec3(0.4f));
    Probe probe(img, glm::mat3(1), 1);
    ProbeMaxGrid grid(probe);
    EXPECT_GE(grid.max_in_cone(sun, 0.01f), 1e5f);
    EXPECT_LT(grid.max_in_cone(glm::normalize(vec3(-0.3f, 0.5f, 0.7f)), 0.05f), 1.0f);
    EXPECT_GE(grid.max_in_cone(glm::normalize(sun + vec3(0.05f, 0, 0)), 0.1f), 1e5f);
}
