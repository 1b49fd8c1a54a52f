#pragma once
#include <atomic>
#include <functional>
#include <memory>

#include "image/image.h"
#include "assets/render_scene.h"

namespace dp {

/// Figures about the passes done so far.
struct RenderStats {
    int passes = 0;
    double seconds = 0;            ///< wall time of completed passes
    uint64_t photons_emitted = 0;
    uint64_t photons_stored = 0;
    uint64_t rays = 0;             ///< photon rays (Embree queries)
    double photons_per_second = 0;
    size_t pixels_gathered = 0;    ///< pixels the last pass shaded
    size_t direct_estimates = 0;   ///< real pixels whose direct-light change the last pass estimated
    size_t pixels_total = 0;
    float radius = 0;              ///< gather radius of the last pass
    size_t non_finite_samples = 0; ///< samples discarded because they were NaN/Inf
    uint64_t samples_per_pixel = 0;///< camera samples per pixel so far (path-traced methods)
    /// Estimated relative RMSE of the image so far over the pixels the objects change, from
    /// the difference of the two interleaved halves of the passes; negative while unknown.
    double estimated_rel_error = -1;
    /// Mean luminance of the pixels the objects change (what estimated_rel_error is relative
    /// to), 0 while unknown: a viewer judges from it whether the noise is still visible.
    double mean_changed_value = 0;
    size_t tiles_total = 0, tiles_shaded = 0;  ///< tiles, and those the last pass shaded
    size_t tiles_stopped = 0;                  ///< tiles adaptive sampling found converged
    /// Where the last pass's time went (seconds): photons, maps, marking the pixels the photons
    /// reach, shading the tiles, adding them up.
    double trace_s = 0, maps_s = 0, mark_s = 0, shade_s = 0, accumulate_s = 0;
    int64_t photons_per_pass = 0;  ///< photons the last pass traced
    /// The photons' share of the per-pass variance over the changed pixels, as last measured
    /// when balancing photons (PhotonBalance); negative while unknown.
    double photon_variance_share = -1;
};

/// A progressive renderer driven one pass at a time: the differential photon mapper, or the
/// standard two-simulation method it is measured against. The session and the benchmark
/// harness use this interface, so either method runs through the same code.
class PassRenderer {
public:
    virtual ~PassRenderer() = default;
    /// Renders and accumulates the next pass; returns false (accumulating nothing) if
    /// `cancel` became true meanwhile.
    virtual bool render_pass(const std::atomic<bool>* cancel = nullptr) = 0;
    virtual const RenderStats& stats() const = 0;
    int passes() const { return stats().passes; }
    /// The augmented photograph (linear).
    virtual Image image() const = 0;
    /// Mean signed change of radiance on real surfaces seen directly.
    virtual Image dL_layer() const = 0;
    /// Fraction of samples that saw a virtual object first (grey RGB).
    virtual Image alpha_layer() const = 0;
    /// The squared error estimate of each pixel's mean luminance (grey RGB; infinite where it
    /// is not known yet), for blend_by_noise; empty where the method keeps none.
    virtual Image variance_layer() const { return {}; }
};

/// Makes the renderer a session runs on a scene with its settings.
using RendererFactory =
    std::function<std::unique_ptr<PassRenderer>(std::shared_ptr<const RenderScene>, const RenderSettings&)>;

}  // namespace dp
