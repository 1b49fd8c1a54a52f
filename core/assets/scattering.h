#pragma once
#include "base/math.h"
#include "base/rng.h"
#include "assets/render_scene.h"

namespace dp {

/// MIS power heuristic (beta = 2) of a strategy with pdf `a` against one with pdf `b`; 0 when
/// both are 0 (a direction neither strategy samples) rather than 0/0.
inline float power_heuristic(float a, float b) {
    const float a2 = a * a, sum = a2 + b * b;
    return sum > 0 ? a2 / sum : 0.0f;
}

/// Mirror reflection of incident direction `d` (travelling towards the surface) about `n`.
inline vec3 reflect(const vec3& d, const vec3& n) { return d - 2.0f * glm::dot(d, n) * n; }

/// Unpolarised Fresnel reflectance for a dielectric interface; `cos_i` > 0 measured on the side
/// the light arrives from, `eta` = n_incident / n_transmitted. Returns 1 on total internal
/// reflection.
float fresnel_dielectric(float cos_i, float eta);

/// The outcome of a specular interaction (mirror or glass).
struct SpecularEvent {
    vec3 dir;          ///< outgoing direction
    vec3 weight{1.0f}; ///< throughput multiplier (already divided by the choice probability)
    bool transmitted = false;
};

/// Picks reflection or refraction by Fresnel (Russian roulette on the choice, total internal
/// reflection included) for glass, plain reflection for a mirror. `d` is the incoming ray
/// direction and `hit.ng` the surface's outward normal.
SpecularEvent scatter_specular(const Material& m, const Hit& hit, const vec3& d, float u);

/// Both branches of a glass interface, for splitting: reflection weight and refraction weight
/// (zero weight for the refraction under total internal reflection).
void split_glass(const Material& m, const Hit& hit, const vec3& d, SpecularEvent& reflected,
                 SpecularEvent& refracted);

/// Cosine-weighted diffuse bounce off the side of `hit` that `d` arrives on.
vec3 sample_diffuse(const Hit& hit, const vec3& d, vec2 u);

/// Normal of the side of the surface facing against direction `d`.
inline vec3 facing_normal(const vec3& n, const vec3& d) { return glm::dot(n, d) < 0 ? n : -n; }

}  // namespace dp
