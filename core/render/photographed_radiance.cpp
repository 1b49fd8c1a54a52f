#include "render/photographed_radiance.h"

#include "assets/scattering.h"

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
    const vec3 to_cam = scene.camera().position() - hit.p;
    // The viewer (looking along dir) and the camera on the same side of the surface.
    const bool same_side = glm::dot(hit.ng, to_cam) * glm::dot(hit.ng, -dir) > 0;
    vec2 px;
    if (same_side && scene.camera_sees(hit.p, hit.ng, &px)) return scene.photo().bilinear(px.x, px.y);
    const ProbeLightSample ls = sample_probe_light(scene, hit, dir, rng);
    if (!ls.valid || scene.occluded_real(ls.ray)) return vec3(0);
    return ls.reflected;
}

}  // namespace dp
