#pragma once
#include <vector>

#include "base/rng.h"
#include "assets/render_scene.h"

namespace dp {

/// Monte Carlo estimate of the probe irradiance at a real surface point under real-geometry
/// visibility (virtual objects are ignored: this is the real scene's E of rho = pi L / E).
struct IrradianceEstimate {
    dvec3 E{0.0};
    /// Standard error of luminance(E) over the samples (0 when fewer than two were taken).
    double luminance_std_error = 0;
};

/// `n` is the unit normal on the side that receives light (the side the camera sees).
/// Directions are drawn by the probe's flux (its alias table); with `cosine_fraction` > 0 that
/// share of them is drawn cosine-distributed instead and the two are combined by their mixture
/// pdf, which keeps points that the sun cannot reach (only the sky lights them) from resting
/// on the handful of samples a flux-proportional draw spends on the sky.
IrradianceEstimate real_irradiance(const RenderScene& scene, const vec3& p, const vec3& n, Rng& rng,
                                   int samples, float cosine_fraction = 0);

/// A surface point and its unit normal on the lit side.
struct SurfacePoint {
    vec3 p, n;
};

/// Mean irradiance over several points (a texel's), with the mixture of real_irradiance:
/// sample k is taken at point k mod count and the strata run over all the samples, so that the
/// share that reaches the sun hardly varies however few samples each point gets.
IrradianceEstimate mean_real_irradiance(const RenderScene& scene, const std::vector<SurfacePoint>& points,
                                        Rng& rng, int samples, float cosine_fraction);

}  // namespace dp
