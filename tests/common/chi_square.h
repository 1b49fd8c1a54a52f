#pragma once
// Statistics shared by the sampling tests: Pearson's chi-square test and its p-value.
#include <cmath>
#include <limits>
#include <vector>

namespace dp::test {

/// Regularised upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a): a series below
/// x = a + 1 and Lentz's continued fraction above (Numerical Recipes, section 6.2).
inline double regularized_gamma_q(double a, double x) {
    if (x <= 0) return 1.0;
    const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
    const double eps = 1e-15;
    if (x < a + 1) {
        double ap = a, sum = 1.0 / a, del = sum;
        for (int n = 0; n < 100000 && std::abs(del) > std::abs(sum) * eps; ++n) {
            ap += 1;
            del *= x / ap;
            sum += del;
        }
        return 1.0 - sum * std::exp(log_prefactor);
    }
    const double tiny = std::numeric_limits<double>::min() / eps;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::abs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1 / d;
        double del = d * c;
        h *= del;
        if (std::abs(del - 1) < eps) break;
    }
    return std::exp(log_prefactor) * h;
}

struct ChiSquare {
    double statistic = 0;
    int dof = 0;
    double p_value = 1;  ///< probability of a statistic at least this large under the model
};

/// Pearson's chi-square goodness-of-fit test. Bins expecting fewer than 5 counts are pooled into
/// one (Cochran's rule); a count in a bin expecting none gives p = 0.
inline ChiSquare chi_square_test(const std::vector<double>& observed,
                                 const std::vector<double>& expected) {
    ChiSquare r;
    double pooled_obs = 0, pooled_exp = 0;
    int bins = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] <= 0) {
            if (observed[i] > 0) return ChiSquare{std::numeric_limits<double>::infinity(), 0, 0};
            continue;
        }
        if (expected[i] < 5) {
            pooled_obs += observed[i];
            pooled_exp += expected[i];
            continue;
        }
        double d = observed[i] - expected[i];
        r.statistic += d * d / expected[i];
        ++bins;
    }
    if (pooled_exp > 0) {
        double d = pooled_obs - pooled_exp;
        r.statistic += d * d / pooled_exp;
        ++bins;
    }
    r.dof = bins - 1;
    r.p_value = r.dof > 0 ? regularized_gamma_q(0.5 * r.dof, 0.5 * r.statistic) : 1.0;
    return r;
}

}  // namespace dp::test
