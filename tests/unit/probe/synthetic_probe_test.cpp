#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "probe/probe.h"
#include "probe/synthetic_probe.h"

using namespace dp;

namespace {

double angle_deg(const vec3& a, const vec3& b) {
    double c = double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z;
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180 / std::numbers::pi;
}

vec3 centre(int i, int j, int w, int h) {
    return latlong_direction((i + 0.5f) / w, (j + 0.5f) / h);
}

}  // namespace

TEST(SyntheticProbe, ConstantProbeHasTheSameRadianceEverywhere) {
    Image img = make_constant_probe(32, 16, vec3(0.5f, 1, 2));
    ASSERT_EQ(img.width(), 32);
    ASSERT_EQ(img.height(), 16);
    for (size_t k = 0; k < img.size(); ++k) EXPECT_EQ(img[k], vec3(0.5f, 1, 2));
}

TEST(SyntheticProbe, SunDiskIsThePixelsWithinItsRadiusOverASkyAndABlackGround) {
    const int w = 256, h = 128;
    const vec3 sun_dir = glm::normalize(vec3(0.2f, 0.5f, -0.7f)), sun(1000, 900, 800);
    const vec3 zenith(0.2f, 0.4f, 1.0f), horizon(0.8f, 0.8f, 0.9f);
    Image img = make_sun_sky_probe(w, h, 3.0f * sun_dir, sun, 5.0f, zenith, horizon);
    int sun_pixels = 0;
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            vec3 d = centre(i, j, w, h);
            double a = angle_deg(d, sun_dir);
            if (std::abs(a - 5.0) < 1e-3) continue;  // too close to the edge to call
            if (a < 5.0) {
                EXPECT_EQ(img.at(i, j), sun);
                ++sun_pixels;
            } else if (d.y > 0) {
                vec3 sky = glm::mix(horizon, zenith, d.y);
                EXPECT_NEAR(glm::length(img.at(i, j) - sky), 0.0f, 1e-5f) << i << " " << j;
            } else {
                EXPECT_EQ(img.at(i, j), vec3(0)) << i << " " << j;
            }
        }
    }
    // Roughly the disk's solid angle over a pixel's at that elevation.
    double disk = 2 * std::numbers::pi * (1 - std::cos(5.0 * std::numbers::pi / 180));
    Probe probe(img, glm::mat3(1), 1);
    int row = int(latlong_uv(sun_dir).y * h);
    EXPECT_NEAR(sun_pixels, disk / probe.pixel_solid_angle(row), 0.15 * sun_pixels);
    // Zenith at the top row, horizon colour just above the horizon.
    EXPECT_NEAR(img.at(10, 0).z, zenith.z, 0.01f);
    EXPECT_NEAR(img.at(10, h / 2 - 1).x, horizon.x, 0.02f);
}

TEST(SyntheticProbe, ASunSmallerThanAPixelIsTheSingleNearestPixel) {
    const int w = 64, h = 32;
    // Slightly off the centre of pixel (40, 13): no centre is within 0.01 degrees.
    vec3 sun_dir = latlong_direction((40 + 0.6f) / w, (13 + 0.45f) / h);
    Image img = make_sun_sky_probe(w, h, sun_dir, vec3(1e6f), 0.01f, vec3(1), vec3(1));
    int count = 0;
    for (size_t k = 0; k < img.size(); ++k) count += img[k] == vec3(1e6f);
    EXPECT_EQ(count, 1);
    EXPECT_EQ(img.at(40, 13), vec3(1e6f));
    EXPECT_THROW(make_sun_sky_probe(w, h, vec3(0), vec3(1), 1, vec3(1), vec3(1)),
                 std::invalid_argument);
}

TEST(SyntheticProbe, SinglePixelProbeLightsOnlyThatPixel) {
    Image img = make_single_pixel_probe(16, 8, 3, 6, vec3(7, 8, 9));
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 16; ++i)
            EXPECT_EQ(img.at(i, j), (i == 3 && j == 6) ? vec3(7, 8, 9) : vec3(0));
    EXPECT_THROW(make_single_pixel_probe(16, 8, 16, 0, vec3(1)), std::out_of_range);
    EXPECT_THROW(make_single_pixel_probe(16, 8, 0, -1, vec3(1)), std::out_of_range);
}
