#pragma once
// The photograph as an ideal pinhole camera would have taken it: the lens distortion of the
// project's camera taken out by resampling. The renderer never needs this (its rays go through
// the distorted camera); it is for other tools that assume a pinhole (a modeller's backdrop,
// another matcher).
#include "camera/camera.h"
#include "image/image.h"

namespace dp {

/// `photo` resampled to the pinhole image of the same size and intrinsics (fx, fy, cx, cy)
/// without distortion: output pixel p shows the photo at K distort(K⁻¹ p), bilinearly
/// interpolated. Output pixels whose source lies outside the photo (beyond its border's pixel
/// edges: the corners, for a pincushion lens) are black; a barrel lens' outer rim is cut off.
/// With zero distortion the photo comes back unchanged but for float rounding of the
/// coordinates. Throws InputError when `camera` is not built for the photo's size.
Image undistort_image(const Image& photo, const Camera& camera);

}  // namespace dp
