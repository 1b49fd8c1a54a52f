#pragma once
#include <cstdint>
#include <vector>

#include "base/math.h"
#include "render/render_scene.h"

namespace dp {

/// What each pixel's centre ray sees, computed once per camera and geometry: the display
/// needs it to skip pixels no photon can change.
struct PixelCache {
    std::vector<uint8_t> near_virtual;  ///< the pixel or a neighbour sees a virtual object
    std::vector<uint8_t> has_real;      ///< the centre ray hits real geometry first
    std::vector<vec3> real_point;       ///< that hit (valid where has_real)
};

/// Traces one ray through every pixel centre (all zero when the scene has no virtual object).
PixelCache build_pixel_cache(const RenderScene& scene);

}  // namespace dp
