// What a probe keeps per pixel: the image shared rather than copied, and tables only where
// they are needed (the sun's table holds the sun's rows), with sampling unchanged.
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
    return make_sun_sky_probe(w, h, glm::normalize(vec3(-0.2f, 0.6f, 0.7f)), vec3(3e4f), 1.0f,
                              vec3(0.3f, 0.5f, 1.0f), vec3(0.9f, 0.9f, 1.0f));
}

}  // namespace

TEST(ProbeMemory, AProbeSharesAFiniteImageAndCopiesOneWithNaNs) {
    auto clean = std::make_shared<const Image>(test::random_probe(32, 16, 3, 1, 4.0f, 0.1f));
    const Probe shared(clean, glm::mat3(1), vec3(1));
    EXPECT_EQ(&shared.image(), clean.get());

    Image dirty = *clean;
    dirty[7] = vec3(NAN, 1, 1);
    auto dirty_ptr = std::make_shared<const Image>(dirty);
    const Probe copied(dirty_ptr, glm::mat3(1), vec3(1));
    EXPECT_NE(&copied.image(), dirty_ptr.get());
    EXPECT_EQ(copied.image()[7], vec3(0));
    EXPECT_TRUE(std::isnan((*dirty_ptr)[7].x)) << "the caller's image is left as it was";
    // The copy samples the other pixels in the same proportions, its pixel 7 never.
    const double ratio = copied.pixel_pmf(0) / shared.pixel_pmf(0);
    EXPECT_GE(ratio, 1.0);
    for (size_t k = 0; k < clean->size(); ++k) {
        if (k == 7) continue;
        EXPECT_NEAR(copied.pixel_pmf(k), ratio * shared.pixel_pmf(k), 1e-12) << "pixel " << k;
    }
    EXPECT_EQ(copied.pixel_pmf(7), 0.0);
}

TEST(ProbeMemory, TheSunsTableHoldsOnlyTheSunsRows) {
    const int w = 512, h = 256;
    const Probe probe(sun_and_sky(w, h), glm::mat3(1), vec3(1));
    const ProbeLights lights(probe);
    ASSERT_TRUE(lights.has_sun());
    // The sky's table has the rows of the whole probe's (all but the black ground's); the sun's
    // adds the few rows of a 2-degree disk: at most 12 of 256 at 8 bytes a pixel, and a little
    // per row of the map.
    const LatLongTable whole(w, h, [&](size_t k) { return probe.pixel_weight(k); });
    const double sun_bytes = lights.bytes_per_pixel() - whole.bytes_per_pixel();
    EXPECT_GT(whole.bytes_per_pixel(), 3.9);  // the sky's half of the rows
    EXPECT_GT(sun_bytes, 0.0);
    EXPECT_LT(sun_bytes, 8.0 * 12 / 256 + 24.0 / 512);
}

TEST(ProbeMemory, ATableWithEmptyRowsSamplesItsPixelsAtTheirPmf) {
    const int w = 64, h = 32, n = 400000;
    std::vector<double> weights(size_t(w) * h, 0.0);
    Rng rng(5, 5);
    for (int j : {0, 9, 10, 31})
        for (int i = 0; i < w; ++i) weights[size_t(j) * w + i] = rng.uniform() < 0.2f ? 0.0 : 1.0 + 9 * rng.uniform();
    const LatLongTable table(w, h, weights);
    EXPECT_LT(table.bytes_per_pixel(), 1.5);  // 4 rows of 32 keep a CDF
    double total = 0;
    for (double x : weights) total += x;
    std::vector<double> observed(weights.size(), 0.0), expected(weights.size());
    for (int k = 0; k < n; ++k) {
        const LatLongTable::Pick p = table.sample(vec2(rng.uniform(), rng.uniform()));
        ASSERT_GT(weights[p.pixel], 0.0) << "picked a pixel of zero weight";
        observed[p.pixel] += 1;
    }
    for (size_t k = 0; k < weights.size(); ++k) {
        EXPECT_NEAR(table.pmf(k), weights[k] / total, 1e-12);
        expected[k] = n * weights[k] / total;
    }
    const test::ChiSquare chi = test::chi_square_test(observed, expected);
    EXPECT_GT(chi.p_value, 1e-3) << chi.statistic << " dof " << chi.dof;
}

TEST(ProbeMemory, EachLightsPdfIsThePdfItsSamplesCarry) {
    const Probe probe(sun_and_sky(256, 128), euler_xyz_deg(vec3(10, -40, 5)), vec3(1.2f, 1.0f, 0.8f));
    const ProbeLights lights(probe);
    ASSERT_TRUE(lights.has_sun());
    Rng rng(6, 1);
    int edge = 0;
    for (int k = 0; k < 20000; ++k) {
        for (const ProbeSample& s : {lights.sample_sun(vec2(rng.uniform(), rng.uniform())),
                                     lights.sample_sky(vec2(rng.uniform(), rng.uniform()))}) {
            // A direction on a pixel's edge may round into its neighbour.
            if (latlong_pixel(probe.to_probe(s.dir), probe.width(), probe.height()) != s.pixel) {
                ++edge;
                continue;
            }
            ASSERT_EQ(lights.pdf(s.dir), s.pdf) << "sample " << k;
            // The probe's own pdf, computed from the image rather than stored, is pmf / Omega.
            const double expected = probe.pixel_pmf(s.pixel) / probe.pixel_solid_angle(int(s.pixel / 256));
            ASSERT_NEAR(probe.pdf(s.dir), expected, 1e-6 * expected) << "sample " << k;
        }
    }
    EXPECT_LE(edge, 40);
}
