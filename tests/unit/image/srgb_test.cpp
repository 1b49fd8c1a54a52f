#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "image/image_io.h"

using namespace dp;

TEST(Srgb, DecodingMatchesKnownValues) {
    EXPECT_EQ(srgb_to_linear(0.0f), 0.0f);
    EXPECT_NEAR(srgb_to_linear(1.0f), 1.0f, 1e-7);
    EXPECT_NEAR(srgb_to_linear(0.5f), 0.214041f, 1e-6);
    // Below the 0.04045 knee the curve is the linear segment v / 12.92.
    EXPECT_NEAR(srgb_to_linear(0.02f), 0.02f / 12.92f, 1e-9);
    EXPECT_NEAR(srgb_to_linear(0.04045f), 0.0031308f, 1e-7);
}

TEST(Srgb, EncodingMatchesKnownValues) {
    EXPECT_EQ(linear_to_srgb(0.0f), 0.0f);
    EXPECT_NEAR(linear_to_srgb(1.0f), 1.0f, 1e-7);
    EXPECT_NEAR(linear_to_srgb(0.214041f), 0.5f, 1e-6);
    EXPECT_NEAR(linear_to_srgb(0.18f), 0.461356f, 1e-6);
    EXPECT_NEAR(linear_to_srgb(0.001f), 0.01292f, 1e-8);
}

TEST(Srgb, EncodingAndDecodingAreInversesOfEachOther) {
    float worst_decode_encode = 0.0f, worst_encode_decode = 0.0f;
    for (int i = 0; i <= 1000; ++i) {
        const float v = float(i) / 1000.0f;
        worst_decode_encode =
            std::max(worst_decode_encode, std::abs(linear_to_srgb(srgb_to_linear(v)) - v));
        worst_encode_decode =
            std::max(worst_encode_decode, std::abs(srgb_to_linear(linear_to_srgb(v)) - v));
    }
    EXPECT_LT(worst_decode_encode, 1e-6f);
    EXPECT_LT(worst_encode_decode, 1e-6f);
}
