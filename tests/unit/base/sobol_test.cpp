// The Owen-scrambled Sobol' sampler: net properties, uniformity, and faster convergence than
// independent random samples on smooth integrands.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "base/rng.h"
#include "base/sobol.h"
#include "common/chi_square.h"

using namespace dp;

namespace {

/// True if `points` has exactly one point in every elementary box 2^-a x 2^-b, a + b = k.
bool is_02_net(const std::vector<vec2>& points, int k) {
    for (int a = 0; a <= k; ++a) {
        const int b = k - a;
        std::set<std::pair<int, int>> boxes;
        for (const vec2& p : points) boxes.insert({int(p.x * float(1 << a)), int(p.y * float(1 << b))});
        if (boxes.size() != points.size()) return false;
    }
    return true;
}

}  // namespace

TEST(Sobol, TheFirstTwoDimensionsMatchTheKnownSequence) {
    const float x[8] = {0, 0.5f, 0.25f, 0.75f, 0.125f, 0.625f, 0.375f, 0.875f};
    const float y[8] = {0, 0.5f, 0.75f, 0.25f, 0.625f, 0.125f, 0.375f, 0.875f};
    for (uint32_t i = 0; i < 8; ++i) {
        EXPECT_EQ(fixed_to_unit(sobol_dimension0(i)), x[i]) << i;
        EXPECT_EQ(fixed_to_unit(sobol_dimension1(i)), y[i]) << i;
    }
}

TEST(Sobol, EveryPowerOfTwoPrefixOfAPixelsPairIsA02Net) {
    for (uint64_t pixel = 0; pixel < 20; ++pixel) {
        PixelSampler base(7, pixel, 0);
        for (int pair = 0; pair < 3; ++pair) {
            std::vector<vec2> pts;
            for (int k = 0; k <= 9; ++k) {
                while (pts.size() < (size_t(1) << k)) {
                    PixelSampler s = base.with_index(uint32_t(pts.size()));
                    for (int d = 0; d < pair; ++d) s.next2d();
                    pts.push_back(s.next2d());
                }
                ASSERT_TRUE(is_02_net(pts, k)) << "pixel " << pixel << " pair " << pair << " 2^" << k;
            }
        }
    }
}

TEST(Sobol, ScrambledPointsAreUniformOverPixelsAndPairsAreIndependent) {
    // Sample 3 of many pixels: each pair is uniform on a 16x16 grid, and the first coordinates
    // of two different pairs are jointly uniform (padding decorrelates them).
    const int cells = 16, pixels = 200000;
    std::vector<double> one(cells * cells, 0), two(cells * cells, 0), expected(cells * cells, pixels / 256.0);
    for (int p = 0; p < pixels; ++p) {
        PixelSampler s(3, uint64_t(p), 3);
        const vec2 a = s.next2d(), b = s.next2d();
        one[int(a.x * cells) * cells + int(a.y * cells)] += 1;
        two[int(a.x * cells) * cells + int(b.x * cells)] += 1;
    }
    const test::ChiSquare c1 = test::chi_square_test(one, expected), c2 = test::chi_square_test(two, expected);
    EXPECT_GT(c1.p_value, 1e-3) << c1.statistic;
    EXPECT_GT(c2.p_value, 1e-3) << c2.statistic;
}

TEST(Sobol, ASmoothIntegrandConvergesFasterThanWithRandomSamples) {
    // f(x, y) = exp(x) * sin(pi y): the exact mean is (e - 1) * 2 / pi.
    const double exact = (std::exp(1.0) - 1) * 2 / 3.14159265358979;
    auto f = [](vec2 p) { return std::exp(double(p.x)) * std::sin(3.14159265358979 * p.y); };
    auto rmse = [&](int n, bool sobol) {
        double sum2 = 0;
        const int trials = 400;
        for (int t = 0; t < trials; ++t) {
            double sum = 0;
            Rng rng(11, uint64_t(t));
            PixelSampler base(5, uint64_t(t), 0);
            for (int i = 0; i < n; ++i) {
                vec2 p = sobol ? base.with_index(uint32_t(i)).next2d() : vec2(rng.uniform(), rng.uniform());
                sum += f(p);
            }
            sum2 += (sum / n - exact) * (sum / n - exact);
        }
        return std::sqrt(sum2 / trials);
    };
    // Log-log slope between 16 and 256 samples: -0.5 for random, about -1.5 for Owen-scrambled.
    const double slope_random = std::log(rmse(256, false) / rmse(16, false)) / std::log(16.0);
    const double slope_sobol = std::log(rmse(256, true) / rmse(16, true)) / std::log(16.0);
    std::printf("error slope: random %.2f, Sobol' %.2f\n", slope_random, slope_sobol);
    EXPECT_NEAR(slope_random, -0.5, 0.15);
    EXPECT_LT(slope_sobol, -1.2);
    EXPECT_LT(rmse(64, true), 0.1 * rmse(64, false));
}
