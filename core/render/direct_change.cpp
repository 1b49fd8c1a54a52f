#include "render/direct_change.h"

#include <algorithm>
#include <cmath>

#include "base/sampling.h"
#include "image/image_metrics.h"
#include "render/photographed_radiance.h"
#include "assets/scattering.h"

namespace dp {

namespace {

/// Uniform direction in the cone about `axis` with 1 - cos(half angle) = one_minus_cos.
vec3 sample_cone(const vec3& axis, double one_minus_cos, vec2 u) {
    const double cos_t = 1 - double(u.x) * one_minus_cos;
    const double sin_t = std::sqrt(std::max(0.0, double(u.x) * one_minus_cos * (1 + cos_t)));
    const double phi = 2 * 3.14159265358979323846 * double(u.y);
    return Frame(axis).to_world(vec3(float(sin_t * std::cos(phi)), float(sin_t * std::sin(phi)), float(cos_t)));
}

/// Scratch space for the cones of one point: estimates run per pixel and per pass, too often
/// for an allocation each.
std::vector<ClusterCone>& scratch_cones() {
    thread_local std::vector<ClusterCone> cones;
    return cones;
}

}  // namespace

DirectChange::DirectChange(const RenderScene& scene, float real_radiance_max)
    : scene_(scene), probe_max_(scene.probe()),
      real_radiance_max_(real_radiance_max > 0 ? real_radiance_max : luminance_quantile(scene.photo(), 0.99)) {}

void DirectChange::cones(const vec3& p, const vec3& n, std::vector<ClusterCone>& out) const {
    const auto& clusters = scene_.clusters();
    out.assign(clusters.size(), ClusterCone{});
    for (size_t k = 0; k < clusters.size(); ++k) {
        const dvec3 to_c = dvec3(clusters[k].center) - dvec3(p);
        const double d2 = glm::dot(to_c, to_c), r = clusters[k].radius, r2 = r * r;
        ClusterCone& c = out[k];
        if (d2 <= r2) {
            c.inside = true;
            c.axis = n;
            c.solid_angle = 2 * kPi;
            c.half_angle = kPi / 2;
            continue;
        }
        const double d = std::sqrt(d2), s2 = r2 / d2;
        c.axis = vec3(to_c / d);
        // Entirely below the horizon: nothing there can block light arriving from above.
        if (glm::dot(dvec3(c.axis), dvec3(n)) < -std::sqrt(s2)) continue;
        c.one_minus_cos = s2 / (1 + std::sqrt(1 - s2));
        c.solid_angle = 2 * kPi * c.one_minus_cos;
        c.half_angle = float(std::asin(std::sqrt(s2)));
    }
}

double DirectChange::cone_pdf(const std::vector<ClusterCone>& cones, const vec3& w, const vec3& n) const {
    double total = 0, pdf = 0;
    for (const ClusterCone& c : cones) total += c.solid_angle;
    if (total <= 0) return 0;
    for (const ClusterCone& c : cones) {
        if (c.solid_angle <= 0) continue;
        if (c.inside) {
            pdf += c.solid_angle / total * double(cosine_hemisphere_pdf(glm::dot(n, w)));
        } else if (1 - glm::dot(dvec3(w), dvec3(c.axis)) <= c.one_minus_cos * (1 + 1e-6) + 1e-12) {
            pdf += 1 / total;  // (solid angle / total) * (1 / solid angle)
        }
    }
    return pdf;
}

vec3 DirectChange::blocked_radiance(const Hit& hit, const vec3& n, const vec3& w, Rng& rng, bool real_only) const {
    if (glm::dot(n, w) <= 0) return vec3(0);
    Hit at = hit;
    at.ng = n;
    const Ray ray{scene_.offset_origin(at, w), w};
    const Hit hv = scene_.intersect_virtual(ray);
    // Glass: the light it lets through lands near its shadow, so photons carry both together.
    if (!hv || hv.surface->transmits()) return vec3(0);
    const Hit hr = scene_.intersect_real(ray);
    if (hr && hr.t < hv.t) return vec3(0);  // a real surface already stood in the way
    if (!hr) return real_only ? vec3(0) : scene_.probe().radiance(w);
    return photographed_radiance(scene_, hr, w, rng);
}

dvec3 DirectChange::light_sample(const Hit& hit, const vec3& n, const std::vector<ClusterCone>& cones,
                                 const ProbeSample& s, Rng& rng, bool real_only) const {
    if (s.pdf <= 0) return dvec3(0);
    const double pb = cone_pdf(cones, s.dir, n);
    if (pb <= 0) return dvec3(0);  // outside every cone nothing virtual can block it: no ray
    const vec3 L = blocked_radiance(hit, n, s.dir, rng, real_only);
    if (L == vec3(0)) return dvec3(0);
    const double pa = s.pdf, weight = pa * pa / (pa * pa + pb * pb);
    return -dvec3(L) * (double(glm::dot(n, s.dir)) / pa * weight);
}

dvec3 DirectChange::estimate(const Hit& hit, const vec3& n, const Samples& u, Rng& rng, bool real_only) const {
    std::vector<ClusterCone>& cs = scratch_cones();
    cones(hit.p, n, cs);
    double total = 0;
    for (const ClusterCone& c : cs) total += c.solid_angle;
    if (total <= 0) return dvec3(0);
    const ProbeLights& lights = scene_.probe_lights();

    // The sun and the sky, by flux: they find a sun that the cone sample would rarely hit.
    dvec3 sum = light_sample(hit, n, cs, lights.sample_sun(u.sun), rng, real_only);
    sum += light_sample(hit, n, cs, lights.sample_sky(u.sky), rng, real_only);

    // The cones: the sky and the real surfaces behind the objects, evenly over what they hide.
    double pick = double(u.pick) * total;
    size_t k = 0;
    for (size_t i = 0; i < cs.size(); ++i) {
        if (cs[i].solid_angle <= 0) continue;
        k = i;  // the last cone with a solid angle, should rounding carry `pick` past all
        if (pick < cs[i].solid_angle) break;
        pick -= cs[i].solid_angle;
    }
    const ClusterCone& c = cs[k];
    const vec3 w = c.inside ? Frame(n).to_world(sample_cosine_hemisphere(u.cone))
                            : sample_cone(c.axis, c.one_minus_cos, u.cone);
    const double pb = cone_pdf(cs, w, n);
    if (pb > 0) {
        const vec3 L = blocked_radiance(hit, n, w, rng, real_only);
        if (L != vec3(0)) {
            const double pa = lights.pdf(w), weight = pb * pb / (pa * pa + pb * pb);
            sum -= dvec3(L) * (double(glm::dot(n, w)) / pb * weight);
        }
    }
    return sum;
}

double DirectChange::bound(const vec3& p, const vec3& n) const {
    std::vector<ClusterCone>& cs = scratch_cones();
    cones(p, n, cs);
    double b = 0;
    for (const ClusterCone& c : cs) {
        if (c.solid_angle <= 0) continue;
        if (c.inside) {
            b += double(kPi) * std::max(probe_max_.global_max(), real_radiance_max_);  // a hemisphere weighs pi
            continue;
        }
        const float light = std::max(probe_max_.max_in_cone(c.axis, c.half_angle), real_radiance_max_);
        // The largest cosine inside the cone: a ball near the horizon blocks light at a grazing angle.
        const double axis_angle = std::acos(std::clamp(double(glm::dot(c.axis, n)), -1.0, 1.0));
        const double cos_max = axis_angle <= c.half_angle ? 1.0 : std::cos(axis_angle - c.half_angle);
        b += c.solid_angle * std::max(0.0, cos_max) * double(light);
    }
    return b;
}

}  // namespace dp
