#pragma once
#include "base/rng.h"
#include "assets/render_scene.h"

namespace dp {

/// Next-event estimation of the virtual lights at `hit`: one sample of each light, shadowed by
/// real and virtual geometry alike (glass too: the light it lets through is the photons'), each
/// weighted by `f(w)`, the BSDF times the cosine towards unit direction w (0 where the light
/// cannot be reflected). No MIS: nothing else adds the lights' light where this is used.
template <class F>
vec3 reflected_light(const RenderScene& scene, const Hit& hit, Rng& rng, F&& f) {
    const LightSet& lights = scene.lights();
    vec3 sum(0);
    for (size_t i = 0; i < lights.size(); ++i) {
        const vec2 u(rng.uniform(), rng.uniform());
        const LightSample ls = lights.sample(i, hit.p, u);
        if (ls.weight == vec3(0)) continue;
        const vec3 fw = f(ls.dir);
        if (fw == vec3(0)) continue;
        // Short of the light by a relative and a scene-scaled margin: an area light on a wall
        // lies on the wall, and must not be shadowed by it.
        const float tmax = ls.dist * (1 - 1e-4f) - scene.ray_epsilon();
        if (tmax <= 0 || scene.occluded(Ray{scene.offset_origin(hit, ls.dir), ls.dir}, tmax)) continue;
        sum += fw * ls.weight;
    }
    return is_finite(sum) ? sum : vec3(0);
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
