#include "probe/latlong_table.h"

#include <algorithm>
#include <cmath>

namespace dp {

namespace {
constexpr double kOneMinusEpsilon = 0x1.fffffffffffffp-1;
double clean(double w) { return std::isfinite(w) && w > 0 ? w : 0.0; }
}  // namespace

LatLongTable::LatLongTable(int width, int height, const std::vector<double>& weights)
    : LatLongTable(weights.size() == size_t(std::max(width, 0)) * size_t(std::max(height, 0)) ? width : 0, height,
                   [&](size_t k) { return weights[k]; }) {}

LatLongTable::LatLongTable(int width, int height, const std::function<double(size_t)>& weight)
    : width_(width), height_(height) {
    if (width <= 0 || height <= 0) return;
    const size_t w = size_t(width);
    row_cdf_.assign(size_t(height) + 1, 0.0);
    row_weight_.assign(size_t(height), 0.0);
    row_start_.assign(size_t(height), kNoRow);
    // First the row sums, to know which rows need a column CDF; the second pass sums in the
    // same order, so each CDF ends where its row sum says.
    uint64_t kept = 0;
    for (int j = 0; j < height; ++j) {
        double sum = 0;
        for (size_t i = 0; i < w; ++i) sum += clean(weight(size_t(j) * w + i));
        row_weight_[j] = sum;
        row_cdf_[j + 1] = row_cdf_[j] + sum;
        if (sum > 0) row_start_[j] = kept++ * (w + 1);
    }
    total_ = row_cdf_[height];
    if (!(total_ > 0) || !std::isfinite(total_)) {
        *this = LatLongTable();
        return;
    }
    column_cdf_.assign(kept * (w + 1), 0.0);
    for (int j = 0; j < height; ++j) {
        if (row_start_[j] == kNoRow) continue;
        double* cdf = &column_cdf_[row_start_[j]];
        for (size_t i = 0; i < w; ++i) cdf[i + 1] = cdf[i] + clean(weight(size_t(j) * w + i));
        // Dividing by the sum itself ends each table at exactly 1, and a pixel of zero weight
        // keeps an empty interval.
        const double row_sum = cdf[w];
        for (size_t i = 1; i <= w; ++i) cdf[i] /= row_sum;
    }
    for (double& c : row_cdf_) c /= total_;
}

double LatLongTable::pmf(size_t pixel) const {
    if (empty()) return 0;
    const size_t j = pixel / size_t(width_), i = pixel % size_t(width_);
    if (row_start_[j] == kNoRow) return 0;
    const double* cdf = &column_cdf_[row_start_[j]];
    return (cdf[i + 1] - cdf[i]) * row_weight_[j] / total_;
}

double LatLongTable::bytes_per_pixel() const {
    const double pixels = double(std::max(width_, 0)) * double(std::max(height_, 0));
    if (pixels <= 0) return 0;
    const double bytes = double(column_cdf_.size()) * sizeof(double) +
                         double(row_cdf_.size() + row_weight_.size()) * sizeof(double) +
                         double(row_start_.size()) * sizeof(uint64_t);
    return bytes / pixels;
}

LatLongTable::Pick LatLongTable::sample(vec2 u) const {
    Pick p;
    if (empty()) return p;
    const double uy = std::min(double(u.y), kOneMinusEpsilon);
    int j = std::clamp(
        int(std::upper_bound(row_cdf_.begin(), row_cdf_.end(), uy) - row_cdf_.begin()) - 1, 0, height_ - 1);
    // upper_bound never stops on a row of zero weight (its interval is empty); should rounding
    // ever make it, the nearest row with weight stands in rather than reading past the table.
    for (int k = j; row_start_[j] == kNoRow && k >= 0; --k) j = k;
    for (int k = j; row_start_[j] == kNoRow && k < height_; ++k) j = k;
    const double row_p = row_cdf_[j + 1] - row_cdf_[j];
    p.fy = row_p > 0 ? std::clamp((uy - row_cdf_[j]) / row_p, 0.0, kOneMinusEpsilon) : 0.5;
    const double* cdf = &column_cdf_[row_start_[j]];
    const double ux = std::min(double(u.x), kOneMinusEpsilon);
    const int i = std::clamp(int(std::upper_bound(cdf, cdf + width_ + 1, ux) - cdf) - 1, 0, width_ - 1);
    const double col_p = cdf[i + 1] - cdf[i];
    p.fx = col_p > 0 ? std::clamp((ux - cdf[i]) / col_p, 0.0, kOneMinusEpsilon) : 0.5;
    p.pixel = size_t(j) * width_ + i;
    return p;
}

}  // namespace dp
