#pragma once
#include <cmath>
#include <cstdint>

#include "base/math.h"

namespace dp {

/// Concentric (Shirley-Chiu) mapping of the unit square onto the unit disk: uniform in area.
vec2 sample_concentric_disk(vec2 u);

/// Cosine-weighted direction about +Z; pdf = cos(theta)/pi.
vec3 sample_cosine_hemisphere(vec2 u);
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0 ? cos_theta * kInvPi : 0; }

/// Uniform direction on the unit sphere; pdf = 1/(4 pi).
vec3 sample_uniform_sphere(vec2 u);

/// Point `index` of the R2 low-discrepancy sequence shifted by `shift` (Cranley-Patterson
/// rotation), in [0,1)^2. Sub-pixel positions from it cover a pixel evenly for any number of
/// samples, so edges and textures seen in mirrors converge faster than with random jitter.
inline vec2 r2_point(uint64_t index, vec2 shift) {
    constexpr double a1 = 0.75487766624669276, a2 = 0.56984029099805327;  // 1/g, 1/g^2, g^3 = g + 1
    const double x = double(shift.x) + a1 * double(index % (uint64_t(1) << 40));
    const double y = double(shift.y) + a2 * double(index % (uint64_t(1) << 40));
    return vec2(float(x - std::floor(x)), float(y - std::floor(y)));
}

}  // namespace dp
