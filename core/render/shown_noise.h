#pragma once
// The noise of a picture as a viewer shows it (denoised or raw), from the pictures of one
// refinement at different pass counts.
#include <cstdint>
#include <memory>
#include <vector>

#include "image/image.h"

namespace dp {

/// Estimates the relative error of the pictures a refinement shows, over the pixels the objects
/// change, by comparing each with an earlier one of the same state: for pictures after k and
/// m > k passes of independent passes, the difference D_m - D_k has the variance of D_m times
/// (m - k) / k, so RMS(D_m - D_k) sqrt(k / (m - k)) estimates D_m's error. It needs no second
/// render and holds for whatever the viewer applies to each picture (a denoiser) as long as it
/// is applied alike: it judges what is seen, where the renderer's odd/even estimate judges the
/// raw sums. It sees noise, not bias: what a filter blurs away is in both pictures alike. The
/// estimate is the RMS over changed pixels divided by their mean value, as
/// RenderStats::estimated_rel_error.
class ShownNoise {
public:
    /// The picture shown after `passes` passes of request `generation` (same size as `photo`,
    /// `alpha` and `raw`: the render's photo, coverage and raw augmented image). Returns the estimated relative
    /// error of `shown`, or -1 while no earlier picture of the state has at most 3/4 of its
    /// passes.
    double add(uint64_t generation, int passes, std::shared_ptr<const Image> shown, const Image& photo,
               const Image& alpha, const Image& raw);
    /// Forgets the pictures kept (another project).
    void clear() { kept_.clear(); }

    /// Pictures kept for later comparisons, at most.
    static constexpr size_t kKept = 6;

private:
    struct Kept {
        int passes;
        std::shared_ptr<const Image> image;
    };
    uint64_t generation_ = 0;
    std::vector<Kept> kept_;  ///< by passes, increasing
};

/// The estimate for one pair: `later` after m passes, `earlier` after k < m passes of the same
/// refinement (see ShownNoise). The pixels judged are those the raw render changes
/// (changed_pixels: alpha > 0, or more than 1 % of the photo's value, floored at value_floor);
/// luminances are clamped at `ceiling` first (the sun in a mirror is not noise), and the largest
/// thousandth of the squared differences is left out (a firefly). -1 if no pixel changes or the
/// sizes differ.
double shown_rel_error(const Image& later, int m, const Image& earlier, int k, const Image& photo, const Image& alpha,
                       const Image& raw, float ceiling);

}  // namespace dp
