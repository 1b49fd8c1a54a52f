#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dp {

/// Builds a Walker/Vose alias table over `n` weights, `weight(i)` for i < n (negative and
/// non-finite ones count as 0), handing each column to `store(i, prob, alias)`: sampling keeps
/// index i with probability prob and takes `alias` otherwise. Columns that need no alias are
/// stored as (i, 1, i). Returns the sum of the weights; when it is 0 (or not finite) nothing is
/// stored. Takes 12 bytes per weight while it runs (the scaled weights and one work list), so
/// that the caller can keep its table in whatever precision it needs.
template <class Weight, class Store>
double build_alias_table(size_t n, Weight&& weight, Store&& store) {
    auto clean = [](double w) { return std::isfinite(w) && w > 0 ? w : 0.0; };
    double total = 0;
    for (size_t i = 0; i < n; ++i) total += clean(weight(i));
    if (!(total > 0) || !std::isfinite(total)) return 0;

    // Vose's method in double, so that a sun 1e6 times the sky (or far more) keeps exact
    // probabilities for the faint pixels. One list holds both stacks: the small indices grow
    // from the front, the large ones from the back, each popped at its top as Vose pops them.
    std::vector<double> scaled(n);
    std::vector<uint32_t> list(n);
    size_t small_end = 0, large_begin = n;
    for (size_t i = 0; i < n; ++i) {
        scaled[i] = clean(weight(i)) / total * double(n);
        if (scaled[i] < 1.0)
            list[small_end++] = uint32_t(i);
        else
            list[--large_begin] = uint32_t(i);
        store(i, 1.0, uint32_t(i));
    }
    while (small_end > 0 && large_begin < n) {
        const uint32_t s = list[--small_end], l = list[large_begin];
        store(s, scaled[s], l);
        // (a + b) - 1 rather than a - (1 - b): Vose's recommended order, less cancellation.
        scaled[l] = (scaled[l] + scaled[s]) - 1.0;
        if (scaled[l] < 1.0) {
            ++large_begin;
            list[small_end++] = l;  // the slot s left is free: small_end < large_begin
        }
    }
    // Leftovers are 1 up to rounding; they keep prob 1 and alias themselves.
    return total;
}

}  // namespace dp
