// Shrinking a lat-long probe keeps its light: the power of each channel and where the sun is.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "image/image_io.h"
#include "probe/probe.h"
#include "probe/probe_lights.h"
#include "probe/probe_resize.h"
#include "probe/synthetic_probe.h"
#include "probe_test_util.h"

using namespace dp;

namespace {

constexpr double kPiD = std::numbers::pi;

/// Sum over pixels of L * Omega per channel, with the band areas computed here from the
/// lat-long convention rather than by the code under test.
dvec3 power(const Image& img) {
    const int w = img.width(), h = img.height();
    dvec3 sum(0);
    for (int j = 0; j < h; ++j) {
        const double omega = 2 * kPiD / w * (std::cos(kPiD * j / h) - std::cos(kPiD * (j + 1) / h));
        dvec3 row(0);
        for (int i = 0; i < w; ++i) row += dvec3(img.at(i, j));
        sum += row * omega;
    }
    return sum;
}

/// Direction of the centre of the brightest pixel (by luminance).
vec3 brightest_direction(const Image& img) {
    size_t best = 0;
    for (size_t k = 1; k < img.size(); ++k)
        if (luminance(img[k]) > luminance(img[best])) best = k;
    const int w = img.width(), h = img.height();
    const float u = (float(best % size_t(w)) + 0.5f) / float(w), v = (float(best / size_t(w)) + 0.5f) / float(h);
    return latlong_direction(u, v);
}

/// Where the light comes from on the whole: the luminance-power-weighted mean of the pixel
/// centres' directions (a first moment of the map, which averaging within pixels keeps).
vec3 mean_light_direction(const Image& img) {
    const int w = img.width(), h = img.height();
    dvec3 sum(0);
    for (int j = 0; j < h; ++j) {
        const double omega = std::cos(kPiD * j / h) - std::cos(kPiD * (j + 1) / h);
        for (int i = 0; i < w; ++i)
            sum += dvec3(latlong_direction((i + 0.5f) / float(w), (j + 0.5f) / float(h))) *
                   (double(luminance(img.at(i, j))) * omega);
    }
    return vec3(sum);
}

double angle_between(const vec3& a, const vec3& b) {
    return std::acos(std::clamp(double(glm::dot(glm::normalize(a), glm::normalize(b))), -1.0, 1.0));
}

/// Checks that `small` holds the power of `big` per channel to `tolerance` (relative), that its
/// light comes from the same mean direction, and, for a map with a sun (`sun`), that its
/// brightest direction is within one pixel of `small` (the diagonal of a pixel at the horizon).
void expect_light_kept(const Image& big, const Image& small, double tolerance, bool sun = true) {
    const dvec3 before = power(big), after = power(small);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GT(before[c], 0.0);
        EXPECT_NEAR(after[c] / before[c], 1.0, tolerance) << "channel " << c;
    }
    const double pixel = std::hypot(2 * kPiD / small.width(), kPiD / small.height());
    EXPECT_LT(angle_between(mean_light_direction(big), mean_light_direction(small)), 0.5 * pixel)
        << "the mean direction of the light moved";
    // Without a sun the brightest pixel is a detail (a lamp, a glint) that an average over a
    // coarser pixel may well lose to a wider bright patch.
    if (sun) {
        EXPECT_LT(angle_between(brightest_direction(big), brightest_direction(small)), pixel)
            << "the brightest direction moved";
    }
    std::printf("%dx%d -> %dx%d: power ratios %.9f %.9f %.9f\n", big.width(), big.height(), small.width(),
                small.height(), after.x / before.x, after.y / before.y, after.z / before.z);
}

}  // namespace

TEST(ProbeResize, ANonIntegerFactorKeepsEachChannelsPowerAndTheSunsDirection) {
    // 1000 -> 333 columns and 500 -> 167 rows: every output edge but the first and last cuts a
    // source pixel, so a filter that assigned whole pixels would move light between neighbours.
    Image img = test::random_probe(1000, 500, 11, 3, 4.0f, 0.05f);
    const vec3 sun = glm::normalize(vec3(0.4f, 0.7f, -0.6f));
    img[latlong_pixel(sun, 1000, 500)] = vec3(2e5f, 1.8e5f, 1.5e5f);
    int w = 0, h = 0;
    shrunk_latlong_size(img.width(), img.height(), 333, w, h);
    ASSERT_EQ(w, 333);
    ASSERT_EQ(h, 167);
    const Image small = shrink_latlong(img, w, h);
    ASSERT_EQ(small.width(), 333);
    ASSERT_EQ(small.height(), 167);
    expect_light_kept(img, small, 1e-6);
    EXPECT_LT(angle_between(brightest_direction(small), sun), std::hypot(2 * kPiD / w, kPiD / h));
}

TEST(ProbeResize, RealProbesKeepTheirPowerAndTheDirectionOfTheirLight) {
    const std::string dir = "/usr/share/blender/datafiles/studiolights/world/";
    if (!std::filesystem::exists(dir + "sunset.exr")) GTEST_SKIP() << "Blender's studio lights not installed";
    for (const char* name : {"sunset.exr", "courtyard.exr", "city.exr"}) {
        SCOPED_TRACE(name);
        const bool sun = std::string(name) == "sunset.exr";
        const Image img = load_image(dir + name, "probe");
        ASSERT_FALSE(img.empty());
        // A third (a non-integer factor for a 1024-wide probe) and a quarter of the width.
        for (int divisor : {3, 4}) {
            int w = 0, h = 0;
            shrunk_latlong_size(img.width(), img.height(), img.width() / divisor, w, h);
            expect_light_kept(img, shrink_latlong(img, w, h), 1e-6, sun);
        }
    }
}

TEST(ProbeResize, AConstantProbeStaysConstant) {
    const Image img(700, 350, vec3(0.25f, 1.5f, 3.0f));
    const Image small = shrink_latlong(img, 129, 64);
    for (size_t k = 0; k < small.size(); ++k)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(small[k][c], img[0][c], 1e-6f * img[0][c]) << "pixel " << k;
}

TEST(ProbeResize, AProbeThatFitsKeepsItsSizeAndAWiderOneKeepsItsProportions) {
    int w = 0, h = 0;
    shrunk_latlong_size(4096, 2048, 8192, w, h);
    EXPECT_EQ(w, 4096);
    EXPECT_EQ(h, 2048);
    shrunk_latlong_size(16384, 8192, 8192, w, h);
    EXPECT_EQ(w, 8192);
    EXPECT_EQ(h, 4096);
    // A non-2:1 map is read as covering the sphere whatever its shape: it stays that shape.
    shrunk_latlong_size(3000, 1000, 1500, w, h);
    EXPECT_EQ(w, 1500);
    EXPECT_EQ(h, 500);
    shrunk_latlong_size(100000, 10, 64, w, h);
    EXPECT_EQ(w, 64);
    EXPECT_EQ(h, 1);
}

TEST(ProbeResize, TheAutomaticWidthHalvesOnlyWhereMemoryIsShort) {
    const double bytes = 28;
    const uint64_t gib = uint64_t(1) << 30;
    EXPECT_EQ(automatic_probe_max_width(0, bytes), 8192);  // unknown memory: the default
    EXPECT_EQ(automatic_probe_max_width(64 * gib, bytes), 8192);
    // 8192 x 4096 at 28 bytes is 0.94 GB: more than a quarter of 2 GiB, less than 4 GiB's.
    EXPECT_EQ(automatic_probe_max_width(4 * gib, bytes), 8192);
    EXPECT_EQ(automatic_probe_max_width(2 * gib, bytes), 4096);
    EXPECT_EQ(automatic_probe_max_width(gib / 64, bytes), 1024);  // never below 1024
}

TEST(ProbeResize, AShrunkProbeLightsASceneAsTheOriginalDoes) {
    // The sampler's view of the light: the total luminance power is the same for the shrunk map.
    const Image img = make_sun_sky_probe(1200, 600, glm::normalize(vec3(-0.3f, 0.5f, 0.8f)), vec3(5e4f), 0.6f,
                                         vec3(0.3f, 0.5f, 1.0f), vec3(0.9f, 0.9f, 1.0f));
    const Probe big(img, glm::mat3(1), 1.0f), small(shrink_latlong(img, 250, 125), glm::mat3(1), 1.0f);
    EXPECT_NEAR(small.total_luminance_power() / big.total_luminance_power(), 1.0, 1e-6);
    // The sun/sky split finds the same sun in both.
    const ProbeLights big_lights(big), small_lights(small);
    ASSERT_TRUE(big_lights.has_sun());
    ASSERT_TRUE(small_lights.has_sun());
    EXPECT_NEAR(small_lights.sun_share(), big_lights.sun_share(), 0.05 * big_lights.sun_share());
}
