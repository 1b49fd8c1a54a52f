#pragma once
// Layers a compositor (Blender's, Nuke) needs to rebuild the render over the plate, or over a
// graded plate: docs/compositing.md gives the recipes.
#include "image/image.h"

namespace dp {

/// The virtual objects alone, premultiplied by their coverage: what the beauty keeps beyond the
/// plate times the catcher, augmented - (1 - alpha) photo catcher, so that the recipe
/// objects + (1 - alpha) photo catcher gives the beauty back to float rounding. Where the
/// catcher is the real surfaces' own ratio this is augmented - (1 - alpha) photo - dL (a
/// pixel's render is alpha obj + (1 - alpha) photo + dL); where it had to be held (at 0 in a
/// noisy shadow, at 1 on a black photo channel or a fully covered pixel) the rest of dL is here,
/// so a noisy pixel may be slightly negative, as its beauty's noise is. Where alpha is 0 and the
/// catcher is the surfaces' own ratio it is exactly 0. Same sizes required.
Image objects_premultiplied(const Image& augmented, const Image& photo, const Image& alpha, const Image& dL);

/// Blender's multiplicative shadow catcher, per channel: the light on the real surface with the
/// objects over the light without them, (photo + dL / (1 - alpha)) / photo. 1 where nothing
/// changes; below 1 in shadows, above 1 where caustics and bounce light land, coloured. Where
/// the photo's channel is 0 (no ratio) or an object covers the pixel fully (alpha >= 0.999, no
/// real surface seen) it is 1. Never negative, finite.
Image shadow_catcher(const Image& photo, const Image& alpha, const Image& dL);

/// The beauty rebuilt from the layers, as the recipe does: objects + (1 - alpha) photo catcher.
Image recomposite(const Image& objects, const Image& alpha, const Image& photo, const Image& catcher);

}  // namespace dp
