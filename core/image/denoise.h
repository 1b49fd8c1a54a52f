#pragma once
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include "image/image.h"

namespace dp {

/// Intel Open Image Denoise (2.x, CPU device) applied to the change a render makes to the photo,
/// never to the photo itself. The library is loaded at run time (dlopen), from the first of:
/// $DP_OIDN_LIBRARY (only that file when set), `.deps/oidn/lib/libOpenImageDenoise.so.2` in the
/// executable's folder or one above it, the same in the source tree, the default loader path.

/// Thrown when the library cannot be loaded; the message says how to get it.
class DenoiserUnavailable : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// True when the library loads and a CPU device can be made. Otherwise false, and `why` (if not
/// null) tells what failed and how to get the library (scripts/install-deps.sh, or
/// DP_OIDN_LIBRARY=/path/libOpenImageDenoise.so.2).
bool denoiser_available(std::string* why = nullptr);

/// Denoises a signed HDR change (negative shadows, positive caustics and reflections) with the
/// RT filter. `albedo` and `normal` are noise-free per-pixel guides of the same size (or both
/// empty for none); see denoise_aovs in render/denoise_aovs.h. Pixels farther than
/// kDenoiseSupport pixels from any non-zero pixel of `change` come back exactly 0, so photo plus
/// the result leaves them bit-exact. A pixel with a channel beyond +-`ceiling` (the sun seen in
/// a mirror) is not noise: it keeps its raw value, and the filter sees it clamped so that its
/// energy does not spread. Every value returned is finite. Throws DenoiserUnavailable, or
/// std::invalid_argument for mismatched sizes, std::runtime_error when the library fails.
/// How hard the filter works. Final: the library's best network; the real surfaces' change
/// (its signed parts apart) and the objects' radiance in separate runs. Interactive: its fast
/// network, and in denoise_augmented one run for both, the change demodulated by the photo and
/// the objects scaled to the change around them: about a sixth of Final's time, a few percent
/// more error. Filters are kept between calls for the same box size (boxes grow in steps of 32
/// pixels), so a viewer's next denoise skips the library's planning.
enum class DenoiseQuality { Final, Interactive };

/// The share of a render's time its denoise may take.
inline constexpr double kDenoiseShare = 0.1;

/// Final where its predicted cost for an image of `pixels` (from the filter runs measured so far
/// in this process, or two-core figures before the first) is at most kDenoiseShare of
/// `render_seconds`, else Interactive: a short render is not held up by its filter.
DenoiseQuality denoise_quality_for(double render_seconds, size_t pixels);

/// `cancel` becoming true stops the filter (std::runtime_error).
Image denoise_change(const Image& change, const Image& albedo = {}, const Image& normal = {},
                     float ceiling = INFINITY, DenoiseQuality quality = DenoiseQuality::Final,
                     const std::atomic<bool>* cancel = nullptr);

/// The augmented photograph with the noise of the render's change removed. `alpha` is the
/// render's virtual coverage (red channel; empty: none) and `dL` its change on real surfaces
/// seen directly (the mean over all of a pixel's samples, 0 for those that saw an object; empty:
/// augmented - photo where alpha is 0). The real surfaces' change and the objects' own radiance
/// are filtered apart, each with the guides, so neither spreads into the other (a bright object
/// does not light the shadow beside it) and the photo behind an object is never smeared. A
/// pixel's object share is filtered where the object covers at least a quarter of it (with `dL`
/// for partly covered pixels); a partly covered pixel's real share is filtered with `dL` only
/// (at Interactive quality only where its object share is not).
/// Pixels where alpha is 0 and the denoised change is 0 keep the photo's bits. The ceiling is
/// denoise_ceiling(photo). Same sizes required; throws as denoise_change.
Image denoise_augmented(const Image& photo, const Image& augmented, const Image& alpha, const Image& dL,
                        const Image& albedo = {}, const Image& normal = {},
                        DenoiseQuality quality = DenoiseQuality::Final,
                        const std::atomic<bool>* cancel = nullptr);

/// kDenoiseCeilingFactor times the photo's 99.9% luminance quantile: the brightness above which
/// a pixel is a highlight to keep (the same level the benchmarks clamp errors at).
float denoise_ceiling(const Image& photo);
inline constexpr float kDenoiseCeilingFactor = 8.0f;

/// How far (pixels) the denoised change may reach beyond the pixels the raw change touches:
/// enough to fill the holes of a noisy estimate, not enough to move the photo far away.
inline constexpr int kDenoiseSupport = 8;

}  // namespace dp
