#include "render/photographed_radiance.h"

#include "assets/real_gloss.h"
#include "assets/scattering.h"
#include "render/light_estimate.h"

namespace dp {

ProbeLightSample sample_probe_light(const RenderScene& scene, const Hit& hit, const vec3& dir, Rng& rng) {
    ProbeLightSample out;
    const vec3 n = facing_normal(hit.ng, dir);
    const ProbeSample s = scene.probe().sample(rng.uniform(), rng.uniform(), rng.uniform());
    const float cos_t = glm::dot(n, s.dir);
    if (cos_t <= 0 || s.pdf <= 0) return out;
    Hit h = hit;
    h.ng = n;
    out.ray = Ray{scene.offset_origin(h, s.dir), s.dir};
    out.reflected = hit.surface->reflectance_at(hit.uv) * kInvPi * s.radiance * (cos_t / s.pdf);
    out.valid = true;
    return out;
}

namespace {

/// The photograph's pixel where the camera sees the point from the side -dir leaves (false
/// elsewhere).
bool photo_pixel(const RenderScene& scene, const Hit& hit, const vec3& dir, vec3& out) {
    const vec3 to_cam = scene.camera().position() - hit.p;
    // The viewer (looking along dir) and the camera on the same side of the surface.
    const bool same_side = glm::dot(hit.ng, to_cam) * glm::dot(hit.ng, -dir) > 0;
    vec2 px;
    if (!same_side || !scene.camera_sees(hit.p, hit.ng, &px)) return false;
    out = scene.photo().bilinear(px.x, px.y);
    return true;
}

/// rho E / pi with E from one probe sample with real-geometry visibility.
vec3 lambert_from_probe(const RenderScene& scene, const Hit& hit, const vec3& dir, Rng& rng) {
    const ProbeLightSample ls = sample_probe_light(scene, hit, dir, rng);
    if (!ls.valid || scene.occluded_real(ls.ray)) return vec3(0);
    return ls.reflected;
}

/// The photograph's pixel, or rho E / pi: a real point as if it were Lambertian.
vec3 lambert_radiance(const RenderScene& scene, const Hit& hit, const vec3& dir, Rng& rng) {
    vec3 photo;
    return photo_pixel(scene, hit, dir, photo) ? photo : lambert_from_probe(scene, hit, dir, rng);
}

}  // namespace

vec3 real_gloss_radiance(const RenderScene& scene, const Hit& hit, const vec3& dir, Rng& rng) {
    const GlossLobe lobe(hit, dir);
    if (!lobe.valid()) return vec3(0);
    vec3 out(0);
    // The probe's sun by light sampling and the lobe's own sample, by MIS: a small bright sun
    // is found by the lobe too rarely.
    const ProbeLights& lights = scene.probe_lights();
    if (lights.has_sun()) {
        const ProbeSample ls = lights.sample_sun(vec2(rng.uniform(), rng.uniform()));
        const float f = ls.pdf > 0 ? lobe.eval_cos(ls.dir) : 0.0f;
        if (f > 0 && !scene.occluded_real(Ray{scene.offset_origin(hit, ls.dir), ls.dir}))
            out += ls.radiance * (f / ls.pdf * power_heuristic(ls.pdf, lobe.pdf(ls.dir)));
    }
    vec3 wi;
    float weight = 0;
    if (lobe.sample(vec2(rng.uniform(), rng.uniform()), wi, weight)) {
        const Hit hr = scene.intersect_real(Ray{scene.offset_origin(hit, wi), wi});
        if (hr) {
            out += weight * lambert_radiance(scene, hr, wi, rng);
        } else {
            const float sun = lights.sun_pdf(wi);
            out += weight * scene.probe().radiance(wi) * (sun > 0 ? power_heuristic(lobe.pdf(wi), sun) : 1.0f);
        }
    }
    return is_finite(out) ? out : vec3(0);
}

vec3 photographed_radiance(const RenderScene& scene, const Hit& hit, const vec3& dir, Rng& rng) {
    const bool glossy = !hit.surface->is_virtual && hit.surface->gloss_f0 > 0;
    vec3 photo;
    if (photo_pixel(scene, hit, dir, photo)) {
        if (!glossy) return photo;
        // The photo shows the gloss as the camera saw it: seen from elsewhere, that part is
        // swapped for the gloss towards the viewer.
        const vec3 from_camera = glm::normalize(hit.p - scene.camera().position());
        if (glm::dot(from_camera, dir) > 0.99999f) return photo;
        return photo - real_gloss_radiance(scene, hit, from_camera, rng) + real_gloss_radiance(scene, hit, dir, rng);
    }
    const vec3 lambert = lambert_from_probe(scene, hit, dir, rng);
    return glossy ? lambert + real_gloss_radiance(scene, hit, dir, rng) : lambert;
}

}  // namespace dp
