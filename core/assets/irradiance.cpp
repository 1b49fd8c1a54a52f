#include "assets/irradiance.h"

#include <algorithm>
#include <cmath>

#include "base/sampling.h"

namespace dp {

namespace {

/// Mean and standard error of luminance from running sums.
void finish(IrradianceEstimate& out, const dvec3& sum, double sum_l, double sum_l2, int samples) {
    out.E = sum / double(samples);
    if (samples > 1) {
        double mean = sum_l / samples;
        double var = std::max(0.0, (sum_l2 / samples - mean * mean) * samples / (samples - 1.0));
        out.luminance_std_error = std::sqrt(var / samples);
    }
}

}  // namespace

IrradianceEstimate real_irradiance(const RenderScene& scene, const vec3& p, const vec3& n, Rng& rng,
                                   int samples, float cosine_fraction) {
    if (cosine_fraction > 0) return mean_real_irradiance(scene, {{p, n}}, rng, samples, cosine_fraction);
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
        dvec3 contribution = dvec3(s.radiance * (cos_t / s.pdf));
        sum += contribution;
        double l = luminance(contribution);
        sum_l += l;
        sum_l2 += l * l;
    }
    finish(out, sum, sum_l, sum_l2, samples);
    return out;
}

IrradianceEstimate mean_real_irradiance(const RenderScene& scene, const std::vector<SurfacePoint>& points,
                                        Rng& rng, int samples, float cosine_fraction) {
    IrradianceEstimate out;
    if (samples <= 0 || points.empty()) return out;
    const Probe& probe = scene.probe();
    const float c = std::clamp(cosine_fraction, 0.0f, 1.0f);
    const int n_cos = int(std::lround(c * samples)), n_probe = samples - n_cos;
    dvec3 sum(0.0);
    double sum_l[2] = {0, 0}, sum_l2[2] = {0, 0};  // per strategy: the split between them is fixed
    for (int k = 0; k < samples; ++k) {
        const SurfacePoint& sp = points[size_t(k) % points.size()];
        const bool cosine = k < n_cos;
        const int stratum = cosine ? k : k - n_cos, strata = cosine ? n_cos : n_probe;
        float u0 = std::min((stratum + rng.uniform()) / strata, 0x1.fffffep-1f);
        float u1 = rng.uniform(), u2 = rng.uniform();
        vec3 dir, radiance;
        float probe_pdf;
        if (cosine) {
            dir = Frame(sp.n).to_world(sample_cosine_hemisphere(vec2(u0, u1)));
            radiance = probe.radiance(dir);
            probe_pdf = probe.pdf(dir);
        } else {
            // The sample's own pdf: a direction on a pixel's edge may look up its neighbour.
            ProbeSample s = probe.sample(u0, u1, u2);
            dir = s.dir;
            radiance = s.radiance;
            probe_pdf = s.pdf;
        }
        float cos_t = glm::dot(sp.n, dir);
        float pdf = c * cosine_hemisphere_pdf(cos_t) + (1 - c) * probe_pdf;
        if (cos_t <= 0 || pdf <= 0) continue;
        Hit at;
        at.p = sp.p;
        at.ng = sp.n;
        if (scene.occluded_real(Ray{scene.offset_origin(at, dir), dir})) continue;
        dvec3 contribution = dvec3(radiance * (cos_t / pdf));
        sum += contribution;
        double l = luminance(contribution);
        sum_l[cosine] += l;
        sum_l2[cosine] += l * l;
    }
    out.E = sum / double(samples);
    // Variance of a stratified sum: each strategy's own sample variance, weighted by its share.
    double var = 0;
    for (int g = 0; g < 2; ++g) {
        int n = g ? n_cos : n_probe;
        if (n < 2) continue;
        double mean = sum_l[g] / n;
        double v = std::max(0.0, (sum_l2[g] / n - mean * mean) * n / (n - 1.0));
        var += double(n) * v / (double(samples) * samples);
    }
    out.luminance_std_error = std::sqrt(var);
    return out;
}

}  // namespace dp
