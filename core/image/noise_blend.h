#pragma once
#include "image/image.h"

namespace dp {

/// A denoised picture never worse than the raw one it came from: each pixel takes
/// raw + w (denoised - raw), with w = V / (V + b^2) from the raw's noise V (the mean of
/// `variance`, the squared error of each pixel's mean luminance) and the denoiser's bias b^2
/// (the mean squared luminance difference of denoised and raw beyond that noise and twice the
/// scatter of its own estimate), both over
/// the (2 kNoiseBlendRadius + 1)^2 box around the pixel. Where the raw is noisy and the filter
/// agrees with it within that noise, w is 1; where the raw has converged and the filter still
/// moves it (detail blurred, a shadow's mean pulled), w falls to 0. An empty `variance` (no
/// estimate yet, as after one pass) returns `denoised`; so does a relative noise above
/// kFilterTrusted. Same sizes required.
Image blend_by_noise(const Image& raw, const Image& denoised, const Image& variance);

/// Relative noise (the root of V over the box's mean luminance) above which the filter's
/// picture is taken whole: there the raw one's error is mostly the photon estimate's early
/// bias, which V leaves out (5x V at 2 passes on the colour-bleeding benchmark scene), and the
/// filter's own error floor (2.5-3.5% on the benchmark scenes) is far below it.
inline constexpr double kFilterTrusted = 0.05;
/// Relative noise below which only the weight V / (V + b^2) decides; linear in between.
inline constexpr double kRawTrusted = 0.02;

/// The box radius (pixels) over which blend_by_noise judges noise and bias.
inline constexpr int kNoiseBlendRadius = 4;

}  // namespace dp
