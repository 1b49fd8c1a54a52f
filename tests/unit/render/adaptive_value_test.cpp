// Adaptive sampling judges a tile's error against its pixels' values clamped where the error's
// halves are: a tile that rare photons of huge flux lit in both halves (so that those pixels'
// clamped halves agree) is not taken as converged against the brightness they gave it.
#include <gtest/gtest.h>

#include <cmath>

#include "render/progressive.h"
#include "render/tile_accumulator.h"

using namespace dp;

namespace {

/// The rule of ProgressiveRenderer::update_convergence for one tile.
bool converged(const TileAccumulator& sums, double before, double floor, double ceiling, double threshold) {
    double e2 = 0, value = 0;
    const int n = sums.width() * sums.height();
    for (size_t i = 0; i < size_t(n); ++i) {
        e2 += sums.error2(i, before, ceiling);
        value += judged_value(before, luminance(sums.mean_pixel_change(i)), floor, ceiling);
    }
    return std::sqrt(e2 / n) < threshold * (value / n);
}

}  // namespace

TEST(AdaptiveValue, ATileLitByHugePhotonsInBothHalvesIsNotTakenAsConverged) {
    constexpr int kTile = 8, kPasses = 64;
    const double before = 0.5, floor = 0.05, ceiling = 4.8, threshold = 0.002;
    TileAccumulator sums(kTile, kTile, kTile);
    for (int pass = 1; pass <= kPasses; ++pass) {
        SampleResult samples[kTile * kTile];
        for (int i = 0; i < kTile * kTile; ++i) {
            // Three quarters of the tile under a caustic of rare, huge photons: 400 in every
            // pass on average, in odd and even passes alike; the rest noisy floor (0.6 in odd
            // passes, 0.4 in even ones).
            const float change = i < 48 ? 400.0f : (pass % 2 ? 0.6f : 0.4f);
            samples[i].pixel_change = samples[i].dL = vec3(change);
        }
        sums.add_tile(0, pass % 2 == 1, samples);
        sums.finish_pass();
    }
    // The caustic's pixels: both halves clamped to the ceiling, no error seen; the floor's: 0.01.
    EXPECT_EQ(sums.error2(0, before, ceiling), 0.0);
    EXPECT_NEAR(sums.error2(63, before, ceiling), 0.01, 1e-6);  // float samples
    EXPECT_EQ(judged_value(before, 400, floor, ceiling), ceiling);
    EXPECT_EQ(judged_value(before, 0.3, floor, ceiling), 0.8);
    EXPECT_EQ(judged_value(0.01, 0, floor, ceiling), floor);
    EXPECT_FALSE(converged(sums, before, floor, ceiling, threshold));
    // Judged against the unclamped values (300 on average) the same tile would have stopped.
    double e2 = 0, value = 0;
    for (size_t i = 0; i < kTile * kTile; ++i) {
        e2 += sums.error2(i, before, ceiling);
        value += before + luminance(sums.mean_pixel_change(i));
    }
    EXPECT_LT(std::sqrt(e2 / 64), threshold * value / 64);
    // A tile whose noise has really gone is still taken as converged.
    TileAccumulator calm(kTile, kTile, kTile);
    for (int pass = 1; pass <= kPasses; ++pass) {
        SampleResult samples[kTile * kTile];
        for (SampleResult& s : samples) s.pixel_change = s.dL = vec3(0.5f);
        calm.add_tile(0, pass % 2 == 1, samples);
        calm.finish_pass();
    }
    EXPECT_TRUE(converged(calm, before, floor, ceiling, threshold));
}
