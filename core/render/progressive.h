#pragma once
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "image/image.h"
#include "render/direct_change.h"
#include "render/frame_plan.h"
#include "assets/pass_renderer.h"
#include "render/photon_tracer.h"
#include "assets/render_scene.h"
#include "render/camera_gather.h"
#include "render/photon_balance.h"
#include "render/tile_accumulator.h"

namespace dp {

/// Errors are estimated on pixel luminances clamped at this multiple of the photo's 99.9th
/// percentile: a display of the photo shows nothing brighter (the benchmarks measure alike).
inline constexpr float kErrorCeilingFactor = 8.0f;

/// The luminance a pixel's error is judged against by adaptive sampling: the photo's `before`
/// plus the mean change, at least `floor` and at most `ceiling`, where the error's two halves are
/// clamped too (TileAccumulator::error2): a rare photon of huge flux that lit a tile must not make
/// its error look small against the brightness it gave it, and stop the tile there.
double judged_value(double before, double change, double floor, double ceiling);

/// Shadow-only matte: the fraction of the photo's light the virtual objects remove,
/// clamp(-lum(dL) / lum(photo), 0, 1), grey RGB; 0 where the photo is black or dL >= 0.
Image shadow_matte(const Image& photo, const Image& dL);

/// Progressive differential photon mapping (Knaus & Zwicker 2011): each pass shoots fresh
/// photons with its own seed and gathers with a shrinking radius; the image is the mean of the
/// pass images, accumulated in double. A pass depends only on (seed, pass index) and on which
/// tiles adaptive sampling has stopped, itself a function of the passes before.
///
/// Under the split estimator (the default) the direct light the objects block at real points
/// is estimated by rays (DirectChange) and photons carry the rest. A pass touches only the
/// tiles its change can reach: tiles with an object, tiles the pass's photons reach, and tiles
/// whose direct-light change Russian roulette picks (FramePlan).
class ProgressiveRenderer final : public PassRenderer {
public:
    ProgressiveRenderer(std::shared_ptr<const RenderScene> scene, const RenderSettings& settings);

    const RenderScene& scene() const { return *scene_; }
    const RenderSettings& settings() const { return settings_; }
    /// Gather radius of pass i (1-based): r_i^2 = r_1^2 prod_{k<i} (k + alpha) / (k + 1).
    float radius_for_pass(int pass) const;

    /// Renders and accumulates the next pass; returns false (accumulating nothing) if
    /// `cancel` became true meanwhile.
    bool render_pass(const std::atomic<bool>* cancel = nullptr) override;
    /// Renders exactly pass `pass` into its own images without accumulating (debugging), as a
    /// fresh render's pass would be (no tile stopped).
    void render_single_pass(int pass, Image& pixel_change, Image& dL, Image& alpha);

    const RenderStats& stats() const override { return stats_; }

    /// Makes the next pass rendered pass `first` (1-based) instead of pass 1: a render shard
    /// that sums passes first.. of a frame. Its accumulator then holds only its own passes.
    /// Passes are independent only without adaptive sampling, so this throws
    /// std::logic_error if adaptive sampling is on or a pass was already rendered.
    void start_at_pass(int first);

    /// Renders only the tiles that meet `window` (a viewer's region of interest), leaving the
    /// rest of the picture as the photo. Call before the first pass.
    void set_window(const PixelWindow& window) { window_ = window; }

    /// Photo plus the mean change: the augmented photograph (linear, may be negative only
    /// where the estimate is; clamp for display).
    Image image() const override;
    /// Mean signed change of radiance on real surfaces seen directly.
    Image dL_layer() const override;
    /// Fraction of samples that saw a virtual object first (grey RGB).
    Image alpha_layer() const override;
    /// From the two interleaved halves of the passes (TileAccumulator::error2); empty before
    /// the second pass. It leaves out the photon estimate's bias, which both halves share
    /// (early on, several times the variance: see blend_by_noise).
    Image variance_layer() const override;
    /// Fraction of pixels the last pass left as the photo, with no ray and no gather.
    double skipped_fraction() const;
    /// Estimates per camera sample on virtual diffuse surfaces (camera_gather.h).
    int camera_diffuse_samples() const { return diffuse_samples_; }
    /// Built with the first pass (empty before it).
    const FramePlan& plan() const { return plan_; }
    const TileAccumulator& accumulator() const { return sums_; }

private:
    /// A photon splatted into a pixel: key = tile * kTile^2 + the pixel's place in the tile.
    struct Splat {
        uint32_t key = 0;
        dvec3 value{0};
    };
    /// One pass's work: the tiles it shades and, per pixel, whether its photons reach it.
    struct PassWork {
        std::vector<uint32_t> tiles;
        std::vector<uint8_t> direct_tile;   ///< per entry of `tiles`: roulette picked its direct light
        std::vector<uint8_t> photon_pixel;  ///< per pixel: some photon cell lies within reach
        std::vector<Splat> splats;          ///< summed per pixel, in key order
        std::vector<uint32_t> splat_begin;  ///< per entry of `tiles`, its first splat (and one past)
    };
    /// Traces pass `pass`'s photons and builds its maps with the pass's radius (timed into
    /// `timing` when given).
    PhotonStats build_pass_maps(int pass, PassMaps& maps, const std::atomic<bool>* cancel,
                                RenderStats* timing = nullptr) const;
    /// Marks the pixels (and tiles) whose camera rays gather the pass's real photons: pixels
    /// within reach of a photon cell, except those the photons are splatted into.
    void mark_photon_pixels(const PassMaps& maps, PassWork& work, std::vector<uint8_t>& photon_tile) const;
    /// Splats the pass's real photons into the pixels whose footprint exceeds the gather disk
    /// (FramePlan::splat_radius): rho/pi times the flux times the pixels per unit area, where
    /// the camera sees the photon's point. Sums in photon order, whatever the threads.
    std::vector<Splat> splat_photons(const PassMaps& maps) const;
    /// Picks the tiles pass `pass` shades: those its change can reach, skipping tiles adaptive
    /// sampling stopped if `respect_stopped`.
    PassWork plan_pass(int pass, const PassMaps& maps, bool respect_stopped) const;
    /// Shades the pass's tiles into `out` (kTile^2 samples per tile, in work.tiles order).
    bool shade_tiles(int pass, const PassMaps& maps, const PassWork& work, std::vector<SampleResult>& out,
                     const std::atomic<bool>* cancel, size_t& shaded, size_t& direct) const;
    /// Whether the objects change pixel i so far: it sees one, or its mean `change` exceeds 1% of
    /// its value `before` (the photo's luminance, floored).
    bool changed_pixel(size_t i, const dvec3& change, double before) const;
    /// Stops converged tiles and refreshes the error estimate.
    void update_convergence();
    /// Adds the pass's samples to the photon balance and, when one is due, sets the next passes'
    /// photon count.
    void balance_photons(const PassWork& work, const std::vector<SampleResult>& samples, uint64_t photon_rays,
                         size_t shaded);
    /// Builds the frame plan and what depends on it, once; false if `cancel` stopped it.
    bool ensure_plan(const std::atomic<bool>* cancel);

    std::shared_ptr<const RenderScene> scene_;
    RenderSettings settings_;
    std::optional<PixelWindow> window_;
    int64_t photons_per_pass_;
    uint64_t seed_;
    float r1_ = 0, alpha_ = 2.0f / 3.0f;
    bool split_ = true;
    bool low_discrepancy_ = true;
    std::optional<DirectChange> direct_;  ///< the direct change by rays (with virtual objects)
    FramePlan plan_;  ///< once per camera and geometry
    bool planned_ = false;
    int diffuse_samples_ = 2;
    TileAccumulator sums_;
    std::optional<PhotonBalance> balance_;  ///< with adaptive sampling and the split estimator
    int first_pass_ = 1;  ///< the index of this renderer's first pass (start_at_pass)
    float ceiling_ = 0;  ///< pixel luminance clamped here when errors are estimated
    RenderStats stats_;
};

}  // namespace dp
