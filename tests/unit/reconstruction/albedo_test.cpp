#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "reconstruction/albedo.h"
#include "common/synthetic_photo.h"

using namespace dp;
using namespace dp::test;

// The per-texel accuracy on a two-tone ground is checked in
// tests/render/reconstruction_albedo_test.cpp (its photo needs many samples per pixel).

TEST(AlbedoTexture, TheBoxTextureGathersItsVisibleFacesWithinFivePercent) {
    GroundAndBox s;
    auto scene = s.photo(32);  // the mean over the box's texels averages the photo's noise
    AlbedoTextureOptions o;
    o.width = o.height = 16;
    AlbedoTexture t = estimate_albedo_texture(*scene, 1, o);
    EXPECT_GT(t.valid, 200u);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t.mean_albedo[c], s.box_albedo[c], 0.05 * s.box_albedo[c]) << c;
}

TEST(AlbedoTexture, ClippedPixelsAreFlaggedAndFilledFromTheirNeighbours) {
    GroundAndBox s;
    auto scene = s.photo(8);
    AlbedoTextureOptions o;
    o.width = o.height = 32;
    // The warm half in sunlight is the brightest part of the photo: clip it.
    std::vector<float> red;
    for (size_t k = 0; k < scene->photo().size(); ++k) red.push_back(scene->photo()[k].x);
    std::sort(red.begin(), red.end());
    o.clip_level = 0.9f * red[red.size() * 9 / 10];
    AlbedoTexture t = estimate_albedo_texture(*scene, 0, o);
    EXPECT_GT(t.clipped, 10u);
    for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 32; ++i) {
            vec3 a = t.albedo.at(i, j);
            ASSERT_TRUE(is_finite(a));
            ASSERT_GE(std::min({a.x, a.y, a.z}), 0.0f);
            ASSERT_LE(std::max({a.x, a.y, a.z}), 0.98f);
            // A clipped texel takes its value from valid ones: not black.
            if (t.mask.at(i, j).x == 1) {
                EXPECT_GT(luminance(a), 0.05f);
            }
        }
}

TEST(AlbedoTexture, FillingCopiesTheNearestValidValuesOutwards) {
    Image img(5, 1), mask(5, 1);
    img.at(0, 0) = vec3(0.2f);
    img.at(4, 0) = vec3(0.6f);
    for (int x = 1; x < 4; ++x) mask.at(x, 0) = vec3(0, 1, 0);
    ASSERT_TRUE(fill_flagged_texels(img, mask));
    EXPECT_FLOAT_EQ(img.at(1, 0).x, 0.2f);
    EXPECT_FLOAT_EQ(img.at(3, 0).x, 0.6f);
    EXPECT_FLOAT_EQ(img.at(2, 0).x, 0.4f);
    Image none(2, 2), all_flagged(2, 2, vec3(1, 0, 0));
    EXPECT_FALSE(fill_flagged_texels(none, all_flagged));
}

TEST(AlbedoTexture, AProxyTheCameraNeverSeesIsAnError) {
    GroundAndBox s;
    // Move the box behind the camera.
    s.project.real[1].transform.translation = vec3(0, 0.4f, 9);
    auto scene = build(s.project, Image(32, 24, vec3(0.1f)), s.probe);
    try {
        AlbedoTextureOptions o;
        o.width = o.height = 16;
        estimate_albedo_texture(*scene, 1, o);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("never sees"), std::string::npos) << e.what();
        EXPECT_EQ(e.field(), "real[1]");
    }
}
