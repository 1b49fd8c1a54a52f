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

TileAccumulator::PixelSums* TileAccumulator::touch(uint32_t tile) {
    std::unique_ptr<PixelSums[]>& block = blocks_[tile];
    if (!block) block = std::make_unique<PixelSums[]>(size_t(tile_) * tile_);
    return block.get();
}

size_t TileAccumulator::tiles_touched() const {
    return size_t(std::count_if(blocks_.begin(), blocks_.end(), [](const auto& b) { return bool(b); }));
}

size_t TileAccumulator::add_tile(uint32_t tile, bool odd, const SampleResult* samples) {
    const int x0 = int(tile % uint32_t(tiles_x_)) * tile_, y0 = int(tile / uint32_t(tiles_x_)) * tile_;
    size_t bad = 0;
    PixelSums* block = blocks_[tile].get();
    for (int ly = 0; ly < tile_; ++ly)
        for (int lx = 0; lx < tile_; ++lx) {
            if (x0 + lx >= width_ || y0 + ly >= height_) continue;
            const SampleResult& r = samples[ly * tile_ + lx];
            if (!is_finite(r.pixel_change) || !is_finite(r.dL) || !std::isfinite(r.alpha)) {
                ++bad;
                continue;
            }
            if (r.pixel_change == vec3(0) && r.dL == vec3(0) && r.alpha == 0) continue;
            if (!block) block = touch(tile);
            PixelSums& s = block[size_t(ly) * tile_ + lx];
            for (int c = 0; c < 3; ++c) {
                s.pixel_change[c].add(r.pixel_change[c]);
                s.dL[c].add(r.dL[c]);
            }
            s.alpha.add(r.alpha);
            if (odd) s.odd_luminance.add(luminance(dvec3(r.pixel_change)));
        }
    return bad;
}

void TileAccumulator::merge(const TileAccumulator& other) {
    for (uint32_t t = 0; t < other.tiles(); ++t) {
        const PixelSums* from = other.tile_sums(t);
        if (!from) continue;
        PixelSums* to = touch(t);
        for (size_t k = 0; k < size_t(tile_) * tile_; ++k) {
            for (int c = 0; c < 3; ++c) {
                to[k].pixel_change[c].add(from[k].pixel_change[c]);
                to[k].dL[c].add(from[k].dL[c]);
            }
            to[k].alpha.add(from[k].alpha);
            to[k].odd_luminance.add(from[k].odd_luminance);
        }
    }
    passes_ += other.passes_;
}

bool TileAccumulator::none_stopped() const {
    return std::all_of(stopped_after_.begin(), stopped_after_.end(), [](int s) { return s == 0; });
}

namespace {
dvec3 value3(const FixedSum (&sums)[3]) { return dvec3(sums[0].value(), sums[1].value(), sums[2].value()); }
}  // namespace

dvec3 TileAccumulator::mean_pixel_change(size_t pixel) const {
    const PixelSums* s = sums(pixel);
    return s ? value3(s->pixel_change) / double(tile_passes(tile_of(pixel))) : dvec3(0);
}

dvec3 TileAccumulator::mean_dL(size_t pixel) const {
    const PixelSums* s = sums(pixel);
    return s ? value3(s->dL) / double(tile_passes(tile_of(pixel))) : dvec3(0);
}

double TileAccumulator::mean_alpha(size_t pixel) const {
    const PixelSums* s = sums(pixel);
    return s ? s->alpha.value() / double(tile_passes(tile_of(pixel))) : 0.0;
}

bool TileAccumulator::untouched(size_t pixel) const {
    const PixelSums* s = sums(pixel);
    return !s || (s->pixel_change[0].zero() && s->pixel_change[1].zero() && s->pixel_change[2].zero());
}

double TileAccumulator::error2(size_t pixel, double base, double ceiling) const {
    const int n = tile_passes(tile_of(pixel)), n_odd = (n + 1) / 2, n_even = n / 2;
    if (n_even == 0) return std::numeric_limits<double>::infinity();
    const PixelSums* s = sums(pixel);
    if (!s) return 0;
    const double total = luminance(value3(s->pixel_change));
    const double odd_sum = s->odd_luminance.value();
    const double odd = std::clamp(base + odd_sum / n_odd, 0.0, ceiling);
    const double even = std::clamp(base + (total - odd_sum) / n_even, 0.0, ceiling);
    const double diff = odd - even;
    // Var(half difference) = v (1/n_odd + 1/n_even) for a per-pass variance v; the mean's is v / n.
    return diff * diff / (double(n) * (1.0 / n_odd + 1.0 / n_even));
}

namespace {
/// Calls f(pixel index) for the image pixels of the touched tiles.
template <class F>
void for_touched_pixels(const TileAccumulator& sums, F&& f) {
    const int tile = sums.tile_size();
    for (uint32_t t = 0; t < sums.tiles(); ++t) {
        if (!sums.touched(t)) continue;
        const int x0 = int(t % uint32_t(sums.tiles_x())) * tile, y0 = int(t / uint32_t(sums.tiles_x())) * tile;
        const int x1 = std::min(x0 + tile, sums.width()), y1 = std::min(y0 + tile, sums.height());
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) f(size_t(y) * size_t(sums.width()) + size_t(x));
    }
}
}  // namespace

Image accumulated_image(const Image& photo, const TileAccumulator& sums) {
    Image out = photo;
    for_touched_pixels(sums, [&](size_t i) {
        if (sums.untouched(i)) return;  // untouched pixels stay bit-exact
        const vec3 v = out[i] + vec3(sums.mean_pixel_change(i));
        if (is_finite(v)) out[i] = v;
    });
    return out;
}

Image accumulated_dL(const TileAccumulator& sums) {
    Image out(sums.width(), sums.height());
    for_touched_pixels(sums, [&](size_t i) { out[i] = vec3(sums.mean_dL(i)); });
    return out;
}

Image accumulated_alpha(const TileAccumulator& sums) {
    Image out(sums.width(), sums.height());
    for_touched_pixels(sums, [&](size_t i) { out[i] = vec3(float(sums.mean_alpha(i))); });
    return out;
}

}  // namespace dp
