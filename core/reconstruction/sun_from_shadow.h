#pragma once
// A clipped sun's light given back from the photo's own shadow: a lit and a shadowed patch of
// one real surface differ by the sun's light alone, so their contrast says how strong the sun
// is against the sky (docs/probe-sun.md).
#include <cstdint>

#include "assets/render_scene.h"

namespace dp {

/// Two patches of one real surface clicked in the photo: one in sunlight, one in the shadow of
/// something (modelled or not) that hides the sun from it.
struct SunShadowPatches {
    vec2 lit{0.0f}, shadow{0.0f};  ///< patch centres (pixels)
    int radius = 2;                ///< each patch is (2 radius + 1)^2 pixels
};

/// What the patches say about the probe's sun.
struct SunFromShadow {
    float scale = 1;           ///< the factor the probe's sun (as loaded) needs
    float sun_scale = 1;       ///< the new probe.sun_scale: the current one times `scale`
    double photo_contrast = 0; ///< lit over shadowed luminance in the photo
    double probe_contrast = 0; ///< the same as the probe lit them before, and after (= photo)
    /// Luminance irradiance at the patch centres: the sun's direct at the lit one, the sky's
    /// (direct and off the real proxies) at both.
    double sun_lit = 0, sky_lit = 0, sky_shadow = 0;
};

/// Scales the probe's sun (find_probe_sun's pixels) so that the probe lights the two patches
/// with the photo's contrast: L_lit / L_shadow = (A_lit + s B_lit) / (A_shadow + s B_shadow),
/// the albedo the same, A the sky's irradiance and B the sun's, each directly and after up to
/// three bounces off the real proxies (a modelled occluder lights its own shadow; what is not
/// modelled lights nothing). The sun's direct light takes its pixels one ray each; the rest
/// `sky_samples` cosine-weighted walks, each vertex one more ray towards the sun. Throws InputError (field "sun_from_shadow") for a patch outside the
/// photo or on no real proxy, patches on two proxies, a probe without a compact sun, a lit
/// patch the probe's sun cannot reach, and a contrast the sky alone already gives.
SunFromShadow match_sun_to_shadow(const RenderScene& scene, const SunShadowPatches& patches,
                                  int sky_samples = 4096, uint64_t seed = 1);

}  // namespace dp
