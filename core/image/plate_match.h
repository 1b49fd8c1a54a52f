#pragma once
// Matching what a render adds to the photograph's own grain and softness: a clean, sharp
// object on a grainy, slightly soft plate looks pasted on (docs/plate-match.md).
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"

namespace dp {

/// A photo's grain: its standard deviation per channel as a function of brightness, how it is
/// correlated between neighbouring pixels and between channels.
struct GrainProfile {
    std::vector<float> levels;  ///< luminance (linear) of each brightness bin, ascending
    std::vector<vec3> sigma;    ///< the grain's standard deviation per channel at each level
    /// The grain's spatial correlation as the width (pixels) of the Gaussian that, applied to
    /// white noise, gives its correlation with the next pixel (0: white).
    float correlation_px = 0;
    /// Correlation between the channels' grain (symmetric, unit diagonal): sensor noise after
    /// demosaicing and JPEG is mostly shared (luminance) grain.
    glm::mat3 channel_correlation{1.0f};
    size_t patches = 0;  ///< flat 8x8 patches the figures come from
    bool empty() const { return levels.empty(); }
    /// The grain's standard deviation per channel at luminance `level` (interpolated on the
    /// logarithm of the levels, held at the ends).
    vec3 sigma_at(float level) const;
};

/// Measures `photo`'s grain from its flattest 8x8 patches in each brightness band: a plane is
/// fitted to each patch and its residual taken as grain; within a band the patches at the 25th
/// percentile of residual variance stand for the grain (texture only adds to it), corrected
/// for that percentile's place in the chi-square spread of pure noise. Pixels at or above
/// `clip_level` (per channel) are left out; a negative `clip_level` finds it: the photo's
/// largest value where at least 0.1% of its pixels reach it (a clipped ceiling), else none.
/// Empty where fewer than 16 flat patches are found.
GrainProfile measure_grain(const Image& photo, float clip_level = -1);

/// The photo's softness: the width (pixels) of the Gaussian blur by which its edges are softer
/// than a sharp edge rendered with a one-pixel box filter (what the renderer's jittered samples
/// give), from the ratio of gradients before and after a known re-blur at its strongest edges
/// (Zhuo and Sim 2011). 0 for a plate as sharp as a render; -1 when it has too few edges.
float measure_softness(const Image& photo);

/// The grain for a render of `width` x `height`: zero-mean, unit-variance noise per channel,
/// correlated as `profile` says, the same for the same seed. Multiply by sigma_at() per pixel.
Image grain_field(const GrainProfile& profile, int width, int height, uint64_t seed);

/// Separable Gaussian blur of `image` by `sigma` pixels (clamped at the borders); a copy for
/// sigma <= 0.
Image gaussian_blur(const Image& image, float sigma);

/// What plate matching adds to a composite, layer by layer (all the render's size).
struct PlateMatch {
    Image beauty;  ///< the matched composite
    Image grain;   ///< the grain added (a compositor's layer: add it over the blurred objects)
};

/// The composite `augmented` (= alpha objects + (1 - alpha) photo + dL) with what the render
/// adds blurred by `blur_px` and the objects given the plate's grain: objects, alpha and dL are
/// blurred alike, and the grain is added in proportion to the blurred alpha at the objects'
/// brightness. Where nothing changes within a few blur widths the photo is untouched. `dL` is
/// read only where alpha > 0: elsewhere the change is augmented - photo, so a denoised composite
/// keeps its denoised change.
PlateMatch match_plate(const Image& augmented, const Image& photo, const Image& alpha, const Image& dL,
                       const GrainProfile& grain, float blur_px, uint64_t seed = 1);

/// What a photo's plate match needs, measured once per photo.
struct PlateFigures {
    GrainProfile grain;
    float softness_px = -1;  ///< measure_softness (-1: too few edges; nothing is blurred)
    /// One line for people: the grain at mid brightness, its correlation, the softness.
    std::string summary() const;
};
PlateFigures measure_plate(const Image& photo);

/// match_plate with `figures`' grain and softness.
PlateMatch match_plate(const Image& augmented, const Image& photo, const Image& alpha, const Image& dL,
                       const PlateFigures& figures, uint64_t seed = 1);

/// The noise power spectrum of a patch, radially averaged into `bands` bands of spatial
/// frequency (0 to the Nyquist frequency), after removing a fitted plane: the figure by which
/// grain is compared (luminance).
std::vector<double> noise_power_bands(const Image& image, int x0, int y0, int size, int bands = 4);

}  // namespace dp
