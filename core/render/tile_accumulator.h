#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "base/fixed_sum.h"
#include "base/math.h"
#include "image/image.h"
#include "render/camera_gather.h"

namespace dp {

/// Per-pixel sums of the pass samples, exact and order-independent in 128-bit fixed point
/// (FixedSum: shadow and caustic photons nearly cancel, a long render adds thousands of passes,
/// and passes summed in separate processes must merge to the same bits), kept per tile and allocated when a tile is first
/// touched: a pass that changes a few pixels costs a few tiles, not the frame. Every live tile
/// counts every pass (an untouched pixel's sample is zero); a tile stopped by adaptive sampling
/// keeps the count it had. The odd passes' luminance is summed apart, so that the difference
/// of the two interleaved halves estimates each pixel's error.
class TileAccumulator {
public:
    TileAccumulator() = default;
    TileAccumulator(int width, int height, int tile);

    /// Adds one tile's samples of the current pass (tile-local row-major order, tile x tile
    /// entries; those outside the image are ignored). `odd`: the pass's index is odd. A sample
    /// with a NaN/Inf channel is dropped whole; returns how many were.
    size_t add_tile(uint32_t tile, bool odd, const SampleResult* samples);
    /// Counts one more pass for every live tile.
    void finish_pass() { ++passes_; }
    /// Stops counting passes for a tile (adaptive sampling found it converged).
    void stop(uint32_t tile) { stopped_after_[tile] = passes_; }
    bool live(uint32_t tile) const { return stopped_after_[tile] == 0; }
    bool touched(uint32_t tile) const { return bool(blocks_[tile]); }

    int passes() const { return passes_; }
    int tile_passes(uint32_t tile) const { return stopped_after_[tile] ? stopped_after_[tile] : passes_; }
    size_t tiles() const { return blocks_.size(); }
    /// Tiles holding sums (counted, not kept: add_tile runs on many tiles at once).
    size_t tiles_touched() const;
    int width() const { return width_; }
    int height() const { return height_; }
    int tile_size() const { return tile_; }
    int tiles_x() const { return tiles_x_; }
    uint32_t tile_of(size_t pixel) const;

    /// Adds another accumulator's sums and passes (render shards of one frame: same size, no
    /// tile stopped in either). The result is bit for bit the accumulator of both pass sets.
    void merge(const TileAccumulator& other);
    /// Sets the number of passes summed (reading a saved accumulator).
    void set_passes(int passes) { passes_ = passes; }
    /// True when adaptive sampling stopped no tile.
    bool none_stopped() const;

    /// Means over the passes of the pixel's tile (zero before the first pass or if untouched).
    dvec3 mean_pixel_change(size_t pixel) const;
    dvec3 mean_dL(size_t pixel) const;
    double mean_alpha(size_t pixel) const;
    /// True while no pass has changed the pixel: it keeps the photo bit for bit.
    bool untouched(size_t pixel) const;
    /// Squared error estimate of the pixel's mean luminance from the two interleaved halves,
    /// each half's luminance (the photo's `base` plus its mean change) clamped to [0, ceiling]
    /// first, so that a sun seen in a mirror does not stand for the whole image's noise;
    /// infinite before both halves hold a pass.
    double error2(size_t pixel, double base = 0, double ceiling = INFINITY) const;

    /// One pixel's sums, per channel.
    struct PixelSums {
        FixedSum pixel_change[3], dL[3];
        FixedSum alpha;
        FixedSum odd_luminance;  ///< luminance of pixel_change summed over odd passes
    };
    /// A touched tile's sums (tile x tile entries, row-major), null if untouched.
    const PixelSums* tile_sums(uint32_t tile) const { return blocks_[tile].get(); }
    /// The tile's sums, allocated (zero) if it was untouched.
    PixelSums* touch(uint32_t tile);

private:
    const PixelSums* sums(size_t pixel) const;

    int width_ = 0, height_ = 0, tile_ = 8, tiles_x_ = 0;
    std::vector<std::unique_ptr<PixelSums[]>> blocks_;
    std::vector<int> stopped_after_;  ///< 0 while live
    int passes_ = 0;
};

/// The photo plus each touched pixel's mean change (untouched pixels keep the photo's bits, as
/// do pixels whose mean is not finite): the augmented photograph.
Image accumulated_image(const Image& photo, const TileAccumulator& sums);
/// The mean signed change of radiance of each pixel.
Image accumulated_dL(const TileAccumulator& sums);
/// The mean coverage of each pixel by virtual objects (grey RGB).
Image accumulated_alpha(const TileAccumulator& sums);

}  // namespace dp
