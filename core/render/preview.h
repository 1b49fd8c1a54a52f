#pragma once
#include <cstdint>

#include "scene/project.h"

namespace dp {

/// How a viewer previews an edit before it refines: a quick pass at reduced size with a share of
/// the photons and a doubled first radius (fewer photons need a wider gather), refining at that
/// size until the full-size render replaces it.
struct PreviewPolicy {
    double photon_fraction = 0.125;
    double scale = 0.5;               ///< of the full size, and at most `max_pixels`
    double max_pixels = 100000;

    RenderSettings settings(const RenderSettings& full) const;
    /// The preview's size for a full render of width x height.
    void size(int width, int height, int& preview_width, int& preview_height) const;
};

}  // namespace dp
