#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "base/euler.h"
#include "base/rng.h"
#include "probe/probe.h"
#include "probe/synthetic_probe.h"
#include "probe_test_util.h"

using namespace dp;

namespace {

constexpr double kPiD = std::numbers::pi;

/// This file's random probes: log-uniform radiance over e^6, a few black pixels.
Image random_probe(int w, int h, uint64_t seed) { return test::random_probe(w, h, seed, 7, 6.0f, 0.03f); }

double band_solid_angle(int row, int w, int h) {
    return 2 * kPiD / w * (std::cos(kPiD * row / h) - std::cos(kPiD * (row + 1) / h));
}

// The pmf the probe should use, computed here independently of the implementation.
std::vector<double> expected_pmf(const Image& img, float intensity) {
    std::vector<double> w(img.size());
    double total = 0;
    for (int j = 0; j < img.height(); ++j) {
        for (int i = 0; i < img.width(); ++i) {
            double lum = luminance(dvec3(img.at(i, j)) * double(intensity));
            double x = std::max(lum, 0.0) * band_solid_angle(j, img.width(), img.height());
            w[size_t(j) * img.width() + i] = x;
            total += x;
        }
    }
    for (double& x : w) x /= total;
    return w;
}

}  // namespace

TEST(ProbeSampling, PickedPixelsPassAChiSquareTestAgainstThePixelPmf) {
    Image img = random_probe(64, 32, 1);
    Probe probe(img, euler_xyz_deg(vec3(10, 20, 30)), 1.7f);
    std::vector<double> pmf = expected_pmf(img, 1.7f);
    for (size_t k = 0; k < pmf.size(); ++k)
        ASSERT_NEAR(probe.pixel_pmf(k), pmf[k], 1e-9 * pmf[k]) << "pixel " << k;

    const int n = 1000000;
    Rng rng(1, 1);
    std::vector<double> observed(pmf.size(), 0.0), expected(pmf.size());
    int outside = 0;
    for (int k = 0; k < n; ++k) {
        ProbeSample s = probe.sample(rng.uniform(), rng.uniform(), rng.uniform());
        observed[s.pixel] += 1;
        if (latlong_pixel(probe.to_probe(s.dir), 64, 32) != s.pixel) ++outside;
    }
    for (size_t k = 0; k < pmf.size(); ++k) expected[k] = n * pmf[k];
    test::ChiSquare chi = test::chi_square_test(observed, expected);
    EXPECT_GT(chi.p_value, 1e-3) << "chi2 " << chi.statistic << " dof " << chi.dof;
    EXPECT_LE(outside, n / 10000) << "sampled directions outside the picked pixel";
}

TEST(ProbeSampling, DirectionsAreUniformInSolidAngleWithinTheirPixel) {
    // 4 x 4 sub-cells per pixel, equal in solid angle: equal steps in u and in cos(theta).
    const int w = 16, h = 8, sub = 4, n = 1000000;
    Image img = random_probe(w, h, 2);
    Probe probe(img, glm::mat3(1), 1);
    std::vector<double> observed(img.size() * sub * sub, 0.0), expected(observed.size());
    Rng rng(2, 2);
    int outside = 0;
    for (int k = 0; k < n; ++k) {
        ProbeSample s = probe.sample(rng.uniform(), rng.uniform(), rng.uniform());
        size_t pixel = latlong_pixel(s.dir, w, h);
        if (pixel != s.pixel) {
            ++outside;
            continue;
        }
        int i = int(pixel % w), j = int(pixel / w);
        double u = latlong_uv(s.dir).x * w - i;
        double cos_top = std::cos(kPiD * j / h), cos_bottom = std::cos(kPiD * (j + 1) / h);
        double t = (cos_top - double(s.dir.y)) / (cos_top - cos_bottom);
        int a = std::clamp(int(u * sub), 0, sub - 1), b = std::clamp(int(t * sub), 0, sub - 1);
        observed[(pixel * sub + b) * sub + a] += 1;
    }
    for (size_t k = 0; k < expected.size(); ++k)
        expected[k] = n * probe.pixel_pmf(k / (sub * sub)) / (sub * sub);
    test::ChiSquare chi = test::chi_square_test(observed, expected);
    EXPECT_GT(chi.p_value, 1e-3) << "chi2 " << chi.statistic << " dof " << chi.dof;
    EXPECT_LE(outside, n / 10000);
}

TEST(ProbeSampling, ConstantProbeGivesIrradiancePiTimesRadianceOnAnUpwardPlane) {
    const vec3 radiance(0.5f, 1.0f, 2.0f);
    const float intensity = 2;
    Probe probe(make_constant_probe(64, 32, radiance), euler_xyz_deg(vec3(20, -30, 40)),
                intensity);
    const int n = 1000000;
    Rng rng(3, 3);
    dvec3 sum(0);
    for (int k = 0; k < n; ++k) {
        ProbeSample s = probe.sample(rng.uniform(), rng.uniform(), rng.uniform());
        ASSERT_GT(s.pdf, 0.0f);
        sum += dvec3(s.radiance) * double(std::max(0.0f, s.dir.y)) / double(s.pdf);
    }
    dvec3 irradiance = sum / double(n);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(irradiance[c] / (kPiD * intensity * radiance[c]), 1.0, 0.01) << "channel " << c;
}

TEST(ProbeSampling, ASunAMillionTimesTheSkyIsSampledAtItsShareOfThePower) {
    const int w = 512, h = 256;
    const vec3 sun_radiance = 1e6f * vec3(1.0f, 0.95f, 0.9f);
    Image img = make_sun_sky_probe(w, h, vec3(0.3f, 0.8f, -0.5f), sun_radiance, 0.5f,
                                   vec3(0.3f, 0.5f, 1.0f), vec3(0.9f, 0.9f, 1.0f));
    Probe probe(img, glm::mat3(1), 1);
    std::vector<double> pmf = expected_pmf(img, 1);
    std::vector<bool> is_sun(img.size());
    double sun_share = 0;
    for (size_t k = 0; k < img.size(); ++k) {
        is_sun[k] = img[k] == sun_radiance;
        if (is_sun[k]) sun_share += pmf[k];
        ASSERT_NEAR(probe.pixel_pmf(k), pmf[k], 1e-9 * pmf[k]) << "pixel " << k;
    }
    ASSERT_GT(sun_share, 0.9);
    ASSERT_LT(sun_share, 0.999);

    // Sun hits against the binomial expectation; sky hits per row against the sky's pmf.
    const int n = 1000000;
    Rng rng(4, 4);
    double sun_hits = 0;
    std::vector<double> observed(h, 0.0), expected(h, 0.0);
    for (int k = 0; k < n; ++k) {
        ProbeSample s = probe.sample(rng.uniform(), rng.uniform(), rng.uniform());
        if (is_sun[s.pixel])
            sun_hits += 1;
        else
            observed[s.pixel / w] += 1;
    }
    for (size_t k = 0; k < img.size(); ++k)
        if (!is_sun[k]) expected[k / w] += n * pmf[k];
    double sigma = std::sqrt(n * sun_share * (1 - sun_share));
    EXPECT_NEAR(sun_hits, n * sun_share, 5 * sigma);
    test::ChiSquare chi = test::chi_square_test(observed, expected);
    EXPECT_GT(chi.p_value, 1e-3) << "chi2 " << chi.statistic << " dof " << chi.dof;
}

TEST(ProbeSampling, FloatRandomNumbersSampleALargeMapAtItsExactPmf) {
    // Half a million pixels (2^19): a float alone would leave 5 bits to flip each alias coin,
    // so every coin would be rounded to a multiple of 1/32; u1 supplies the missing bits.
    // Every sky pixel gets the same weight, so that rounding could not average out.
    const int w = 1024, h = 512, bright_i = 700, bright_j = 100;
    const double bright_share = 0.7;
    Probe unit(Image(w, h), glm::mat3(1), 1);
    Image img(w, h);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) img.at(i, j) = vec3(float(1 / unit.pixel_solid_angle(j)));
    double bright_weight = bright_share / (1 - bright_share) * (double(w) * h - 1);
    img.at(bright_i, bright_j) = vec3(float(bright_weight / unit.pixel_solid_angle(bright_j)));
    Probe probe(img, glm::mat3(1), 1);
    const size_t bright = size_t(bright_j) * w + bright_i;
    double p = probe.pixel_pmf(bright);
    ASSERT_NEAR(p, bright_share, 1e-6);

    const int n = 1000000;
    Rng rng(6, 6);
    double hits = 0;
    for (int k = 0; k < n; ++k)
        if (probe.sample(rng.uniform(), rng.uniform(), rng.uniform()).pixel == bright) hits += 1;
    EXPECT_NEAR(hits, n * p, 5 * std::sqrt(n * p * (1 - p)));
}

TEST(ProbeSampling, InversionPicksPixelsAtThePixelPmfAndDirectionsUniformlyInside) {
    const int w = 32, h = 16, sub = 2, n = 1000000;
    Image img = random_probe(w, h, 8);
    Probe probe(img, euler_xyz_deg(vec3(-15, 40, 5)), 0.8f);
    std::vector<double> observed(img.size() * sub * sub, 0.0), expected(observed.size());
    Rng rng(8, 8);
    int outside = 0;
    for (int k = 0; k < n; ++k) {
        ProbeSample s = probe.sample_inverse(vec2(rng.uniform(), rng.uniform()));
        const vec3 d = probe.to_probe(s.dir);
        size_t pixel = latlong_pixel(d, w, h);
        if (pixel != s.pixel) {  // a direction on a pixel's edge may round into its neighbour
            ++outside;
            continue;
        }
        ASSERT_EQ(s.pdf, probe.pdf(s.dir)) << "sample " << k;
        int i = int(pixel % w), j = int(pixel / w);
        double u = latlong_uv(d).x * w - i;
        double cos_top = std::cos(kPiD * j / h), cos_bottom = std::cos(kPiD * (j + 1) / h);
        double t = (cos_top - double(d.y)) / (cos_top - cos_bottom);
        int a = std::clamp(int(u * sub), 0, sub - 1), b = std::clamp(int(t * sub), 0, sub - 1);
        observed[(pixel * sub + b) * sub + a] += 1;
    }
    for (size_t k = 0; k < expected.size(); ++k)
        expected[k] = n * probe.pixel_pmf(k / (sub * sub)) / (sub * sub);
    test::ChiSquare chi = test::chi_square_test(observed, expected);
    EXPECT_GT(chi.p_value, 1e-3) << "chi2 " << chi.statistic << " dof " << chi.dof;
    EXPECT_LE(outside, n / 10000);
}

TEST(ProbeSampling, InversionSpreadsAStratifiedGridEvenlyOverTheSunsDisk) {
    // A sun of 2 degrees in a black sky: a 16 x 16 grid of strata should put the sun's samples
    // evenly over its disk, where independent random numbers would clump. Measured by the
    // spread of the samples' mean direction around the sun's centre over many jittered grids.
    const int w = 1024, h = 512;
    const vec3 sun_dir = glm::normalize(vec3(0.3f, 0.8f, -0.5f));
    Image img = make_sun_sky_probe(w, h, sun_dir, vec3(1e5f), 2.0f, vec3(0.0f), vec3(0.0f));
    Probe probe(img, glm::mat3(1), 1);
    auto spread = [&](bool stratified) {
        Rng rng(9, stratified);
        double sum2 = 0;
        const int trials = 50, g = 16;
        vec3 overall(0);
        std::vector<vec3> means;
        for (int t = 0; t < trials; ++t) {
            dvec3 mean(0);
            for (int a = 0; a < g; ++a)
                for (int b = 0; b < g; ++b) {
                    vec2 u = stratified ? vec2((a + rng.uniform()) / g, (b + rng.uniform()) / g)
                                        : vec2(rng.uniform(), rng.uniform());
                    mean += dvec3(probe.sample_inverse(u).dir);
                }
            means.push_back(vec3(glm::normalize(mean)));
            overall += means.back();
        }
        overall = glm::normalize(overall);
        for (const vec3& m : means) sum2 += double(glm::dot(m - overall, m - overall));
        return std::sqrt(sum2 / trials);
    };
    const double random = spread(false), stratified = spread(true);
    std::printf("spread of the mean sun direction: random %.3g, stratified %.3g\n", random, stratified);
    EXPECT_LT(stratified, 0.2 * random);
}
