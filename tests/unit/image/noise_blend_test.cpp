// The blend of a denoised picture with its raw one: the filter's picture where the raw is noisy
// and the filter only took noise away, the raw one where the raw has converged and the filter
// blurs what is really there.
#include "image/noise_blend.h"

#include <gtest/gtest.h>

#include <random>

#include "image/image_metrics.h"

using namespace dp;

namespace {

constexpr int kW = 96, kH = 64;

// A truth with fine detail (a 2-pixel checker of 3% of the value on a ramp), its raw render with
// white noise of deviation sigma, and a "denoised" picture that is noise-free but has lost the
// checker (about the error floor of the real filter on the benchmark scenes).
struct Case {
    Image truth, raw, denoised, variance;
};

Case make_case(float sigma, uint32_t seed) {
    Case c{Image(kW, kH), Image(kW, kH), Image(kW, kH), Image(kW, kH, vec3(sigma * sigma))};
    std::mt19937 rng(seed);
    std::normal_distribution<float> gauss(0.0f, sigma);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const float ramp = 0.3f + 0.4f * float(x) / kW, detail = ((x / 2 + y / 2) % 2) ? 0.015f : -0.015f;
            c.truth.at(x, y) = vec3(ramp + detail);
            c.denoised.at(x, y) = vec3(ramp);
            c.raw.at(x, y) = vec3(ramp + detail + gauss(rng));  // grey: luminance noise = sigma
        }
    return c;
}

double rmse(const Image& a, const Image& b) { return image_error(a, b).rmse; }

}  // namespace

TEST(NoiseBlend, ANoisyRawTakesTheFiltersPicture) {
    const Case c = make_case(0.1f, 1);  // noise seven times the detail the filter lost
    const Image out = blend_by_noise(c.raw, c.denoised, c.variance);
    EXPECT_LT(rmse(out, c.truth), 1.2 * rmse(c.denoised, c.truth));
    EXPECT_LT(rmse(out, c.truth), 0.3 * rmse(c.raw, c.truth));
}

TEST(NoiseBlend, AConvergedRawKeepsTheDetailTheFilterBlurred) {
    const Case c = make_case(0.002f, 2);  // noise a seventh of the detail
    const Image out = blend_by_noise(c.raw, c.denoised, c.variance);
    EXPECT_LE(rmse(out, c.truth), 1.1 * rmse(c.raw, c.truth));
    EXPECT_LT(rmse(out, c.truth), 0.3 * rmse(c.denoised, c.truth));
}

TEST(NoiseBlend, NeverWorseThanTheBetterOfTheTwoByMuch) {
    for (float sigma : {0.002f, 0.005f, 0.01f, 0.02f, 0.05f, 0.1f}) {
        const Case c = make_case(sigma, 3);
        const double best = std::min(rmse(c.raw, c.truth), rmse(c.denoised, c.truth));
        EXPECT_LT(rmse(blend_by_noise(c.raw, c.denoised, c.variance), c.truth), 1.25 * best) << "sigma " << sigma;
    }
}

TEST(NoiseBlend, WithoutAnEstimateTheFiltersPictureStandsAndUntouchedPixelsKeepTheirBits) {
    const Case c = make_case(0.1f, 4);
    EXPECT_EQ(rmse(blend_by_noise(c.raw, c.denoised, Image()), c.denoised), 0.0);
    Image same = c.denoised;
    same.at(5, 5) = c.raw.at(5, 5);
    const Image out = blend_by_noise(c.raw, same, c.variance);
    EXPECT_EQ(out.at(5, 5), c.raw.at(5, 5));
    EXPECT_THROW(blend_by_noise(c.raw, Image(3, 3), c.variance), std::invalid_argument);
}
