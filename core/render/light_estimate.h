#pragma once
#include "base/rng.h"
#include "assets/principled_scatter.h"
#include "assets/render_scene.h"
#include "assets/scattering.h"

namespace dp {

/// Next-event estimation of the virtual lights (lamps and emissive objects) at `hit`: one
/// sample of each light, shadowed by real and virtual geometry alike (glass too: the light it
/// lets through is the photons'), each weighted by `f(w)`, the BSDF times the cosine towards
/// unit direction w (0 where the light cannot be reflected). `bsdf_pdf(w)` is the density with
/// which the caller's BSDF sampling meets the light too (lights_seen counts that ray): the
/// power heuristic shares them. Return 0 from it where no BSDF-sampled ray counts the lights.
template <class F, class P>
vec3 reflected_light(const RenderScene& scene, const Hit& hit, Rng& rng, F&& f, P&& bsdf_pdf) {
    const LightSet& lights = scene.lights();
    vec3 sum(0);
    for (size_t i = 0; i < lights.size(); ++i) {
        const vec2 u(rng.uniform(), rng.uniform());
        const LightSample ls = lights.sample(i, hit.p, u);
        if (ls.weight == vec3(0)) continue;
        const vec3 fw = f(ls.dir);
        if (fw == vec3(0)) continue;
        // Short of the light by a relative and a scene-scaled margin: an area light on a wall
        // lies on the wall, and an emitter's own surface is where the sample lies.
        const float tmax = ls.dist * (1 - 1e-4f) - scene.ray_epsilon();
        if (tmax <= 0 || scene.occluded(Ray{scene.offset_origin(hit, ls.dir), ls.dir}, tmax)) continue;
        const float w = ls.pdf > 0 ? power_heuristic(ls.pdf, bsdf_pdf(ls.dir)) : 1.0f;
        sum += fw * ls.weight * w;
    }
    return is_finite(sum) ? sum : vec3(0);
}

/// reflected_light where no BSDF-sampled ray counts the lights (next-event estimation alone).
template <class F>
vec3 reflected_light(const RenderScene& scene, const Hit& hit, Rng& rng, F&& f) {
    return reflected_light(scene, hit, rng, std::forward<F>(f), [](const vec3&) { return 0.0f; });
}

/// What a BSDF-sampled ray (density `bsdf_pdf`) sees of the lights: a lamp's face before `hit`,
/// or `hit` itself where it is an emitter, weighted against reflected_light's samples by the
/// power heuristic. Together the two count each light once.
inline vec3 lights_seen(const RenderScene& scene, const Ray& ray, const Hit& hit, float bsdf_pdf) {
    const LightSet& lights = scene.lights();
    if (lights.empty()) return vec3(0);
    float t = 0, light_pdf = 0;
    const vec3 face = lights.emitted(ray, hit ? hit.t : INFINITY, &t, &light_pdf);
    if (face != vec3(0)) return face * power_heuristic(bsdf_pdf, light_pdf);
    if (!hit || !hit.surface->is_virtual) return vec3(0);
    const vec3 L = emitted_radiance(*hit.surface);
    if (L == vec3(0)) return vec3(0);
    const int e = lights.emitter_of(hit.surface->index);
    return L * power_heuristic(bsdf_pdf, lights.emitter_pdf(e, ray.org, ray.dir, hit.t, hit.ng));
}

/// The irradiance the virtual lights send to `hit` on the side of unit normal `n`.
inline vec3 light_irradiance(const RenderScene& scene, const Hit& hit, const vec3& n, Rng& rng) {
    if (scene.lights().empty()) return vec3(0);
    return reflected_light(scene, hit, rng, [&](const vec3& w) {
        // The geometric normal too: no light through the surface from behind.
        const float c = glm::dot(n, w);
        return c > 0 && glm::dot(hit.ng, w) * glm::dot(hit.ng, n) > 0 ? vec3(c) : vec3(0);
    });
}

}  // namespace dp
