// Per-texel albedo from a path-traced photograph: the texture comes back within 5% where the
// photo sees the ground lit and unclipped, in sunlight and in a shadow lit by the sky alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/synthetic_photo.h"
#include "reconstruction/albedo.h"

using namespace dp;
using namespace dp::test;

namespace {

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

