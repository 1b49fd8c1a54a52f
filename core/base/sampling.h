#pragma once
#include "base/math.h"

namespace dp {

/// Concentric (Shirley-Chiu) mapping of the unit square onto the unit disk: uniform in area.
vec2 sample_concentric_disk(vec2 u);

/// Cosine-weighted direction about +Z; pdf = cos(theta)/pi.
vec3 sample_cosine_hemisphere(vec2 u);
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0 ? cos_theta * kInvPi : 0; }

/// Uniform direction on the unit sphere; pdf = 1/(4 pi).
vec3 sample_uniform_sphere(vec2 u);

}  // namespace dp
