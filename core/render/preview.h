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

/// Pixel budgets of the previews shown while an object is dragged, largest first, each
/// 1/sqrt(2) of the one before: a viewer steps through them to keep its frame rate, and the
/// few fixed sizes let resampled photos be cached.
inline constexpr int kDragPreviewLevels = 7;
double drag_preview_pixels(int level, double max_pixels = 100000);

/// The relative error (RMS over changed pixels, as RenderStats::estimated_rel_error) at which
/// noise is invisible on an 8-bit sRGB display: one standard error below half a code value at
/// the changed pixels' mean value (`mean_value`, linear) shown at `exposure_stops`.
double invisible_relative_error(double mean_value, double exposure_stops);

}  // namespace dp
