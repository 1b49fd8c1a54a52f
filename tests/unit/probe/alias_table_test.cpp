#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "base/rng.h"
#include "probe/probe.h"
#include "probe_test_util.h"

using namespace dp;

namespace {

// Recovers the probability with which sample() returns each index, using only the public
// interface: within column c (u in [c, c+1)/n) the result switches once, from c to its alias,
// at a threshold found by bisection in u. The ends stay a few ulps inside the column so that
// rounding in u * n cannot reach the neighbours.
std::vector<double> realized_pmf(const AliasTable& table) {
    const size_t n = table.size();
    std::vector<double> p(n, 0.0);
    for (size_t c = 0; c < n; ++c) {
        double begin = double(c) / n, end = double(c + 1) / n;
        double margin = 4 * (std::nextafter(end, 2.0) - end);
        double lo = begin + margin, hi = end - margin;
        size_t first = table.sample(lo), last = table.sample(hi);
        if (first == last) {
            p[first] += end - begin;
            continue;
        }
        for (int it = 0; it < 80; ++it) {
            double mid = 0.5 * (lo + hi);
            (table.sample(mid) == first ? lo : hi) = mid;
        }
        p[first] += lo - begin;
        p[last] += end - lo;
    }
    return p;
}

}  // namespace

TEST(AliasTable, PmfIsEachWeightOverTheTotal) {
    std::vector<double> w = {1, 0, 3, 6, 0.5, 9.5};
    AliasTable t(w);
    ASSERT_EQ(t.size(), w.size());
    EXPECT_DOUBLE_EQ(t.total(), 20.0);
    for (size_t i = 0; i < w.size(); ++i) EXPECT_DOUBLE_EQ(t.pmf(i), w[i] / 20.0);
}

TEST(AliasTable, SampledFrequenciesPassAChiSquareTest) {
    Rng rng(3, 9);
    std::vector<double> w(1000);
    for (size_t i = 0; i < w.size(); ++i) w[i] = i % 7 == 0 ? 0.0 : std::exp(4 * rng.uniform());
    AliasTable t(w);
    const int n = 1000000;
    std::vector<double> observed(w.size(), 0.0), expected(w.size());
    for (int k = 0; k < n; ++k) observed[t.sample(rng.uniform_double())] += 1;
    for (size_t i = 0; i < w.size(); ++i) expected[i] = n * t.pmf(i);
    test::ChiSquare chi = test::chi_square_test(observed, expected);
    EXPECT_GT(chi.p_value, 1e-3) << "chi2 " << chi.statistic << " dof " << chi.dof;
}

TEST(AliasTable, RealizedProbabilitiesMatchThePmfAtABillionToOne) {
    // Bright entries a billion times the faint ones: single-precision sums and residuals would
    // misplace the faint entries' share. Probabilities below ~1e-15 cannot be resolved through
    // a double u at all, so those entries are only checked through pmf().
    std::vector<double> w = {1e9, 1.0, 3.0, 1e9, 0.5, 2e6, 0.0, 5.0, 1e-8, 1e9};
    AliasTable t(w);
    std::vector<double> p = realized_pmf(t);
    double sum = 0;
    for (double x : w) sum += x;
    for (size_t i = 0; i < w.size(); ++i) {
        EXPECT_DOUBLE_EQ(t.pmf(i), w[i] / sum);
        EXPECT_NEAR(p[i], t.pmf(i), 1e-6 * t.pmf(i) + 2e-15) << "index " << i;
    }
}

TEST(AliasTable, RealizedProbabilitiesMatchThePmfForASunOverAWholeSky) {
    // One entry a million times each of 2^17 others: the bright entry is paired with every faint
    // one in turn, and any rounding in its running remainder ends up in the faint entries.
    Rng rng(8, 1);
    std::vector<double> w(1 << 17);
    for (double& x : w) x = 0.5 + rng.uniform_double();
    w[4321] = 1e6;
    AliasTable t(w);
    std::vector<double> p = realized_pmf(t);
    double worst = 0;
    for (size_t i = 0; i < w.size(); ++i) worst = std::max(worst, std::abs(p[i] / t.pmf(i) - 1));
    EXPECT_LT(worst, 1e-6);
}

TEST(AliasTable, AllZeroWeightsGiveAnEmptyTableThatSamplesIndexZero) {
    AliasTable zeros(std::vector<double>{0, 0, 0});
    EXPECT_EQ(zeros.total(), 0.0);
    EXPECT_EQ(zeros.size(), 3u);
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(zeros.pmf(i), 0.0);
    EXPECT_EQ(zeros.sample(0.9), 0u);
    EXPECT_EQ(zeros.sample(0.0), 0u);

    AliasTable none(std::vector<double>{});
    EXPECT_EQ(none.total(), 0.0);
    EXPECT_EQ(none.sample(0.5), 0u);
    AliasTable defaulted;
    EXPECT_EQ(defaulted.sample(0.5), 0u);
}

TEST(AliasTable, NegativeAndNonFiniteWeightsCountAsZero) {
    const double inf = std::numeric_limits<double>::infinity();
    AliasTable t(std::vector<double>{2, -5, std::nan(""), inf, 2});
    EXPECT_DOUBLE_EQ(t.total(), 4.0);
    EXPECT_DOUBLE_EQ(t.pmf(0), 0.5);
    EXPECT_EQ(t.pmf(1), 0.0);
    EXPECT_EQ(t.pmf(2), 0.0);
    EXPECT_EQ(t.pmf(3), 0.0);
    for (int k = 0; k < 1000; ++k) {
        size_t i = t.sample((k + 0.5) / 1000);
        EXPECT_TRUE(i == 0 || i == 4) << i;
    }
}

TEST(AliasTable, RemappedNumberIsUniformGivenTheIndex) {
    std::vector<double> w = {1, 2, 3, 4, 50, 0.25, 7};
    AliasTable t(w);
    const int n = 700000, bins = 10;
    Rng rng(11, 2);
    std::vector<double> observed(w.size() * bins, 0.0), expected(w.size() * bins);
    for (int k = 0; k < n; ++k) {
        double r = -1;
        size_t i = t.sample(rng.uniform_double(), &r);
        ASSERT_GE(r, 0.0);
        ASSERT_LT(r, 1.0);
        observed[i * bins + size_t(r * bins)] += 1;
    }
    for (size_t i = 0; i < w.size(); ++i)
        for (int b = 0; b < bins; ++b) expected[i * bins + b] = n * t.pmf(i) / bins;
    test::ChiSquare chi = test::chi_square_test(observed, expected);
    EXPECT_GT(chi.p_value, 1e-3) << "chi2 " << chi.statistic << " dof " << chi.dof;
}

TEST(ChiSquareHelper, MatchesClosedFormsAndTables) {
    // Two degrees of freedom: Q = exp(-x / 2).
    for (double x : {0.1, 1.0, 3.0, 10.0, 40.0})
        EXPECT_NEAR(test::regularized_gamma_q(1.0, x / 2), std::exp(-x / 2), 1e-12);
    // Tabulated 0.001 critical values for 10 and 100 degrees of freedom.
    EXPECT_NEAR(test::regularized_gamma_q(5.0, 29.588 / 2), 1e-3, 2e-6);
    EXPECT_NEAR(test::regularized_gamma_q(50.0, 149.449 / 2), 1e-3, 2e-6);
    std::vector<double> o = {10, 10, 10, 70}, e = {25, 25, 25, 25};
    EXPECT_LT(test::chi_square_test(o, e).p_value, 1e-6);
}
