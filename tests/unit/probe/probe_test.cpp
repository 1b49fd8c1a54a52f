#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "base/euler.h"
#include "base/rng.h"
#include "base/sampling.h"
#include "probe/probe.h"
#include "probe/synthetic_probe.h"
#include "probe_test_util.h"

using namespace dp;

namespace {

constexpr double kPiD = std::numbers::pi;

/// This file's random probes: log-uniform radiance over e^8, a few black pixels.
Image random_probe(int w, int h, uint64_t seed) { return test::random_probe(w, h, seed, 5, 8.0f, 0.05f); }

vec3 pixel_centre(int i, int j, int w, int h) {
    return latlong_direction((i + 0.5f) / w, (j + 0.5f) / h);
}

float angle_deg(const vec3& a, const vec3& b) {
    float c = glm::dot(glm::normalize(a), glm::normalize(b));
    return std::acos(std::clamp(c, -1.0f, 1.0f)) * 180 / kPi;
}

}  // namespace

TEST(Probe, PixelSolidAnglesAreTheExactRowBandsAndSumToFourPi) {
    for (auto [w, h] : {std::pair{1, 1}, {3, 2}, {64, 32}, {17, 9}, {4096, 2048}}) {
        Probe probe(Image(w, h, vec3(1)), glm::mat3(1), 1);
        double sum = 0;
        for (int j = 0; j < h; ++j) {
            double band = 2 * kPiD / w * (std::cos(kPiD * j / h) - std::cos(kPiD * (j + 1) / h));
            EXPECT_NEAR(probe.pixel_solid_angle(j), band, 1e-12 * band + 1e-15);
            sum += probe.pixel_solid_angle(j) * w;
        }
        EXPECT_NEAR(sum, 4 * kPiD, 1e-9) << w << "x" << h;
    }
}

TEST(Probe, RadianceIsTheNearestPixelTimesTheIntensity) {
    Image img = random_probe(32, 16, 3);
    Probe probe(img, glm::mat3(1), 2.5f);
    for (int j = 0; j < 16; ++j) {
        for (int i = 0; i < 32; ++i) {
            // Anywhere inside the pixel, not only at its centre.
            vec3 d = latlong_direction((i + 0.2f) / 32, (j + 0.9f) / 16);
            EXPECT_EQ(probe.radiance(d), img.at(i, j) * 2.5f);
            EXPECT_EQ(probe.pixel_radiance(size_t(j) * 32 + i), img.at(i, j) * 2.5f);
        }
    }
}

TEST(Probe, PdfIntegratesToOneOverTheSphere) {
    Probe probe(random_probe(48, 24, 4), euler_xyz_deg(vec3(30, -50, 10)), 0.3f);
    double integral = 0;
    for (int j = 0; j < 24; ++j)
        for (int i = 0; i < 48; ++i)
            integral += probe.pdf(probe.to_world(pixel_centre(i, j, 48, 24))) *
                        probe.pixel_solid_angle(j);
    EXPECT_NEAR(integral, 1.0, 1e-5);
}

TEST(Probe, PdfOfASampledDirectionEqualsThePdfReturnedBySample) {
    Image img = random_probe(64, 32, 5);
    Probe probe(img, euler_xyz_deg(vec3(15, 70, -20)), 3.0f);
    Rng rng(5, 5);
    const int n = 200000;
    int pdf_mismatches = 0, radiance_mismatches = 0;
    for (int k = 0; k < n; ++k) {
        ProbeSample s = probe.sample(rng.uniform(), rng.uniform(), rng.uniform());
        ASSERT_GT(s.pdf, 0.0f);
        ASSERT_NEAR(glm::length(s.dir), 1.0f, 1e-5f);
        if (std::abs(probe.pdf(s.dir) - s.pdf) > 1e-5f * s.pdf) ++pdf_mismatches;
        if (probe.radiance(s.dir) != s.radiance) ++radiance_mismatches;
    }
    // Only a direction rounded across a pixel edge by the rotation may disagree.
    EXPECT_LE(pdf_mismatches, n / 10000);
    EXPECT_LE(radiance_mismatches, n / 10000);
}

TEST(Probe, RotationMovesTheBrightPixelsSampledDirection) {
    const int w = 64, h = 32, px = 32, py = 16;
    // Pixel (32, 16) sits just past the image centre, i.e. close to -Z in probe space.
    glm::mat3 rotation = euler_xyz_deg(vec3(0, 90, 0));
    Probe probe(make_single_pixel_probe(w, h, px, py, vec3(5)), rotation, 1);
    vec3 centre_world = rotation * pixel_centre(px, py, w, h);
    EXPECT_LT(angle_deg(centre_world, vec3(-1, 0, 0)), 5.0f);  // Y by +90 deg takes -Z to -X

    Rng rng(1, 2);
    vec3 mean(0);
    for (int k = 0; k < 10000; ++k) {
        ProbeSample s = probe.sample(rng.uniform(), rng.uniform(), rng.uniform());
        ASSERT_EQ(s.pixel, size_t(py * w + px));
        // Within the pixel's half-diagonal: 5.625 degree pixels, so about 3.98 degrees.
        ASSERT_LT(angle_deg(s.dir, centre_world), 4.0f);
        mean += s.dir;
    }
    EXPECT_LT(angle_deg(mean, centre_world), 0.2f);
    EXPECT_EQ(probe.radiance(centre_world), vec3(5));
    EXPECT_GT(probe.pdf(centre_world), 0.0f);
    EXPECT_EQ(probe.radiance(pixel_centre(px, py, w, h)), vec3(0));  // the unrotated place
    EXPECT_EQ(probe.pdf(pixel_centre(px, py, w, h)), 0.0f);
}

TEST(Probe, NonFinitePixelsAreTreatedAsBlack) {
    const float inf = std::numeric_limits<float>::infinity();
    Image img(8, 4, vec3(1));
    img.at(1, 1) = vec3(std::nanf(""), 1, 1);
    img.at(5, 2) = vec3(1, inf, 1);
    img.at(6, 3) = vec3(-inf, 0, 0);
    Probe probe(img, glm::mat3(1), 1);
    EXPECT_TRUE(std::isfinite(probe.total_luminance_power()));
    EXPECT_NEAR(probe.total_luminance_power(),
                4 * kPiD - probe.pixel_solid_angle(1) - probe.pixel_solid_angle(2) -
                    probe.pixel_solid_angle(3),
                1e-9);
    for (auto [i, j] : {std::pair{1, 1}, {5, 2}, {6, 3}}) {
        EXPECT_EQ(probe.pixel_pmf(size_t(j) * 8 + i), 0.0);
        EXPECT_EQ(probe.radiance(pixel_centre(i, j, 8, 4)), vec3(0));
        EXPECT_EQ(probe.pdf(pixel_centre(i, j, 8, 4)), 0.0f);
    }
}

TEST(Probe, ABlackProbeSamplesNothing) {
    for (const Probe& probe : {Probe(Image(16, 8), glm::mat3(1), 1),
                               Probe(Image(16, 8, vec3(1)), glm::mat3(1), 0), Probe()}) {
        EXPECT_EQ(probe.total_luminance_power(), 0.0);
        ProbeSample s = probe.sample(0.3f, 0.6f, 0.9f);
        EXPECT_EQ(s.pdf, 0.0f);
        EXPECT_EQ(s.radiance, vec3(0));
        EXPECT_EQ(probe.pdf(vec3(0, 1, 0)), 0.0f);
        EXPECT_EQ(probe.radiance(vec3(0, 1, 0)), vec3(0));
    }
}

TEST(Probe, IntensityScalesRadianceButNotThePmf) {
    Image img = random_probe(16, 8, 9);
    Probe a(img, glm::mat3(1), 1), b(img, glm::mat3(1), 40);
    EXPECT_NEAR(b.total_luminance_power(), 40 * a.total_luminance_power(),
                1e-12 * b.total_luminance_power());
    for (size_t k = 0; k < img.size(); ++k) {
        EXPECT_NEAR(a.pixel_pmf(k), b.pixel_pmf(k), 1e-12);
        EXPECT_EQ(b.pixel_radiance(k), 40.0f * img[k]);
    }
    ProbeSample sa = a.sample(0.4f, 0.5f, 0.6f), sb = b.sample(0.4f, 0.5f, 0.6f);
    EXPECT_EQ(sa.pixel, sb.pixel);
    EXPECT_NEAR(sa.pdf, sb.pdf, 1e-5f * sa.pdf);
}

TEST(Probe, AGainPerChannelScalesEachChannelAndSamplesByTheScaledLuminance) {
    Image img = random_probe(16, 8, 11);
    const vec3 gain(1.2f, 1.0f, 0.7f);
    Probe p(img, glm::mat3(1), gain);
    double total = 0;
    for (size_t k = 0; k < img.size(); ++k) {
        EXPECT_EQ(p.pixel_radiance(k), img[k] * gain);
        total += std::max(0.0, luminance(dvec3(img[k]) * dvec3(gain))) *
                 p.pixel_solid_angle(int(k / 16));
    }
    EXPECT_NEAR(p.total_luminance_power(), total, 1e-9 * total);
    // A grey gain is the intensity it stands for.
    Probe grey(img, glm::mat3(1), vec3(3.0f)), scalar(img, glm::mat3(1), 3.0f);
    for (size_t k = 0; k < img.size(); ++k) EXPECT_EQ(grey.pixel_pmf(k), scalar.pixel_pmf(k));
}
