#pragma once
// Isotropic GGX (Trowbridge-Reitz) microfacet distribution, Smith masking-shadowing, visible
// normal sampling and the Fresnel terms the principled material uses. Everything works in a
// local shading frame whose z axis is the surface normal (see Frame in base/math.h).
#include "base/math.h"

namespace dp {

/// The smallest alpha the distribution takes: keeps D finite in floats.
inline constexpr float kMinGgxAlpha = 1e-4f;

/// Below this roughness (alpha = roughness^2 < 9e-4) GGX's peak is too narrow to meet by chance
/// or to evaluate accurately in floats; the renderers raise a principled roughness to it
/// (principled_at), where the lobes already reflect what a mirror or glass does within 1%.
inline constexpr float kSpecularRoughness = 0.03f;

/// glTF's convention: alpha = roughness^2, clamped to kMinGgxAlpha.
float ggx_alpha(float roughness);

/// Isotropic Trowbridge-Reitz distribution of microfacet normals, with Smith's height-correlated
/// masking-shadowing (Heitz 2014). Directions are unit vectors in the local frame (z = normal).
class Ggx {
public:
    explicit Ggx(float alpha);
    float alpha() const { return alpha_; }

    /// D(m): density of microfacet normals per unit solid angle, normalised so that
    /// \f$\int D(m)\, m_z\, dm = 1\f$. Zero for m below the horizon.
    float D(const vec3& m) const;

    /// Smith's Lambda(w): the masking function is G1 = 1 / (1 + Lambda). Infinite at grazing.
    float lambda(const vec3& w) const;

    /// Masking of direction w (either hemisphere: depends on |w.z| only).
    float G1(const vec3& w) const { return 1.0f / (1.0f + lambda(w)); }

    /// Height-correlated masking-shadowing of the pair (wo, wi), for reflection and
    /// transmission alike.
    float G2(const vec3& wo, const vec3& wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }

    /// Density of the normals visible from w (w.z > 0): G1(w) max(0, w.m) D(m) / w.z. It
    /// integrates to 1 over the sphere of m.
    float visible_pdf(const vec3& w, const vec3& m) const;

    /// A normal distributed by visible_pdf(w, .) (w.z > 0), by the spherical-cap construction
    /// of Dupuy & Benyoub 2023: uniform on a cap of the sphere in the stretched
    /// (alpha = 1) configuration, then unstretched.
    vec3 sample_visible(const vec3& w, vec2 u) const;

private:
    float alpha_;
};

/// Mirror direction of w about the unit normal m (both pointing away from the surface).
inline vec3 reflect_about(const vec3& w, const vec3& m) { return 2.0f * glm::dot(w, m) * m - w; }

/// Refraction of w (on the side of m: w.m > 0) through a microfacet with normal m, where
/// `eta` = n_transmitted / n_incident. False on total internal reflection.
bool refract_about(const vec3& w, const vec3& m, float eta, vec3& wt);

/// (1 - cos)^5, Schlick's weight.
inline float schlick_weight(float cos_theta) {
    const float c = glm::clamp(1.0f - cos_theta, 0.0f, 1.0f), c2 = c * c;
    return c2 * c2 * c;
}

/// Schlick's Fresnel from the colour at normal incidence (glTF's metal: f0 = base colour).
inline vec3 fresnel_schlick(const vec3& f0, float cos_theta) {
    return f0 + (vec3(1.0f) - f0) * schlick_weight(cos_theta);
}

/// Reflectance at normal incidence of a dielectric of index `ior` in air: ((ior-1)/(ior+1))^2.
inline float dielectric_f0(float ior) {
    const float r = (ior - 1) / (ior + 1);
    return r * r;
}

}  // namespace dp
