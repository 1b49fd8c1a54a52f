#include "assets/principled_scatter.h"

#include <algorithm>

namespace dp {

namespace {

/// The same side of the geometric surface in local (shading) terms and in world terms: a
/// shading normal can put a direction on one side of the frame and the other of the triangle.
bool sides_agree(const Hit& hit, const vec3& d, const vec3& wi, bool transmitted) {
    const float a = glm::dot(-d, hit.ng), b = glm::dot(wi, hit.ng);
    return transmitted ? a * b < 0 : a * b > 0;
}

}  // namespace

PrincipledBsdf principled_at(const Surface& surface, const Hit& hit) {
    const Material& m = surface.material;
    PrincipledParams p;
    p.base_colour = surface.reflectance_at(hit.uv);
    p.metallic = m.principled.metallic;
    p.roughness = m.principled.roughness;
    if (surface.metallic_roughness && !surface.metallic_roughness->empty()) {
        // glTF: green scales roughness, blue metallic.
        const vec3 t = glm::clamp(texture_at(*surface.metallic_roughness, hit.uv), vec3(0.0f), vec3(1.0f));
        p.roughness *= t.y;
        p.metallic *= t.z;
    }
    p.roughness = std::max(p.roughness, kSpecularRoughness);
    p.ior = m.principled.ior;
    p.specular = m.principled.specular;
    p.transmission = m.principled.transmission;
    p.emission = m.principled.emission;
    return PrincipledBsdf(p);
}

PrincipledEvent sample_principled(const PrincipledBsdf& bsdf, const Hit& hit, const vec3& d, const vec3& u,
                                  Transport mode) {
    const Frame frame = shading_frame(hit.ns);
    const BsdfSample s = bsdf.sample(frame.to_local(-d), u, mode);
    PrincipledEvent e;
    if (!s) return e;
    e.dir = glm::normalize(frame.to_world(s.wi));
    e.transmitted = s.transmitted;
    if (!sides_agree(hit, d, e.dir, s.transmitted) || !is_finite(s.weight)) return e;
    e.weight = s.weight;
    e.pdf = s.pdf;
    return e;
}

vec3 eval_principled(const PrincipledBsdf& bsdf, const Hit& hit, const vec3& d, const vec3& wi, Transport mode) {
    const Frame frame = shading_frame(hit.ns);
    const vec3 wo = frame.to_local(-d), wl = frame.to_local(wi);
    if (!sides_agree(hit, d, wi, wo.z * wl.z < 0)) return vec3(0.0f);
    const vec3 f = bsdf.eval(wo, wl, mode);
    return is_finite(f) ? f : vec3(0.0f);
}

float pdf_principled(const PrincipledBsdf& bsdf, const Hit& hit, const vec3& d, const vec3& wi) {
    const Frame frame = shading_frame(hit.ns);
    return bsdf.pdf(frame.to_local(-d), frame.to_local(wi));
}

SpecularEvent scatter_non_diffuse(const Surface& surface, const Hit& hit, const vec3& d, Rng& rng, Transport mode) {
    if (surface.material.kind != Material::Kind::Principled)
        return scatter_specular(surface.material, hit, d, rng.uniform());
    const vec3 u(rng.uniform(), rng.uniform(), rng.uniform());
    const PrincipledEvent e = sample_principled(principled_at(surface, hit), hit, d, u, mode);
    SpecularEvent out;
    out.dir = e.pdf > 0 ? e.dir : -d;
    out.weight = e.weight;
    out.transmitted = e.transmitted;
    return out;
}

}  // namespace dp
