#pragma once
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "image/image.h"
#include "render/pass_renderer.h"
#include "render/pass_accumulator.h"
#include "render/photon_tracer.h"
#include "render/pixel_cache.h"
#include "render/render_scene.h"
#include "render/shading.h"

namespace dp {

/// Shadow-only matte: the fraction of the photo's light the virtual objects remove,
/// clamp(-lum(dL) / lum(photo), 0, 1), grey RGB; 0 where the photo is black or dL >= 0.
Image shadow_matte(const Image& photo, const Image& dL);

/// Sub-pixel offset in [-0.5, 0.5)^2 of pixel `pixel`'s camera sample in pass `pass`: point
/// `pass` of the pixel's shifted R2 sequence, so the passes cover each pixel evenly.
vec2 camera_jitter(uint64_t seed, int pass, size_t pixel);

/// Progressive differential photon mapping (Knaus & Zwicker 2011): each pass shoots fresh
/// photons with its own seed and gathers with a shrinking radius; the image is the mean of the
/// pass images, accumulated in double. A pass depends only on (seed, pass index).
class ProgressiveRenderer final : public PassRenderer {
public:
    ProgressiveRenderer(std::shared_ptr<const RenderScene> scene, int64_t photons_per_pass, uint64_t seed);

    const RenderScene& scene() const { return *scene_; }
    /// Gather radius of pass i (1-based): r_i^2 = r_1^2 prod_{k<i} (k + alpha) / (k + 1).
    float radius_for_pass(int pass) const;
    float initial_radius() const { return r1_; }

    /// Renders and accumulates the next pass; returns false (accumulating nothing) if
    /// `cancel` became true meanwhile.
    bool render_pass(const std::atomic<bool>* cancel = nullptr) override;
    /// Renders exactly pass `pass` into its own images without accumulating (debugging).
    void render_single_pass(int pass, Image& delta, Image& dL, Image& alpha);

    const RenderStats& stats() const override { return stats_; }

    /// Photo plus the mean change: the augmented photograph (linear, may be negative only
    /// where the estimate is; clamp for display).
    Image image() const override;
    /// Mean signed change of radiance on real surfaces seen directly.
    Image delta_layer() const override;
    /// Fraction of samples that saw a virtual object first (grey RGB).
    Image alpha_layer() const override;
    /// Fraction of pixels the last pass left as the photo, with no ray and no gather.
    double skipped_fraction() const;
    /// Estimates per camera sample on virtual diffuse surfaces (shading.h).
    int camera_diffuse_samples() const { return diffuse_samples_; }

private:
    /// Traces pass `pass`'s photons and builds its maps with the pass's radius.
    PhotonStats build_pass_maps(int pass, PassMaps& maps, const std::atomic<bool>* cancel) const;
    void shade_pass(int pass, const PassMaps& maps, std::vector<SampleResult>& out,
                    const std::atomic<bool>* cancel, size_t& gathered);

    std::shared_ptr<const RenderScene> scene_;
    int64_t photons_per_pass_;
    uint64_t seed_;
    float r1_ = 0, alpha_ = 2.0f / 3.0f;
    PixelCache cache_;  ///< what the centre rays see, once per camera and geometry
    int diffuse_samples_ = 2;
    PassAccumulator sums_;
    std::vector<SampleResult> samples_;  ///< the current pass's samples, reused
    RenderStats stats_;
};

}  // namespace dp
