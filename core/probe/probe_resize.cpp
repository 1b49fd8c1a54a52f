#include "probe/probe_resize.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace dp {

namespace {

/// One source interval's share of an output interval.
struct Overlap {
    int source = 0;
    double weight = 0;
};

/// For each of `out` output intervals over [0, 1), the source intervals (of `in` over [0, 1))
/// that overlap it, weighted by `measure(a, b)` of the overlap [a, b] (in source units).
/// Overlap bounds are the source's and the output's own edges, so the weights of one output
/// interval add up to its measure except for rounding.
template <class Measure>
std::vector<std::vector<Overlap>> overlaps(int in, int out, Measure measure) {
    std::vector<std::vector<Overlap>> result(static_cast<size_t>(out));
    const double scale = double(in) / double(out);
    for (int o = 0; o < out; ++o) {
        const double a = o * scale, b = o + 1 == out ? double(in) : (o + 1) * scale;
        const int first = std::clamp(int(std::floor(a)), 0, in - 1);
        const int last = std::clamp(int(std::ceil(b)) - 1, first, in - 1);
        for (int s = first; s <= last; ++s) {
            const double lo = std::max(a, double(s)), hi = std::min(b, double(s + 1));
            if (hi > lo) result[size_t(o)].push_back({s, measure(lo, hi)});
        }
    }
    return result;
}

}  // namespace

Image shrink_latlong(const Image& src, int width, int height) {
    if (src.empty()) throw std::invalid_argument("shrink_latlong: empty probe");
    if (width <= 0 || height <= 0) throw std::invalid_argument("shrink_latlong: non-positive size");
    const int sw = src.width(), sh = src.height();
    // Along a row every source pixel spans the same angle: the weight is the length covered.
    const auto columns = overlaps(sw, width, [](double a, double b) { return b - a; });
    // Across rows the weight is the band's area, cos(theta_a) - cos(theta_b) with
    // theta = pi * v: rows near the poles hold less of the sphere than rows at the horizon.
    const double to_theta = std::numbers::pi / double(sh);
    const auto rows = overlaps(sh, height, [&](double a, double b) {
        // 2 sin((a + b) / 2) sin((b - a) / 2) rather than the difference of cosines: no
        // cancellation for the thin bands near the poles.
        return 2 * std::sin(0.5 * (a + b) * to_theta) * std::sin(0.5 * (b - a) * to_theta);
    });

    Image out(width, height);
    std::vector<dvec3> row_sum(static_cast<size_t>(width));
    for (int y = 0; y < height; ++y) {
        std::fill(row_sum.begin(), row_sum.end(), dvec3(0));
        double band = 0;
        for (const Overlap& r : rows[size_t(y)]) {
            band += r.weight;
            const vec3* line = &src[size_t(r.source) * size_t(sw)];
            for (int x = 0; x < width; ++x) {
                dvec3 sum(0);
                for (const Overlap& c : columns[size_t(x)]) sum += dvec3(line[c.source]) * c.weight;
                row_sum[size_t(x)] += sum * r.weight;
            }
        }
        for (int x = 0; x < width; ++x) {
            double span = 0;
            for (const Overlap& c : columns[size_t(x)]) span += c.weight;
            // Power over the output pixel's solid angle: the weighted mean of the radiance.
            const double area = band * span;
            out.at(x, y) = area > 0 ? vec3(row_sum[size_t(x)] / area) : vec3(0);
        }
    }
    return out;
}

void shrunk_latlong_size(int width, int height, int max_width, int& out_width, int& out_height) {
    if (width <= max_width || max_width <= 0) {
        out_width = width;
        out_height = height;
        return;
    }
    out_width = max_width;
    out_height = std::max(1, int(std::lround(double(height) * max_width / width)));
}

int automatic_probe_max_width(uint64_t memory_bytes, double bytes_per_pixel) {
    constexpr int kWidest = 8192, kNarrowest = 1024;
    int width = kWidest;
    auto bytes = [&](int w) { return double(w) * double(w / 2) * bytes_per_pixel; };
    while (memory_bytes > 0 && width > kNarrowest && bytes(width) > 0.25 * double(memory_bytes)) width /= 2;
    return width;
}

}  // namespace dp
