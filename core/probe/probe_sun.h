#pragma once
// The probe's sun as its pixels hold it, and whether it holds all of it. A camera that shot the
// probe without enough stops clips the sun: it keeps its place but loses most of its light,
// and every shadow in the render comes out too weak (docs/probe-sun.md).
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"

namespace dp {

/// The compact brightest region of a lat-long probe (probe space, +Y up).
struct ProbeSun {
    bool found = false;
    /// Row-major pixel indices of the region: the pixels within kSunCapDeg of the brightest
    /// one and at least `level` times its luminance.
    std::vector<uint32_t> pixels;
    float level = 0;           ///< the fraction of the peak the region was cut at
    float peak = 0;            ///< luminance of the brightest pixel
    vec3 direction{0, 1, 0};   ///< unit, flux-weighted centre of the region
    double elevation_deg = 0;  ///< of `direction` above the probe's horizon
    double solid_angle = 0;    ///< of the region (sr)
    /// Luminance irradiance the region gives a surface facing it, and the rest of the upper
    /// hemisphere a horizontal surface (cosine-weighted).
    double sun_irradiance = 0, sky_irradiance = 0;
    /// Pixels at least kCeilingLevel times the peak, and how far the furthest of them lies from
    /// the brightest (degrees): separate lights that all reach the same peak met a ceiling.
    int near_peak = 0;
    double near_peak_spread_deg = 0;
    /// Solid angle of the pixels at least half the peak: hot spots, or a softbox's panels.
    double half_peak_solid_angle = 0;
    /// sun_irradiance / sky_irradiance (0 without sky).
    double ratio() const { return sky_irradiance > 0 ? sun_irradiance / sky_irradiance : 0.0; }
};

/// The sun is looked for within this angle of the brightest pixel...
inline constexpr double kSunCapDeg = 10.0;
/// ...cut at the first of these fractions of the peak at which every pixel that bright on the
/// whole probe lies inside that cap (a bright sky around a clipped sun fails the first cuts).
inline constexpr float kSunLevels[] = {0.05f, 0.25f, 0.5f};

/// Pixels this close to the peak are "at the peak"; if one stands further from the brightest
/// than the sun's cap and all pixels half as bright cover less than kMaxCeilingSolidAngle (hot
/// spots, not a studio's equal panels), they met a ceiling.
inline constexpr float kCeilingLevel = 0.95f;
inline constexpr double kMaxCeilingSolidAngle = 0.01;

/// Finds the sun of a lat-long probe; `found` false when no cut gives a compact region (an
/// overcast sky, a studio of softboxes) or the probe is black.
ProbeSun find_probe_sun(const Image& latlong);

/// A clear sun this high gives a horizontal surface several times the sky's light (about 3 to
/// 10 times from 10 degrees up), a hazy one about twice; less than kMinSunSkyRatio is a sun
/// that lost its light to clipping (or one behind cloud, which casts no crisp shadow either).
inline constexpr double kCheckedElevationDeg = 10.0;
inline constexpr double kMinSunSkyRatio = 2.5;

/// Why the probe's sun looks clipped, as a warning naming `field`: separate hot spots at one
/// peak (a ceiling), or a sun at least kCheckedElevationDeg up giving less than kMinSunSkyRatio
/// times the sky's light. Empty when it looks whole, when there is none, or when it is lower
/// (a low sun is weak anyway: only a shadow in the photo can tell).
std::string clipped_sun_warning(const ProbeSun& sun, const std::string& field = "probe.path");

/// Multiplies the pixels of `sun` in `latlong` by `scale` (probe.sun_scale).
void scale_probe_sun(Image& latlong, const ProbeSun& sun, float scale);

}  // namespace dp
