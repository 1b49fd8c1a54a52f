#include "probe/probe_bounds.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dp {

namespace {
constexpr double kPiD = std::numbers::pi;

/// Floor division for possibly negative numerators.
int floor_div(long long a, long long b) { return int(a >= 0 ? a / b : -((-a + b - 1) / b)); }
}  // namespace

ProbeMaxGrid::ProbeMaxGrid(const Probe& probe, int columns, int rows) : probe_(&probe) {
    const int w = probe.width(), h = probe.height();
    if (w <= 0 || h <= 0) return;
    columns_ = std::clamp(columns, 1, w);
    rows_ = std::clamp(rows, 1, h);
    cells_.assign(size_t(columns_) * rows_, 0.0f);
    for (int j = 0; j < h; ++j) {
        const int cj = int((long long)j * rows_ / h);
        for (int i = 0; i < w; ++i) {
            const float l = luminance(probe.pixel_radiance(size_t(j) * w + i));
            float& c = cells_[size_t(cj) * columns_ + int((long long)i * columns_ / w)];
            if (l > c) c = l;  // NaN and negative luminance never raise a maximum
        }
    }
    row_max_.assign(rows_, 0.0f);
    row_theta_.assign(size_t(rows_) + 1, 0.0);
    for (int r = 0; r < rows_; ++r) {
        for (int c = 0; c < columns_; ++c) row_max_[r] = std::max(row_max_[r], cell(c, r));
        global_max_ = std::max(global_max_, row_max_[r]);
        // First pixel row of cell row r: the smallest j with j * rows / h == r.
        row_theta_[r] = kPiD * double(((long long)r * h + rows_ - 1) / rows_) / h;
    }
    row_theta_[rows_] = kPiD;
}

float ProbeMaxGrid::max_in_cone(const vec3& axis, float half_angle) const {
    if (cells_.empty()) return 0;
    // Wide cones reach most of the sky: not worth a finer answer.
    if (!(half_angle < 0.7f)) return global_max_;
    const int w = probe_->width(), h = probe_->height();
    const vec3 d = probe_->to_probe(axis);
    const double theta = std::atan2(std::hypot(double(d.x), double(d.z)), double(d.y));
    const double phi = std::atan2(double(d.x), -double(d.z));
    const double beta = half_angle, sin_beta = std::sin(beta);
    const double t0 = theta - beta, t1 = theta + beta;
    const bool pole = t0 <= 0 || t1 >= kPiD;
    // Pixel rows the cone can touch, one pixel of margin for rounding, then their cell rows.
    const int j0 = std::clamp(int(std::floor(t0 / kPiD * h)) - 1, 0, h - 1);
    const int j1 = std::clamp(int(std::floor(t1 / kPiD * h)) + 1, 0, h - 1);
    const int r0 = int((long long)j0 * rows_ / h), r1 = int((long long)j1 * rows_ / h);
    float m = 0;
    for (int r = r0; r <= r1; ++r) {
        // The band's smallest sin(theta) within the cone's rows: the widest span in phi.
        const double a = std::clamp(t0, row_theta_[r], row_theta_[r + 1]);
        const double b = std::clamp(t1, row_theta_[r], row_theta_[r + 1]);
        const double s = std::min(std::sin(a), std::sin(b));
        if (pole || s <= sin_beta * 1.0001) {
            m = std::max(m, row_max_[r]);
            continue;
        }
        const double dphi = std::asin(sin_beta / s);
        const double u0 = (phi - dphi) / (2 * kPiD) + 0.5, u1 = (phi + dphi) / (2 * kPiD) + 0.5;
        const long long i0 = (long long)std::floor(u0 * w) - 1, i1 = (long long)std::floor(u1 * w) + 1;
        const int c0 = floor_div(i0 * columns_, w), c1 = floor_div(i1 * columns_, w);
        if (c1 - c0 + 1 >= columns_) {
            m = std::max(m, row_max_[r]);
            continue;
        }
        for (int c = c0; c <= c1; ++c) m = std::max(m, cell(((c % columns_) + columns_) % columns_, r));
    }
    return m;
}

}  // namespace dp
