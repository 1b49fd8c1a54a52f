#include "render/irradiance.h"

#include <algorithm>
#include <cmath>

namespace dp {

IrradianceEstimate real_irradiance(const RenderScene& scene, const vec3& p, const vec3& n, Rng& rng,
                                   int samples) {
    IrradianceEstimate out;
    if (samples <= 0) return out;
    const Probe& probe = scene.probe();
    Hit at;
    at.p = p;
    at.ng = n;
    dvec3 sum(0.0);
    double sum_l = 0, sum_l2 = 0;
    for (int k = 0; k < samples; ++k) {
        // The three draws stay in one call, as the per-proxy estimate made them: its results keep.
        ProbeSample s = probe.sample(rng.uniform(), rng.uniform(), rng.uniform());
        float cos_t = glm::dot(n, s.dir);
        if (cos_t <= 0 || s.pdf <= 0) continue;
        if (scene.occluded_real(Ray{scene.offset_origin(at, s.dir), s.dir})) continue;
        dvec3 c = dvec3(s.radiance * (cos_t / s.pdf));
        sum += c;
        double l = luminance(c);
        sum_l += l;
        sum_l2 += l * l;
    }
    out.E = sum / double(samples);
    if (samples > 1) {
        double mean = sum_l / samples;
        double var = std::max(0.0, (sum_l2 / samples - mean * mean) * samples / (samples - 1.0));
        out.luminance_std_error = std::sqrt(var / samples);
    }
    return out;
}

}  // namespace dp
