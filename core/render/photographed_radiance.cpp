#include "render/photographed_radiance.h"

#include "render/scattering.h"

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

vec3 photographed_radiance(const RenderScene& scene, const Hit& hit, const vec3& dir, Rng& rng) {
    const Camera& cam = scene.camera();
    const vec3 to_cam = cam.position() - hit.p;
    vec2 px;
    const bool same_side = glm::dot(hit.ng, to_cam) * glm::dot(hit.ng, -dir) > 0;
    if (same_side && cam.project(hit.p, px) && cam.in_image(px)) {
        const float dist = glm::length(to_cam);
        const vec3 d = to_cam / dist;
        if (!scene.occluded_real(Ray{scene.offset_origin(hit, d), d}, dist * (1 - 1e-4f)))
            return scene.photo().bilinear(px.x, px.y);
    }
    const ProbeLightSample ls = sample_probe_light(scene, hit, dir, rng);
    if (!ls.valid || scene.occluded_real(ls.ray)) return vec3(0);
    return ls.reflected;
}

}  // namespace dp
