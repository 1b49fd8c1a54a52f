#include "render/tile_accumulator.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dp {

TileAccumulator::TileAccumulator(int width, int height, int tile)
    : width_(width), height_(height), tile_(tile), tiles_x_((width + tile - 1) / tile) {
    const size_t tiles = size_t(tiles_x_) * size_t((height + tile - 1) / tile);
    blocks_.resize(tiles);
    stopped_after_.assign(tiles, 0);
}

uint32_t TileAccumulator::tile_of(size_t pixel) const {
    const int x = int(pixel % size_t(width_)), y = int(pixel / size_t(width_));
    return uint32_t((y / tile_) * tiles_x_ + x / tile_);
}

const TileAccumulator::PixelSums* TileAccumulator::sums(size_t pixel) const {
    const int x = int(pixel % size_t(width_)), y = int(pixel / size_t(width_));
    const auto& block = blocks_[size_t((y / tile_) * tiles_x_ + x / tile_)];
    return block ? &block[size_t(y % tile_) * tile_ + x % tile_] : nullptr;
}

size_t TileAccumulator::add_tile(uint32_t tile, bool odd, const SampleResult* samples) {
    const int x0 = int(tile % uint32_t(tiles_x_)) * tile_, y0 = int(tile / uint32_t(tiles_x_)) * tile_;
    size_t bad = 0;
    std::unique_ptr<PixelSums[]>& block = blocks_[tile];
    for (int ly = 0; ly < tile_; ++ly)
        for (int lx = 0; lx < tile_; ++lx) {
            if (x0 + lx >= width_ || y0 + ly >= height_) continue;
            const SampleResult& r = samples[ly * tile_ + lx];
            if (!is_finite(r.pixel_change) || !is_finite(r.dL) || !std::isfinite(r.alpha)) {
                ++bad;
                continue;
            }
            if (r.pixel_change == vec3(0) && r.dL == vec3(0) && r.alpha == 0) continue;
            if (!block) {
                block = std::make_unique<PixelSums[]>(size_t(tile_) * tile_);
                ++touched_;
            }
            PixelSums& s = block[size_t(ly) * tile_ + lx];
            s.pixel_change += dvec3(r.pixel_change);
            s.dL += dvec3(r.dL);
            s.alpha += r.alpha;
            if (odd) s.odd_luminance += luminance(dvec3(r.pixel_change));
        }
    return bad;
}

dvec3 TileAccumulator::mean_pixel_change(size_t pixel) const {
    const PixelSums* s = sums(pixel);
    return s ? s->pixel_change / double(tile_passes(tile_of(pixel))) : dvec3(0);
}

dvec3 TileAccumulator::mean_dL(size_t pixel) const {
    const PixelSums* s = sums(pixel);
    return s ? s->dL / double(tile_passes(tile_of(pixel))) : dvec3(0);
}

double TileAccumulator::mean_alpha(size_t pixel) const {
    const PixelSums* s = sums(pixel);
    return s ? s->alpha / double(tile_passes(tile_of(pixel))) : 0.0;
}

bool TileAccumulator::untouched(size_t pixel) const {
    const PixelSums* s = sums(pixel);
    return !s || s->pixel_change == dvec3(0);
}

double TileAccumulator::error2(size_t pixel, double base, double ceiling) const {
    const int n = tile_passes(tile_of(pixel)), n_odd = (n + 1) / 2, n_even = n / 2;
    if (n_even == 0) return std::numeric_limits<double>::infinity();
    const PixelSums* s = sums(pixel);
    if (!s) return 0;
    const double total = luminance(s->pixel_change);
    const double odd = std::clamp(base + s->odd_luminance / n_odd, 0.0, ceiling);
    const double even = std::clamp(base + (total - s->odd_luminance) / n_even, 0.0, ceiling);
    const double diff = odd - even;
    // Var(half difference) = v (1/n_odd + 1/n_even) for a per-pass variance v; the mean's is v / n.
    return diff * diff / (double(n) * (1.0 / n_odd + 1.0 / n_even));
}

}  // namespace dp
