#pragma once
// Display transform for the viewport: linear radiance to 8-bit sRGB, as `diffphoton convert`
// writes it (exposure in stops, clamp, the core's linear_to_srgb), through a lookup table.
#include <QImage>

#include "image/display_transform.h"
#include "image/image.h"

namespace dp::ui {

enum class ViewMode { Photo, Augmented, Delta };

/// The widest picture the viewport converts for the screen: a larger render (a 12 MP photo) is
/// shown from every n-th pixel, so a frame costs the UI thread the same whatever the photo.
inline constexpr int kDisplayMaxWidth = 2560;

/// linear * 2^exposure -> sRGB, clamped to [0, 1]; at most `max_width` wide (0: any), from
/// every n-th pixel. With a `view` other than Standard, through it (its own exposure is ignored:
/// `exposure` is applied first).
QImage to_display(const Image& image, float exposure, int max_width = 0, const DisplayTransform* view = nullptr);

/// Signed false colour for dL: red where the objects add light (caustics, reflections), blue
/// where they remove it (shadows), black where nothing changed; |dL| * 2^exposure through sRGB.
QImage to_false_colour(const Image& delta, float exposure, int max_width = 0);

}  // namespace dp::ui
