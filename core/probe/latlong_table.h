#pragma once
#include <cstddef>
#include <vector>

#include "base/math.h"
#include "probe/huge_pages.h"

namespace dp {

/// A distribution over the pixels of a lat-long map, sampled by inverting its marginal (rows)
/// and conditional (columns) CDFs: a monotone map of the unit square, so stratified or
/// low-discrepancy points stay evenly spread over a bright region such as the sun's disk.
class LatLongTable {
public:
    LatLongTable() = default;
    /// `weights` per pixel, row-major, width x height; negative and non-finite weights count
    /// as 0. A pixel or row of zero weight is never picked.
    LatLongTable(int width, int height, const std::vector<double>& weights);

    bool empty() const { return !(total_ > 0); }
    double total() const { return total_; }
    /// The probability of a pixel: its weight over the total (0 for an empty table).
    double pmf(size_t pixel) const;

    /// The pixel holding point u of the unit square (u.x along the row, u.y across rows) and
    /// the fractions of u inside the pixel's interval, in [0, 1).
    struct Pick {
        size_t pixel = 0;
        double fx = 0.5, fy = 0.5;
    };
    Pick sample(vec2 u) const;

private:
    int width_ = 0, height_ = 0;
    double total_ = 0;
    std::vector<double> row_cdf_;  ///< height + 1 entries
    std::vector<double, HugePageAllocator<double>> column_cdf_;  ///< per row, width + 1 entries
    std::vector<double> row_weight_;  ///< each row's total weight
};

}  // namespace dp
