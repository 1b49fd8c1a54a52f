#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "reconstruction/albedo.h"
#include "recon_test_util.h"

using namespace dp;
using namespace dp::test;

namespace {

/// A 6 x 6 m two-tone ground and a grey box casting a shadow on it, under a sun and sky.
struct GroundAndBox {
    Project project = look_at_project(vec3(0.3f, 3.0f, 5.0f), vec3(0, 0, -0.2f), 50.0f);
    Image probe = sky_probe(vec3(0.6f, 0.45f, 0.35f));
    vec3 box_albedo{0.5f, 0.45f, 0.4f};
    GroundAndBox() {
        project.real.push_back(ground_plane(vec3(0.5f), 6.0f));
        RealProxy box;
        box.name = "box";
        box.shape.kind = Shape::Kind::Box;
        box.shape.size = vec3(0.8f);
        box.transform.translation = vec3(-0.6f, 0.4f, 0.3f);
        box.albedo.rgb = box_albedo;
        project.real.push_back(box);
    }
    std::shared_ptr<RenderScene> photo(int spp) {
        return photographed(project, probe, {two_tone_texture(), Image()}, 160, 120, spp);
    }
};

struct Errors {
    std::vector<double> rel;  // per valid texel and channel
    double quantile(double q) {
        std::sort(rel.begin(), rel.end());
        return rel.empty() ? 1e9 : rel[std::min(rel.size() - 1, size_t(q * rel.size()))];
    }
};

}  // namespace

TEST(AlbedoTexture, PerTexelEstimateOfATwoToneGroundIsWithinFivePercent) {
    GroundAndBox s;
    auto scene = s.photo(256);  // photo noise would otherwise dominate the error
    AlbedoTextureOptions o;
    o.width = o.height = 32;  // texel edges fall on the tone boundary at u = 1/2
    o.subsamples = 4;
    o.probe_samples = 1024;
    AlbedoTexture t = estimate_albedo_texture(*scene, 0, o);
    ASSERT_EQ(t.albedo.width(), 32);
    // Texels wholly in sunlight or wholly in the box's shadow (lit by the sky alone, so E is
    // small but must still be right); those across the shadow's edge, next to the tone
    // boundary or next to a flagged texel are left out: there a photo pixel mixes both sides.
    const vec3 sun = glm::normalize(vec3(0.6f, 0.45f, 0.35f));
    auto sunlit = [&](float u, float v) {
        vec3 p(6.0f * (u - 0.5f), 0, 6.0f * (0.5f - v));
        return !scene->occluded_real(Ray{p + vec3(0, 1e-3f, 0), sun});
    };
    Errors lit, shadow;
    for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 32; ++i) {
            if (i == 15 || i == 16) continue;
            bool interior = true;  // next to a flagged texel (the box's foot, the photo's edge)
            for (int k = 0; k < 9; ++k) {
                int x = std::clamp(i + k % 3 - 1, 0, 31), y = std::clamp(j + k / 3 - 1, 0, 31);
                interior = interior && t.mask.at(x, y) == vec3(0.0f);
            }
            if (!interior) continue;
            int sunny = 0;
            for (int k = 0; k < 16; ++k) sunny += sunlit((i + (k % 4 + 0.5f) / 4) / 32, (j + (k / 4 + 0.5f) / 4) / 32);
            if (sunny != 0 && sunny != 16) continue;
            vec3 want = two_tone((i + 0.5f) / 32), got = t.albedo.at(i, j);
            for (int c = 0; c < 3; ++c) (sunny ? lit : shadow).rel.push_back(std::abs(got[c] - want[c]) / want[c]);
        }
    RecordProperty("valid_texels", int(t.valid));
    RecordProperty("lit_median_rel_error", std::to_string(lit.quantile(0.5)));
    RecordProperty("lit_p95_rel_error", std::to_string(lit.quantile(0.95)));
    RecordProperty("shadow_median_rel_error", std::to_string(shadow.quantile(0.5)));
    RecordProperty("shadow_p95_rel_error", std::to_string(shadow.quantile(0.95)));
    RecordProperty("bounce_fraction", std::to_string(t.bounce_fraction));
    EXPECT_GT(t.valid, 600u);
    ASSERT_GT(lit.rel.size(), 1500u);
    ASSERT_GT(shadow.rel.size(), 15u);
    EXPECT_LT(lit.quantile(0.5), 0.02);
    EXPECT_LT(lit.quantile(0.95), 0.05);
    EXPECT_LT(shadow.quantile(0.5), 0.05);
    EXPECT_LT(t.irradiance_rel_error, 0.02);
}

TEST(AlbedoTexture, TheBoxTextureGathersItsVisibleFacesWithinFivePercent) {
    GroundAndBox s;
    auto scene = s.photo(64);
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
