#pragma once
#include "base/rng.h"
#include "render/render_scene.h"

namespace dp {

/// Monte Carlo estimate of the probe irradiance at a real surface point: probe directions drawn
/// by flux (the probe's alias table), each kept when it is above the surface and no real proxy
/// blocks it (virtual objects are ignored: this is the real scene's E of rho = pi L / E).
struct IrradianceEstimate {
    dvec3 E{0.0};
    /// Standard error of luminance(E) over the samples (0 when fewer than two were taken).
    double luminance_std_error = 0;
};

/// `n` is the unit normal on the side that receives light (the side the camera sees).
IrradianceEstimate real_irradiance(const RenderScene& scene, const vec3& p, const vec3& n, Rng& rng,
                                   int samples);

}  // namespace dp
