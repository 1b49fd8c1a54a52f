#pragma once
// The glTF 2.0 metallic-roughness material (the spec's appendix B) with KHR_materials_ior,
// KHR_materials_specular and KHR_materials_transmission, as one BSDF for Monte Carlo transport:
//
//   f = mix(dielectric, conductor, metallic)
//   conductor  = GGX reflection with Schlick's Fresnel, F0 = base colour, plus the Kulla-Conty
//                multiple-scattering lobe (a white conductor keeps its energy at any roughness)
//   dielectric = GGX reflection with the exact dielectric Fresnel (its F0 scaled by the
//                specular colour and factor as KHR_materials_specular says)
//              + over what it does not reflect: mix(Lambert base colour, rough transmission
//                (Walter et al. 2007) tinted by the base colour, transmission)
//
// All directions are unit vectors in the local shading frame (z = normal; shading_frame()),
// both pointing away from the surface. The material is two-sided when opaque; with
// transmission > 0, wo.z < 0 means wo is inside (the relative index of refraction flips).
//
// Where this departs from the spec's formulas, and why (docs/materials.md has the figures):
// - the dielectric layer's Fresnel is fresnel_dielectric, not Schlick's, so that reflection and
//   transmission split the light exactly and total internal reflection happens;
// - the base under the layer is weighted by (1 - E(mu_o)) (1 - E(mu_i)) / (1 - E_avg), E the
//   layer's directional albedo (tabulated), instead of the spec's 1 - F(V.H): reciprocal, and
//   a white base under the layer keeps all the light the layer does not reflect (with the
//   spec's form a white plastic returns 1.57 of the light at 85 degrees, roughness 0.1; with
//   (1 - F(mu_o)) (1 - F(mu_i)) / (1 - F_avg) it returns 0.45 at roughness 1);
// - the specular factor and colour act on reflection only: transmission keeps 1 - F.
//
// Energy: a white conductor keeps 99.6-100.3% at every roughness (multiple-scattering lobe), a
// white base under the layer 100-100.5%. Rough transmission is not compensated: what one bounce
// off the microfacets loses stays lost. Reflection plus transmission of white glass (importance
// transport, at 2 / 60 / 85 degrees; PrincipledBsdf.DielectricEnergyIsMeasured):
//   roughness   from outside              from inside
//   0.1         1.000  1.000  0.994       1.000  1.000  0.992
//   0.3         0.999  0.994  0.922       0.991  0.970  0.867
//   0.6         0.983  0.934  0.894       0.860  0.740  0.764
//   1.0         0.893  0.741  0.751       0.417  0.512  0.514
// From inside, total internal reflection off steep microfacets sends light back into the
// surface, which single scattering drops.
#include "assets/microfacet.h"
#include "base/math.h"

namespace dp {

/// What the path that queries the BSDF carries: it decides the eta^2 factor of transmission.
enum class Transport {
    /// Camera paths: wo points towards the camera, wi towards the light. Radiance crossing
    /// into a denser medium grows by (n_t / n_i)^2, its cone compressed by refraction.
    Radiance,
    /// Light paths (photons carry flux, an importance-like quantity): wo points back towards
    /// the light, wi where the flux goes. The adjoint BSDF, f*(wo, wi) = f(wi, wo): flux is
    /// conserved through an interface, no eta^2.
    Importance,
};

/// glTF 2.0 metallic-roughness parameters plus KHR_materials_ior, _specular and _transmission.
/// Values are clamped to their ranges by PrincipledBsdf.
struct PrincipledParams {
    vec3 base_colour{0.8f};      ///< linear RGB in [0, 1]
    float metallic = 0.0f;       ///< [0, 1]
    float roughness = 0.5f;      ///< perceptual, [0, 1]; alpha = roughness^2
    float ior = 1.5f;            ///< KHR_materials_ior, clamped to [1.01, 5]
    float specular = 1.0f;       ///< KHR_materials_specular specularFactor, [0, 1]
    vec3 specular_colour{1.0f};  ///< KHR_materials_specular specularColorFactor, >= 0
    float transmission = 0.0f;   ///< KHR_materials_transmission transmissionFactor, [0, 1]
    vec3 emission{0.0f};         ///< emitted radiance (emissiveFactor x strength); not scattering
};

/// One direction drawn by PrincipledBsdf::sample.
struct BsdfSample {
    vec3 wi{0.0f};
    vec3 weight{0.0f};  ///< eval(wo, wi) / pdf(wo, wi): f |cos theta_i| / pdf
    float pdf = 0.0f;   ///< 0 when no direction was drawn (weight 0)
    bool transmitted = false;
    explicit operator bool() const { return pdf > 0; }
};

/// The local shading frame of a unit normal: z along n (to_local / to_world convert).
inline Frame shading_frame(const vec3& n) { return Frame(n); }

/// The principled BSDF of one set of parameters. Cheap to build (no allocation, two table
/// look-ups), so it can be made per shading point.
class PrincipledBsdf {
public:
    explicit PrincipledBsdf(const PrincipledParams& params);

    /// The clamped parameters.
    const PrincipledParams& params() const { return p_; }

    /// Emitted radiance, for the caller to add; the BSDF itself does not emit.
    const vec3& emission() const { return p_.emission; }

    /// f(wo, wi) |cos theta_i|; reflection when wo.z and wi.z have the same sign, transmission
    /// otherwise. Zero for grazing directions (z = 0).
    vec3 eval(const vec3& wo, const vec3& wi, Transport mode = Transport::Radiance) const;

    /// Solid-angle density with which sample() draws wi given wo. Independent of `mode`.
    float pdf(const vec3& wo, const vec3& wi) const;

    /// Draws wi: a lobe by its estimated albedo for wo (with u.z), then a direction in it (u.x,
    /// u.y). The weight is exactly eval(wo, wi, mode) / pdf(wo, wi) of the returned direction.
    BsdfSample sample(const vec3& wo, const vec3& u, Transport mode = Transport::Radiance) const;

private:
    struct Lobes {
        float cosine, interface, conductor;  // selection probabilities, sum 1 (or all 0)
    };
    Lobes lobe_probabilities(float cos_o, float eta) const;
    void interface_split(float fresnel, float& p_reflect, float& p_transmit) const;
    float layer_albedo(float cos_theta) const;
    vec3 layer_fresnel(float cos_om, float eta) const;
    vec3 cosine_lobe(float cos_o, float cos_i) const;
    vec3 eval_local(const vec3& wo, const vec3& wi, float eta, Transport mode) const;
    vec3 eval_transmission(const vec3& wo, const vec3& wi, float eta, Transport mode) const;
    float pdf_local(const vec3& wo, const vec3& wi, float eta) const;
    float eta_for(float wo_z) const;

    PrincipledParams p_;
    Ggx ggx_;
    float f0_;             // dielectric F0 from the IOR alone
    vec3 f0_layer_;        // min(f0 * specular colour, 1): the layer's F0 before the factor
    float f0_layer_max_;   // its largest component
    float albedo_avg_;        // E_avg(roughness) of the F = 1 lobe
    float layer_albedo_avg_;  // hemispherical average of layer_albedo
    vec3 multiscatter_;       // Kulla-Conty colour factor of the conductor's compensation lobe
    float reflect_strength_, transmit_strength_;  // the interface lobe's split, times F and 1 - F
};

}  // namespace dp
