#include "probe/latlong_table.h"

#include <algorithm>
#include <cmath>

namespace dp {

namespace {
constexpr double kOneMinusEpsilon = 0x1.fffffffffffffp-1;
double clean(double w) { return std::isfinite(w) && w > 0 ? w : 0.0; }
}  // namespace

LatLongTable::LatLongTable(int width, int height, const std::vector<double>& weights)
    : width_(width), height_(height) {
    if (width <= 0 || height <= 0 || weights.size() != size_t(width) * height) return;
    row_cdf_.assign(size_t(height) + 1, 0.0);
    row_weight_.assign(size_t(height), 0.0);
    column_cdf_.assign(size_t(height) * (width + 1), 0.0);
    for (int j = 0; j < height; ++j) {
        double* cdf = &column_cdf_[size_t(j) * (width + 1)];
        for (int i = 0; i < width; ++i) cdf[i + 1] = cdf[i] + clean(weights[size_t(j) * width + i]);
        const double row_sum = cdf[width];
        row_weight_[j] = row_sum;
        row_cdf_[j + 1] = row_cdf_[j] + row_sum;
        // Dividing by the sum itself ends each table at exactly 1, and a pixel of zero weight
        // keeps an empty interval.
        for (int i = 1; i <= width; ++i) cdf[i] = row_sum > 0 ? cdf[i] / row_sum : double(i) / width;
    }
    total_ = row_cdf_[height];
    if (!(total_ > 0) || !std::isfinite(total_)) {
        total_ = 0;
        return;
    }
    for (double& c : row_cdf_) c /= total_;
}

double LatLongTable::pmf(size_t pixel) const {
    if (empty()) return 0;
    const size_t j = pixel / size_t(width_), i = pixel % size_t(width_);
    const double* cdf = &column_cdf_[j * (width_ + 1)];
    return (cdf[i + 1] - cdf[i]) * row_weight_[j] / total_;
}

LatLongTable::Pick LatLongTable::sample(vec2 u) const {
    Pick p;
    if (empty()) return p;
    const double uy = std::min(double(u.y), kOneMinusEpsilon);
    const int j = std::clamp(
        int(std::upper_bound(row_cdf_.begin(), row_cdf_.end(), uy) - row_cdf_.begin()) - 1, 0, height_ - 1);
    const double row_p = row_cdf_[j + 1] - row_cdf_[j];
    p.fy = row_p > 0 ? std::clamp((uy - row_cdf_[j]) / row_p, 0.0, kOneMinusEpsilon) : 0.5;
    const double* cdf = &column_cdf_[size_t(j) * (width_ + 1)];
    const double ux = std::min(double(u.x), kOneMinusEpsilon);
    const int i = std::clamp(int(std::upper_bound(cdf, cdf + width_ + 1, ux) - cdf) - 1, 0, width_ - 1);
    const double col_p = cdf[i + 1] - cdf[i];
    p.fx = col_p > 0 ? std::clamp((ux - cdf[i]) / col_p, 0.0, kOneMinusEpsilon) : 0.5;
    p.pixel = size_t(j) * width_ + i;
    return p;
}

}  // namespace dp
