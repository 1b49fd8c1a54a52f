#include <algorithm>
#include <cmath>

#include "probe/probe.h"

namespace dp {

namespace {
// Largest double below 1: keeps fractions and remapped numbers inside [0, 1).
constexpr double kOneMinusEpsilon = 0x1.fffffffffffffp-1;
}  // namespace

AliasTable::AliasTable(const std::vector<double>& weights) {
    const size_t n = weights.size();
    pmf_.assign(n, 0.0);
    prob_.assign(n, 1.0);
    alias_.resize(n);
    for (size_t i = 0; i < n; ++i) alias_[i] = uint32_t(i);

    auto clean = [](double w) { return std::isfinite(w) && w > 0 ? w : 0.0; };
    double total = 0;
    for (double w : weights) total += clean(w);
    if (!(total > 0) || !std::isfinite(total)) return;  // empty-ish table: total_ stays 0
    total_ = total;
    for (size_t i = 0; i < n; ++i) pmf_[i] = clean(weights[i]) / total;

    // Vose's method. Everything stays in double so that a sun 1e6 times the sky (or far more)
    // keeps exact probabilities for the faint pixels.
    std::vector<double> scaled(n);
    std::vector<uint32_t> small, large;
    small.reserve(n);
    large.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        scaled[i] = pmf_[i] * double(n);
        (scaled[i] < 1.0 ? small : large).push_back(uint32_t(i));
    }
    while (!small.empty() && !large.empty()) {
        uint32_t s = small.back(), l = large.back();
        small.pop_back();
        prob_[s] = scaled[s];
        alias_[s] = l;
        // (a + b) - 1 rather than a - (1 - b): Vose's recommended order, less cancellation.
        scaled[l] = (scaled[l] + scaled[s]) - 1.0;
        if (scaled[l] < 1.0) {
            large.pop_back();
            small.push_back(l);
        }
    }
    // Leftovers are 1 up to rounding; they keep prob 1 and alias themselves.
}

size_t AliasTable::sample(double u) const { return sample(u, nullptr); }

size_t AliasTable::sample(double u, double* u_remapped) const {
    const size_t n = pmf_.size();
    if (total_ <= 0 || n == 0) {
        if (u_remapped) *u_remapped = std::clamp(u, 0.0, kOneMinusEpsilon);
        return 0;
    }
    double scaled = std::clamp(u, 0.0, kOneMinusEpsilon) * double(n);
    size_t i = std::min(size_t(scaled), n - 1);
    double frac = std::min(scaled - double(i), kOneMinusEpsilon);
    size_t picked;
    double rest;
    if (frac < prob_[i]) {
        picked = i;
        rest = frac / prob_[i];
    } else {
        picked = alias_[i];
        rest = (frac - prob_[i]) / (1.0 - prob_[i]);
    }
    if (u_remapped) *u_remapped = std::clamp(rest, 0.0, kOneMinusEpsilon);
    return picked;
}

}  // namespace dp
