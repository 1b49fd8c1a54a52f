#pragma once
// Display transform for the viewport: linear radiance to 8-bit sRGB, as `diffphoton convert`
// writes it (exposure in stops, clamp, the core's linear_to_srgb), through a lookup table.
#include <QImage>

#include "image/image.h"

namespace dp::ui {

enum class ViewMode { Photo, Augmented, Delta };

/// linear * 2^exposure -> sRGB, clamped to [0, 1].
QImage to_display(const Image& image, float exposure);

/// Signed false colour for dL: red where the objects add light (caustics, reflections), blue
/// where they remove it (shadows), black where nothing changed; |dL| * 2^exposure through sRGB.
QImage to_false_colour(const Image& delta, float exposure);

}  // namespace dp::ui
