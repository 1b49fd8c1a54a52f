#include "assets/scattering.h"

#include <algorithm>
#include <cmath>

#include "base/sampling.h"

namespace dp {

float fresnel_dielectric(float cos_i, float eta) {
    cos_i = std::clamp(cos_i, 0.0f, 1.0f);
    float sin2_t = eta * eta * std::max(0.0f, 1 - cos_i * cos_i);
    if (sin2_t >= 1) return 1;
    float cos_t = std::sqrt(1 - sin2_t);
    float rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    float rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (rs * rs + rp * rp);
}

namespace {

struct Interface {
    vec3 n;      // normal on the incident side
    float eta;   // n_i / n_t
    float cos_i;
    bool entering;
};

Interface interface_at(const Material& m, const Hit& hit, const vec3& d) {
    Interface f;
    f.entering = glm::dot(d, hit.ns) < 0;
    f.n = f.entering ? hit.ns : -hit.ns;
    f.eta = f.entering ? 1.0f / m.ior : m.ior;
    f.cos_i = std::clamp(-glm::dot(d, f.n), 0.0f, 1.0f);
    return f;
}

vec3 refract_dir(const vec3& d, const Interface& f) {
    float sin2_t = f.eta * f.eta * std::max(0.0f, 1 - f.cos_i * f.cos_i);
    float cos_t = std::sqrt(std::max(0.0f, 1 - sin2_t));
    return glm::normalize(f.eta * d + (f.eta * f.cos_i - cos_t) * f.n);
}

// Tint is applied once per crossing, on the way in.
vec3 transmit_weight(const Material& m, const Interface& f) { return f.entering ? m.tint : vec3(1.0f); }

}  // namespace

SpecularEvent scatter_specular(const Material& m, const Hit& hit, const vec3& d, float u) {
    SpecularEvent e;
    if (m.kind == Material::Kind::Mirror) {
        e.dir = glm::normalize(reflect(d, facing_normal(hit.ns, d)));
        e.weight = m.reflectance;
        return e;
    }
    Interface f = interface_at(m, hit, d);
    float F = fresnel_dielectric(f.cos_i, f.eta);
    if (u < F) {
        e.dir = glm::normalize(reflect(d, f.n));
    } else {
        e.dir = refract_dir(d, f);
        e.weight = transmit_weight(m, f);
        e.transmitted = true;
    }
    return e;
}

void split_glass(const Material& m, const Hit& hit, const vec3& d, SpecularEvent& reflected,
                 SpecularEvent& refracted) {
    Interface f = interface_at(m, hit, d);
    float F = fresnel_dielectric(f.cos_i, f.eta);
    reflected.dir = glm::normalize(reflect(d, f.n));
    reflected.weight = vec3(F);
    reflected.transmitted = false;
    refracted.transmitted = true;
    if (F >= 1) {
        refracted.weight = vec3(0);
        refracted.dir = reflected.dir;
        return;
    }
    refracted.dir = refract_dir(d, f);
    refracted.weight = (1 - F) * transmit_weight(m, f);
}

vec3 sample_diffuse(const Hit& hit, const vec3& d, vec2 u) {
    vec3 n = facing_normal(hit.ns, d);
    // Keep the bounce on the geometric side the photon came from.
    vec3 local = sample_cosine_hemisphere(u);
    vec3 out = Frame(n).to_world(local);
    if (glm::dot(out, facing_normal(hit.ng, d)) <= 0) out = reflect(out, facing_normal(hit.ng, d));
    return glm::normalize(out);
}

}  // namespace dp
