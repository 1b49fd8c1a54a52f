#include <gtest/gtest.h>

#include <cmath>

#include "base/euler.h"
#include "base/rng.h"
#include "probe/probe_lights.h"
#include "probe/synthetic_probe.h"
#include "probe_test_util.h"

using namespace dp;

namespace {

Image sun_and_sky(int w, int h) {
    return make_sun_sky_probe(w, h, glm::normalize(vec3(0.3f, 0.8f, -0.5f)), vec3(2e4f), 1.0f, vec3(0.3f, 0.5f, 1.0f),
                              vec3(0.9f, 0.9f, 1.0f));
}

}  // namespace

TEST(ProbeLights, ASunIsSplitOffAndEachLightSamplesOnlyItsOwnPixelsAtTheirPmf) {
    const int w = 256, h = 128, n = 400000;
    Probe probe(sun_and_sky(w, h), euler_xyz_deg(vec3(5, 30, 0)), 1.5f);
    ProbeLights lights(probe);
    ASSERT_TRUE(lights.has_sun());
    EXPECT_GT(lights.sun_share(), 0.5);
    std::vector<double> sun_obs(size_t(w) * h, 0), sky_obs(size_t(w) * h, 0);
    Rng rng(1, 2);
    for (int k = 0; k < n; ++k) {
        const ProbeSample s = lights.sample_sun(vec2(rng.uniform(), rng.uniform()));
        const ProbeSample t = lights.sample_sky(vec2(rng.uniform(), rng.uniform()));
        sun_obs[s.pixel] += 1;
        sky_obs[t.pixel] += 1;
        ASSERT_GT(s.pdf, 0);
        ASSERT_GT(t.pdf, 0);
    }
    // The two tables split the probe's pmf: sun pixels in one, the others in the other.
    double sun_total = 0;
    for (size_t k = 0; k < sun_obs.size(); ++k)
        if (sun_obs[k] > 0) sun_total += probe.pixel_pmf(k);
    std::vector<double> sun_exp(sun_obs.size()), sky_exp(sky_obs.size());
    for (size_t k = 0; k < sun_obs.size(); ++k) {
        const bool in_sun = sun_obs[k] > 0;
        EXPECT_FALSE(in_sun && sky_obs[k] > 0) << "pixel " << k << " drawn by both lights";
        sun_exp[k] = in_sun ? n * probe.pixel_pmf(k) / sun_total : 0;
        sky_exp[k] = in_sun ? 0 : n * probe.pixel_pmf(k) / (1 - sun_total);
    }
    EXPECT_NEAR(sun_total, lights.sun_share(), 1e-6);
    const test::ChiSquare cs = test::chi_square_test(sun_obs, sun_exp), ck = test::chi_square_test(sky_obs, sky_exp);
    EXPECT_GT(cs.p_value, 1e-3) << cs.statistic << " dof " << cs.dof;
    EXPECT_GT(ck.p_value, 1e-3) << ck.statistic << " dof " << ck.dof;
}

TEST(ProbeLights, OneSampleOfEachLightEstimatesTheIrradianceWithoutBias) {
    const int w = 512, h = 256, n = 200000;
    Probe probe(sun_and_sky(w, h), glm::mat3(1), 1);
    ProbeLights lights(probe);
    ASSERT_TRUE(lights.has_sun());
    // Truth: the irradiance on an upward plane summed over the pixels (their centre directions).
    double truth = 0;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const vec3 d = latlong_direction((i + 0.5f) / w, (j + 0.5f) / h);
            truth += luminance(probe.pixel_radiance(size_t(j) * w + i)) * std::max(0.0f, d.y) * probe.pixel_solid_angle(j);
        }
    Rng rng(3, 4);
    double sum = 0;
    for (int k = 0; k < n; ++k)
        for (const ProbeSample& s : {lights.sample_sun(vec2(rng.uniform(), rng.uniform())),
                                     lights.sample_sky(vec2(rng.uniform(), rng.uniform()))})
            if (s.pdf > 0) sum += luminance(s.radiance) * std::max(0.0f, s.dir.y) / s.pdf;
    EXPECT_NEAR(sum / n / truth, 1.0, 0.005);
}

TEST(ProbeLights, AnEvenlyLitProbeIsOneLight) {
    Probe probe(make_constant_probe(64, 32, vec3(1.0f)), glm::mat3(1), 1);
    ProbeLights lights(probe);
    EXPECT_FALSE(lights.has_sun());
    EXPECT_EQ(lights.sample_sun(vec2(0.5f)).pdf, 0.0f);
    const ProbeSample s = lights.sample_sky(vec2(0.3f, 0.6f));
    EXPECT_FLOAT_EQ(s.pdf, probe.pdf(s.dir));
    EXPECT_FLOAT_EQ(lights.pdf(s.dir), probe.pdf(s.dir));
}
