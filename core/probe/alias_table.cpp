#include <algorithm>
#include <cmath>

#include "probe/alias_build.h"
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
    total_ = build_alias_table(
        n, [&](size_t i) { return weights[i]; },
        [&](size_t i, double prob, uint32_t alias) {
            prob_[i] = prob;
            alias_[i] = alias;
        });
    if (total_ <= 0) return;  // empty-ish table
    for (size_t i = 0; i < n; ++i)
        pmf_[i] = std::isfinite(weights[i]) && weights[i] > 0 ? weights[i] / total_ : 0.0;
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
