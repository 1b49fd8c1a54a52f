#pragma once
// The principled material (principled.h) at a hit of a render scene: world-space sampling and
// evaluation for the renderers. Directions are in world space; `d` is the direction the path
// travels towards the surface, `wi` the direction it leaves in.
#include "assets/principled.h"
#include "assets/render_scene.h"
#include "assets/scattering.h"
#include "base/rng.h"

namespace dp {

/// The BSDF of a principled surface at `hit`: the base colour from its albedo or texture (at
/// hit.uv), the other parameters from its material (roughness and metallic times a file's
/// metallic-roughness texture, glTF's rule). Roughness is raised to kSpecularRoughness:
/// at 0.03 the lobes already reflect what a mirror or glass does within 1% (docs/materials.md),
/// and every renderer can then sample, evaluate and MIS-weight one model with no delta cases.
PrincipledBsdf principled_at(const Surface& surface, const Hit& hit);

/// A direction drawn at a principled surface.
struct PrincipledEvent {
    vec3 dir{0.0f};
    vec3 weight{0.0f};  ///< f |cos| / pdf; zero when nothing was drawn
    float pdf = 0.0f;
    bool transmitted = false;
};

/// Draws the direction a path arriving along `d` leaves in. Reflections that would leave
/// through the geometric surface (shading normals) and transmissions that would not cross it
/// are dropped (weight 0).
PrincipledEvent sample_principled(const PrincipledBsdf& bsdf, const Hit& hit, const vec3& d, const vec3& u,
                                  Transport mode);

/// f |cos theta_i| for a path arriving along `d` and leaving along `wi` (0 where the geometric
/// surface disagrees with the shading frame's side).
vec3 eval_principled(const PrincipledBsdf& bsdf, const Hit& hit, const vec3& d, const vec3& wi, Transport mode);

/// The density with which sample_principled draws `wi`.
float pdf_principled(const PrincipledBsdf& bsdf, const Hit& hit, const vec3& d, const vec3& wi);

/// The next direction at a virtual surface that is not diffuse: mirror and glass by
/// scatter_specular, principled by sample_principled (zero weight where nothing was drawn).
SpecularEvent scatter_non_diffuse(const Surface& surface, const Hit& hit, const vec3& d, Rng& rng, Transport mode);

/// Emitted radiance of a surface (a principled material's emission; zero otherwise).
inline vec3 emitted_radiance(const Surface& s) {
    return s.is_virtual && s.material.kind == Material::Kind::Principled ? s.material.principled.emission : vec3(0.0f);
}

}  // namespace dp
