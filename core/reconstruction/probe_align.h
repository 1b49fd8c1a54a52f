#pragma once
#include <string>

#include "assets/render_scene.h"
#include "camera/camera.h"
#include "image/image.h"

namespace dp {

/// A shadow cue clicked in the photo: a point of an object and the tip of its shadow on the
/// ground. The object point is either at a known height above the ground (`object_is_base` =
/// false: its pixel is the point itself) or directly above a clicked base point on the ground
/// (`object_is_base` = true: its pixel is the base, the point is `height` above it).
struct ShadowCue {
    vec2 object_px{0.0f};
    float height = 0;
    bool object_is_base = false;
    vec2 shadow_px{0.0f};
};

/// Unit world direction towards the sun from a shadow cue (the object point minus the shadow
/// tip). Throws InputError for points above the horizon, a non-positive height or a shadow tip
/// on the object's own foot.
vec3 sun_direction_from_shadow(const Camera& camera, const ShadowCue& cue);

/// Probe-space direction of a lat-long map's brightest region: the luminance-and-solid-angle
/// weighted centroid of the pixels within `cone_deg` of the brightest pixel whose luminance is
/// at least `fraction` of it. Throws InputError (labelled `field`) for a black map.
vec3 brightest_direction(const Image& latlong, float fraction = 0.5f, float cone_deg = 20.0f,
                         const std::string& field = "probe.path");

/// Compass bearing of a world direction, in degrees.
struct Bearing {
    float azimuth_deg = 0;    ///< from -Z towards +X, as the probe's lat-long map counts it
    float elevation_deg = 0;  ///< above the horizon
};

/// Azimuth and elevation of unit world direction `d` (e.g. the sun's).
Bearing bearing_of(const vec3& d);

/// A yaw (rotation about world +Y) that brings the probe's brightest region onto a direction.
struct ProbeYaw {
    vec3 rotation_deg{0.0f};  ///< the probe's new Euler XYZ angles (world Y turn applied last)
    float yaw_deg = 0;        ///< the turn added, in (-180, 180]
    /// Elevation of the brightest region (after the turn) minus the target's, in degrees: a
    /// turn about Y cannot change it, so it measures how well the cue and the probe agree.
    float elevation_mismatch_deg = 0;
    vec3 bright_world{0.0f};  ///< the brightest region's world direction after the turn
};

/// Turns the probe (current Euler angles `rotation_deg`) about world Y so that the brightest
/// region `bright_probe` (probe space) has the azimuth of `target_world`. Throws InputError when
/// either direction is vertical (no azimuth).
ProbeYaw align_probe_yaw(const vec3& bright_probe, const vec3& rotation_deg,
                         const vec3& target_world);

/// A patch of known reflectance in the photo (pixel rectangle, corners inclusive).
struct GreyCard {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    float reflectance = 0.18f;
};

/// Probe intensity that makes rho * E / pi match the photo on a grey card.
struct ExposureMatch {
    float intensity = 1;  ///< the new probe intensity
    float scale = 1;      ///< new intensity / current intensity
    int pixels = 0;       ///< card pixels used
    /// Coefficient of variation of the per-pixel ratios pi L / (rho E) over the card: how
    /// evenly the card is lit and seen (noise, shading, a wrong reflectance do not show here).
    float spread = 0;
};

/// Exposure from a grey card: every card pixel's camera ray is traced to the real proxy it shows,
/// E is estimated there with real-geometry visibility, and the intensity is scaled by
/// pi * sum(L) / (rho * sum(E)) in luminance. Throws InputError for a rectangle outside the
/// photo, pixels that show no real proxy, clipped pixels (`clip_level`, photo units after
/// exposure) or an unlit card.
ExposureMatch match_exposure_grey_card(const RenderScene& scene, const GreyCard& card,
                                       float clip_level = INFINITY, int probe_samples = 256,
                                       uint64_t seed = 1);

/// Exposure and white balance from a grey card: what match_exposure_grey_card measures, per
/// channel. `intensity` is the luminance of the new gain (intensity times white balance) and
/// `scale` that over the current intensity; `pixels` and `spread` are as there.
struct WhiteBalanceMatch : ExposureMatch {
    vec3 white_balance{1.0f};  ///< the probe's new white balance, of luminance 1
    /// New gain over the current gain, per channel: pi sum(L_c) / (rho sum(E_c)).
    vec3 channel_scale{1.0f};
    /// The card's colour as r, g, b summing to 1: in the photo, and as the probe lit it
    /// (rho E / pi) before and after the match (equal to the photo's but for rounding).
    vec3 photo_chromaticity{1.0f / 3.0f}, before_chromaticity{1.0f / 3.0f},
        after_chromaticity{1.0f / 3.0f};
};

/// Probe intensity and white balance from a grey card (a neutral reflectance): the card is traced
/// as in match_exposure_grey_card, and the probe's gain per channel c (intensity times white
/// balance) is scaled by pi * sum(L_c) / (rho * sum(E_c)). The result is split into the
/// luminance of the new gain (the intensity) and the gain over it (the white balance, of
/// luminance 1). Throws InputError as match_exposure_grey_card does, and for a channel in which
/// the card is black or unlit.
WhiteBalanceMatch match_white_balance_grey_card(const RenderScene& scene, const GreyCard& card,
                                                float clip_level = INFINITY,
                                                int probe_samples = 256, uint64_t seed = 1);

}  // namespace dp
