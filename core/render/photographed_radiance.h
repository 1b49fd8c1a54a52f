#pragma once
#include "base/rng.h"
#include "assets/render_scene.h"

namespace dp {

/// One probe sample seen from a real point, on its side facing -dir: the ray towards the probe
/// and the radiance the point reflects from it, rho/pi * L cos / pdf, if nothing blocks it.
struct ProbeLightSample {
    Ray ray;
    vec3 reflected{0};
    bool valid = false;  ///< false: below the surface, or a direction of pdf 0
};
ProbeLightSample sample_probe_light(const RenderScene& scene, const Hit& hit, const vec3& dir, Rng& rng);

/// Radiance a real surface point sends towards -dir in the unaltered scene: the photograph's
/// pixel where the camera sees the point (same side, in frame, unoccluded by real geometry;
/// Lambertian, so the direction does not matter), else rho E / pi with E from one probe sample
/// with real-geometry visibility (unbiased, averaged over passes). A glossy proxy's photo
/// pixel holds its gloss as the camera saw it: seen from elsewhere, that gloss is replaced by
/// the gloss towards the viewer (real_gloss_radiance; the pixel itself where the viewer is the
/// camera), and rho E / pi gets the gloss towards the viewer added.
vec3 photographed_radiance(const RenderScene& scene, const Hit& hit, const vec3& dir, Rng& rng);

/// What the gloss layer of a real point reflects towards -dir in the unaltered scene: the probe
/// (its sun sampled as a light too, by MIS), or the real surface it sees, taken as Lambertian
/// (one bounce of gloss: a glossy surface seen in another is not glossy again). 0 for a matte
/// surface.
vec3 real_gloss_radiance(const RenderScene& scene, const Hit& hit, const vec3& dir, Rng& rng);

}  // namespace dp
