#pragma once
#include <cstdint>
#include <vector>

#include "image/image.h"

namespace dp {

/// A holdout as the renderer reads it (scene/project.h, Holdout): the part of the frame its mask
/// covers, and how far from the camera the occluder stands.
struct HoldoutMask {
    int width = 0, height = 0;
    std::vector<uint8_t> covered;  ///< row-major, 1 where the occluder is
    float depth = 1;               ///< metres along the camera's view axis

    /// Covers the pixels of `mask` whose luminance (as stored) is >= 0.5.
    static HoldoutMask from_image(const Image& mask, float depth);
    /// Whether the mask covers the point (u, v) of the frame, each in [0, 1) from the top left
    /// (the mask is stretched over the photo; its nearest pixel answers).
    bool covers(float u, float v) const;
    /// The share of the frame the mask covers, [0, 1].
    double coverage() const;
};

}  // namespace dp
