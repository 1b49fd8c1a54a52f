#include "assets/principled.h"

#include <algorithm>

#include "assets/microfacet.h"
#include "assets/microfacet_albedo.h"
#include "assets/scattering.h"
#include "base/sampling.h"

namespace dp {

namespace {

float mean(const vec3& v) { return (v.x + v.y + v.z) / 3; }
float max_component(const vec3& v) { return std::max({v.x, v.y, v.z}); }

PrincipledParams clamped(PrincipledParams p) {
    p.base_colour = glm::clamp(p.base_colour, vec3(0.0f), vec3(1.0f));
    p.metallic = std::clamp(p.metallic, 0.0f, 1.0f);
    p.roughness = std::clamp(p.roughness, 0.0f, 1.0f);
    // Index 1 would make the refracted direction independent of the microfacet (a delta).
    p.ior = std::clamp(p.ior, 1.01f, 5.0f);
    p.specular = std::clamp(p.specular, 0.0f, 1.0f);
    p.specular_colour = glm::max(p.specular_colour, vec3(0.0f));
    p.transmission = std::clamp(p.transmission, 0.0f, 1.0f);
    return p;
}

// The refraction half vector (Walter et al. 2007), on the side of the normal; eta is
// n(wi's side) / n(wo's side). False where it is undefined.
bool transmission_half_vector(const vec3& wo, const vec3& wi, float eta, vec3& m) {
    const vec3 h = wo + eta * wi;
    const float len = glm::length(h);
    if (!(len > 0)) return false;
    m = h.z < 0 ? -h / len : h / len;
    return true;
}

}  // namespace

PrincipledBsdf::PrincipledBsdf(const PrincipledParams& params)
    : p_(clamped(params)), ggx_(ggx_alpha(p_.roughness)) {
    f0_ = dielectric_f0(p_.ior);
    f0_layer_ = glm::min(f0_ * p_.specular_colour, vec3(1.0f));
    f0_layer_max_ = max_component(f0_layer_);
    albedo_avg_ = ggx_average_albedo(p_.roughness);
    layer_albedo_avg_ = p_.specular * (f0_layer_max_ * albedo_avg_ + (1 - f0_layer_max_) *
                                                                   ggx_dielectric_average_albedo(p_.roughness, p_.ior));
    // Kulla & Conty 2017: the compensation lobe's colour, a geometric series of bounces each
    // keeping the average Fresnel (Schlick's average: f0 + (1 - f0) / 21).
    const vec3 f_avg = p_.base_colour + (vec3(1.0f) - p_.base_colour) / 21.0f;
    multiscatter_ = f_avg * f_avg * albedo_avg_ / (vec3(1.0f) - f_avg * (1 - albedo_avg_));
    // What the interface's reflection carries relative to F (more with a brighter specular
    // colour), and what its transmission carries relative to 1 - F.
    reflect_strength_ = p_.specular * std::max(1.0f, f0_layer_max_ / f0_);
    transmit_strength_ = p_.transmission * mean(p_.base_colour);
}

float PrincipledBsdf::eta_for(float wo_z) const {
    return p_.transmission > 0 && wo_z < 0 ? 1 / p_.ior : p_.ior;
}

// KHR_materials_specular's layer Fresnel with the exact dielectric curve in place of Schlick's
// weight: s * (F0' + (1 - F0') w), w rising from 0 at normal incidence to 1 at grazing or TIR.
vec3 PrincipledBsdf::layer_fresnel(float cos_om, float eta) const {
    const float w = std::clamp((fresnel_dielectric(cos_om, 1 / eta) - f0_) / (1 - f0_), 0.0f, 1.0f);
    return p_.specular * (f0_layer_ + (vec3(1.0f) - f0_layer_) * w);
}

// What the dielectric layer reflects at this angle, its strongest channel, seen from outside:
// the base below receives the rest.
float PrincipledBsdf::layer_albedo(float cos_theta) const {
    return p_.specular * (f0_layer_max_ * ggx_albedo(cos_theta, p_.roughness) +
                          (1 - f0_layer_max_) * ggx_dielectric_albedo(cos_theta, p_.roughness, p_.ior));
}

// Lambert under the layer plus the conductor's multiple scattering: both are products of a
// function of mu_o and the same function of mu_i, hence reciprocal, and cosine-sampled.
vec3 PrincipledBsdf::cosine_lobe(float cos_o, float cos_i) const {
    vec3 f(0.0f);
    const float diffuse = (1 - p_.metallic) * (1 - p_.transmission);
    if (diffuse > 0 && layer_albedo_avg_ < 1 - 1e-6f) {
        f += diffuse * kInvPi * p_.base_colour * (1 - layer_albedo(cos_o)) * (1 - layer_albedo(cos_i)) /
             (1 - layer_albedo_avg_);
    }
    if (p_.metallic > 0 && albedo_avg_ < 1 - 1e-6f) {
        const float e_o = ggx_albedo(cos_o, p_.roughness), e_i = ggx_albedo(cos_i, p_.roughness);
        f += p_.metallic * kInvPi * multiscatter_ * (1 - e_o) * (1 - e_i) / (1 - albedo_avg_);
    }
    return f;
}

// The interface lobe reflects or refracts in proportion to what each carries.
void PrincipledBsdf::interface_split(float fresnel, float& p_reflect, float& p_transmit) const {
    const float r = reflect_strength_ * fresnel, t = transmit_strength_ * (1 - fresnel);
    if (!(r + t > 0)) {
        p_reflect = p_transmit = 0;
        return;
    }
    p_reflect = r / (r + t);
    p_transmit = t / (r + t);
}

// Each lobe by its albedo estimated at cos_o; a lobe that can be non-zero always has a
// positive share (the conductor's floor covers a black metal's Fresnel edge).
PrincipledBsdf::Lobes PrincipledBsdf::lobe_probabilities(float cos_o, float eta) const {
    const float m = p_.metallic, e_o = ggx_albedo(cos_o, p_.roughness);
    const float cosine = (1 - m) * (1 - p_.transmission) * mean(p_.base_colour) * (1 - layer_albedo(cos_o)) +
                         m * mean(multiscatter_) * (1 - e_o);
    const float fresnel = fresnel_dielectric(cos_o, 1 / eta);
    const float iface = (1 - m) * (reflect_strength_ * fresnel + transmit_strength_ * (1 - fresnel));
    const float conductor = m * std::max(mean(fresnel_schlick(p_.base_colour, cos_o)), 0.05f) * e_o;
    const float sum = cosine + iface + conductor;
    if (!(sum > 0)) return {0, 0, 0};
    return {cosine / sum, iface / sum, conductor / sum};
}

vec3 PrincipledBsdf::eval_transmission(const vec3& wo, const vec3& wi, float eta, Transport mode) const {
    const float weight = (1 - p_.metallic) * p_.transmission;
    vec3 m;
    if (!(weight > 0) || !transmission_half_vector(wo, wi, eta, m)) return vec3(0.0f);
    const float cos_om = glm::dot(wo, m), cos_im = glm::dot(wi, m);
    if (cos_om <= 0 || cos_im >= 0) return vec3(0.0f);  // a microfacet seen from behind
    const float fresnel = fresnel_dielectric(cos_om, 1 / eta);
    const float denom = cos_im + cos_om / eta;
    float ft = ggx_.D(m) * ggx_.G2(wo, wi) * (1 - fresnel) * -cos_im * cos_om / (wo.z * -wi.z * denom * denom);
    // Radiance entering a denser medium is compressed into a narrower cone.
    if (mode == Transport::Radiance) ft /= eta * eta;
    return weight * p_.base_colour * ft * -wi.z;
}

// wo.z > 0 here; eta = n(other side) / n(wo's side).
vec3 PrincipledBsdf::eval_local(const vec3& wo, const vec3& wi, float eta, Transport mode) const {
    if (wi.z < 0) return eval_transmission(wo, wi, eta, mode);
    if (wi.z == 0) return vec3(0.0f);
    vec3 f = cosine_lobe(wo.z, wi.z);
    const vec3 m = glm::normalize(wo + wi);
    const float cos_om = glm::dot(wo, m);
    const float spec = ggx_.D(m) * ggx_.G2(wo, wi) / (4 * wo.z * wi.z);
    if (p_.metallic < 1 && p_.specular > 0) f += (1 - p_.metallic) * spec * layer_fresnel(cos_om, eta);
    if (p_.metallic > 0) f += p_.metallic * spec * fresnel_schlick(p_.base_colour, cos_om);
    return f * wi.z;
}

float PrincipledBsdf::pdf_local(const vec3& wo, const vec3& wi, float eta) const {
    const Lobes lobes = lobe_probabilities(wo.z, eta);
    if (wi.z > 0) {
        const vec3 m = glm::normalize(wo + wi);
        const float cos_om = glm::dot(wo, m);
        const float reflect = ggx_.visible_pdf(wo, m) / (4 * cos_om);  // dm/dwi = 1 / (4 wo.m)
        float p = lobes.cosine * wi.z * kInvPi + lobes.conductor * reflect;
        if (lobes.interface > 0) {
            float pr, pt;
            interface_split(fresnel_dielectric(cos_om, 1 / eta), pr, pt);
            p += lobes.interface * pr * reflect;
        }
        return p;
    }
    vec3 m;
    if (!(wi.z < 0) || !(lobes.interface > 0) || !transmission_half_vector(wo, wi, eta, m)) return 0;
    const float cos_om = glm::dot(wo, m), cos_im = glm::dot(wi, m);
    if (cos_om <= 0 || cos_im >= 0) return 0;
    float pr, pt;
    interface_split(fresnel_dielectric(cos_om, 1 / eta), pr, pt);
    const float denom = cos_im + cos_om / eta;
    return lobes.interface * pt * ggx_.visible_pdf(wo, m) * -cos_im / (denom * denom);
}

vec3 PrincipledBsdf::eval(const vec3& wo, const vec3& wi, Transport mode) const {
    if (wo.z == 0) return vec3(0.0f);
    const bool flip = wo.z < 0;
    return eval_local(flip ? -wo : wo, flip ? -wi : wi, eta_for(wo.z), mode);
}

float PrincipledBsdf::pdf(const vec3& wo, const vec3& wi) const {
    if (wo.z == 0) return 0;
    const bool flip = wo.z < 0;
    return pdf_local(flip ? -wo : wo, flip ? -wi : wi, eta_for(wo.z));
}

BsdfSample PrincipledBsdf::sample(const vec3& wo_given, const vec3& u, Transport mode) const {
    if (wo_given.z == 0) return {};
    const bool flip = wo_given.z < 0;  // work on wo's side, as eval and pdf do
    const vec3 wo = flip ? -wo_given : wo_given;
    const float eta = eta_for(wo_given.z);
    const Lobes lobes = lobe_probabilities(wo.z, eta);
    if (!(lobes.cosine + lobes.interface + lobes.conductor > 0)) return {};

    vec3 wi;
    bool refracted = false;
    if (u.z < lobes.cosine) {
        wi = sample_cosine_hemisphere(vec2(u.x, u.y));
    } else if (u.z < lobes.cosine + lobes.interface) {
        const vec3 m = ggx_.sample_visible(wo, vec2(u.x, u.y));
        float pr, pt;
        interface_split(fresnel_dielectric(glm::dot(wo, m), 1 / eta), pr, pt);
        // The lobe's stretch of u.z, reused for the reflect-or-refract choice.
        const float u_choice = (u.z - lobes.cosine) / lobes.interface;
        if (u_choice < pr) {
            wi = reflect_about(wo, m);
        } else {
            if (!(pt > 0) || !refract_about(wo, m, eta, wi)) return {};
            refracted = true;
        }
    } else {
        wi = reflect_about(wo, ggx_.sample_visible(wo, vec2(u.x, u.y)));
    }
    // A reflection that leaves below the horizon (or a refraction above it) is no sample.
    if (refracted ? !(wi.z < 0) : !(wi.z > 0)) return {};

    BsdfSample s;
    s.pdf = pdf_local(wo, wi, eta);
    if (!(s.pdf > 0)) return {};
    s.weight = eval_local(wo, wi, eta, mode) / s.pdf;
    s.wi = flip ? -wi : wi;
    s.transmitted = refracted;
    return s;
}

}  // namespace dp
