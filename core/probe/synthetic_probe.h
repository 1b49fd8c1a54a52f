#pragma once
#include "base/math.h"
#include "image/image.h"

namespace dp {

/// Synthetic lat-long probes (convention of probe.h) for tests and benchmarks.

/// Every pixel has the same radiance: a uniform white furnace.
Image make_constant_probe(int w, int h, vec3 radiance);

/// A clear sky with a sun disk. Above the horizon the sky blends from `sky_horizon` to
/// `sky_zenith` linearly in the sine of the elevation; below the horizon the ground is black.
/// Sun pixels are those whose centre direction lies within `sun_angular_radius_deg` of
/// `sun_dir_probe_space` (normalised here); they are set to `sun_radiance`, replacing the sky.
/// If no pixel centre is that close, the single pixel nearest the sun direction is the sun.
/// Throws std::invalid_argument for a zero sun direction.
Image make_sun_sky_probe(int w, int h, vec3 sun_dir_probe_space, vec3 sun_radiance,
                         float sun_angular_radius_deg, vec3 sky_zenith, vec3 sky_horizon);

/// All black but pixel (px, py): a directional light of that pixel's solid angle.
/// Throws std::out_of_range when the pixel is outside the map.
Image make_single_pixel_probe(int w, int h, int px, int py, vec3 radiance);

}  // namespace dp
