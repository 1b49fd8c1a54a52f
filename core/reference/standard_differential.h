#pragma once
#include <memory>
#include <vector>

#include "reference/path_tracer.h"
#include "assets/pass_renderer.h"

namespace dp {

/// Standard differential rendering (Debevec 1998; the paper's Fig. 1), the baseline the
/// differential photon mapper is measured against: two full path-traced simulations of the
/// whole scene, L_old (real proxies only) and L_new (with the virtual objects), composited per
/// camera sample as photo + (L_new - L_old) where the sample sees real geometry or the probe,
/// and L_new where it sees a virtual object or a virtual light's face. Each pass adds `samples_per_pass` samples per
/// pixel; the image depends only on the seed, not on threads.
///
/// Two variants: `Independent`, the paper's two separate renders (each simulation has its own
/// camera jitter and random numbers), and `Correlated`, which gives both simulations of a camera
/// sample the same ray and random numbers, so their difference is exactly zero wherever no path
/// meets a virtual object: a stronger baseline than the paper measured against.
class StandardDifferentialRenderer final : public PassRenderer {
public:
    enum class Sampling { Independent, Correlated };
    /// Path depth and seed come from `settings`.
    StandardDifferentialRenderer(std::shared_ptr<const RenderScene> scene, const RenderSettings& settings,
                                 Sampling sampling, int samples_per_pass = 1);

    /// After `passes` passes, later passes sample only the pixels the objects change (some
    /// sample saw an object, or the mean changed by more than 0.6% of the photo), grown by two
    /// pixels: a truth spends its samples where the change is. 0 (the default) never focuses.
    void focus_after(int passes) { focus_after_ = passes; }

    bool render_pass(const std::atomic<bool>* cancel = nullptr) override;
    const RenderStats& stats() const override { return stats_; }
    Image image() const override;
    Image dL_layer() const override;
    Image alpha_layer() const override;

private:
    std::shared_ptr<const RenderScene> scene_;
    Sampling sampling_;
    int samples_per_pass_;
    ReferenceOptions with_virtual_, real_only_;
    // Per-pixel sums over samples, in double: L_new - L_old on real samples, L_new on virtual.
    std::vector<dvec3> sum_delta_, sum_virtual_;
    std::vector<uint32_t> virtual_count_;
    std::vector<uint32_t> samples_;  ///< per pixel
    std::vector<uint32_t> focus_;    ///< pixels later passes sample, in order (empty: all)
    int focus_after_ = 0;
    RenderStats stats_;

    void build_focus();
};

}  // namespace dp
