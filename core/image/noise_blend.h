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
/// estimate yet, as after one pass) returns `denoised`. Same sizes required.
Image blend_by_noise(const Image& raw, const Image& denoised, const Image& variance);

/// The box radius (pixels) over which blend_by_noise judges noise and bias.
inline constexpr int kNoiseBlendRadius = 4;

}  // namespace dp
