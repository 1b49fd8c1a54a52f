#include "assets/microfacet.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dp {

float ggx_alpha(float roughness) {
    const float r = std::clamp(roughness, 0.0f, 1.0f);
    return std::max(r * r, kMinGgxAlpha);
}

Ggx::Ggx(float alpha) : alpha_(std::clamp(alpha, kMinGgxAlpha, 1.0f)) {}

float Ggx::D(const vec3& m) const {
    if (m.z <= 0) return 0;
    // 1 - cos^2 written as x^2 + y^2: no cancellation near the peak, where alpha is small.
    const float a2 = alpha_ * alpha_;
    const float t = m.x * m.x + m.y * m.y + a2 * m.z * m.z;
    return a2 / (kPi * t * t);
}

float Ggx::lambda(const vec3& w) const {
    const float z2 = w.z * w.z;
    if (z2 == 0) return std::numeric_limits<float>::infinity();
    // (sqrt(1 + x) - 1) / 2 with x = alpha^2 tan^2: the quotient form keeps small x accurate.
    const float x = alpha_ * alpha_ * (w.x * w.x + w.y * w.y) / z2;
    return x / (2.0f * (1.0f + std::sqrt(1.0f + x)));
}

float Ggx::visible_pdf(const vec3& w, const vec3& m) const {
    const float cos_wm = glm::dot(w, m);
    if (w.z <= 0 || cos_wm <= 0) return 0;
    return G1(w) * cos_wm * D(m) / w.z;
}

vec3 Ggx::sample_visible(const vec3& w, vec2 u) const {
    // Stretched to alpha = 1, the visible normals are c + wh with c uniform on the spherical
    // cap z >= -wh.z of the unit sphere.
    const vec3 wh = glm::normalize(vec3(alpha_ * w.x, alpha_ * w.y, w.z));
    const float phi = 2 * kPi * u.x;
    const float z = (1 - u.y) * (1 + wh.z) - wh.z;
    const float s = std::sqrt(std::max(0.0f, 1 - z * z));
    const vec3 h = vec3(s * std::cos(phi), s * std::sin(phi), z) + wh;
    return glm::normalize(vec3(alpha_ * h.x, alpha_ * h.y, std::max(h.z, 1e-7f)));
}

bool refract_about(const vec3& w, const vec3& m, float eta, vec3& wt) {
    const float cos_i = glm::dot(w, m);
    const float sin2_t = std::max(0.0f, 1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return false;
    const float cos_t = std::sqrt(1 - sin2_t);
    wt = glm::normalize(-w / eta + (cos_i / eta - cos_t) * m);
    return true;
}

}  // namespace dp
