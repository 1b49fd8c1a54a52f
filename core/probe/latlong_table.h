#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "base/math.h"
#include "probe/huge_pages.h"

namespace dp {

/// A distribution over the pixels of a lat-long map, sampled by inverting its marginal (rows)
/// and conditional (columns) CDFs: a monotone map of the unit square, so stratified or
/// low-discrepancy points stay evenly spread over a bright region such as the sun's disk.
/// Only rows of positive weight keep a column CDF (8 bytes a pixel): a table of the sun's few
/// rows takes next to nothing.
class LatLongTable {
public:
    LatLongTable() = default;
    /// `weights` per pixel, row-major, width x height; negative and non-finite weights count
    /// as 0. A pixel or row of zero weight is never picked.
    LatLongTable(int width, int height, const std::vector<double>& weights);
    /// As above with the weight of pixel k given by `weight(k)`, called twice per pixel, so that
    /// no per-pixel array of weights is needed to build the table.
    LatLongTable(int width, int height, const std::function<double(size_t)>& weight);

    bool empty() const { return !(total_ > 0); }
    double total() const { return total_; }
    /// The probability of a pixel: its weight over the total (0 for an empty table).
    double pmf(size_t pixel) const;
    /// Bytes held per pixel of the map (the column CDFs of the rows that have weight).
    double bytes_per_pixel() const;

    /// The pixel holding point u of the unit square (u.x along the row, u.y across rows) and
    /// the fractions of u inside the pixel's interval, in [0, 1).
    struct Pick {
        size_t pixel = 0;
        double fx = 0.5, fy = 0.5;
    };
    Pick sample(vec2 u) const;

private:
    static constexpr uint64_t kNoRow = ~uint64_t(0);

    int width_ = 0, height_ = 0;
    double total_ = 0;
    std::vector<double> row_cdf_;     ///< height + 1 entries
    std::vector<double> row_weight_;  ///< each row's total weight
    /// Where each row's column CDF starts in column_cdf_ (kNoRow for a row of zero weight).
    std::vector<uint64_t> row_start_;
    std::vector<double, HugePageAllocator<double>> column_cdf_;  ///< width + 1 entries per kept row
};

}  // namespace dp
