#include "assets/real_gloss.h"

#include <algorithm>
#include <cmath>

#include "assets/scattering.h"

namespace dp {

GlossLobe::GlossLobe(const Hit& hit, const vec3& dir)
    : frame_(facing_normal(hit.ns, dir)), ggx_(hit.surface ? std::max(hit.surface->gloss_alpha, kMinGgxAlpha) : 1.0f) {
    if (!hit.surface || hit.surface->is_virtual || hit.surface->gloss_f0 <= 0) return;
    f0_ = hit.surface->gloss_f0;
    ng_ = facing_normal(hit.ng, dir);
    wo_ = frame_.to_local(-dir);
    valid_ = wo_.z > 1e-6f;
}

float GlossLobe::eval_cos(const vec3& wi_world) const {
    if (!valid_ || glm::dot(wi_world, ng_) <= 0) return 0;
    const vec3 wi = frame_.to_local(wi_world);
    if (wi.z <= 0) return 0;
    const vec3 m = glm::normalize(wo_ + wi);
    const float F = f0_ + (1 - f0_) * schlick_weight(glm::dot(wo_, m));
    return F * ggx_.D(m) * ggx_.G2(wo_, wi) / (4 * wo_.z);
}

bool GlossLobe::sample(const vec2& u, vec3& wi_world, float& weight) const {
    if (!valid_) return false;
    const vec3 m = ggx_.sample_visible(wo_, u);
    const vec3 wi = reflect_about(wo_, m);
    if (wi.z <= 0) return false;
    wi_world = frame_.to_world(wi);
    if (glm::dot(wi_world, ng_) <= 0) return false;
    // f cos / pdf with pdf = D_visible / (4 wo.m): F G2 / G1(wo).
    const float F = f0_ + (1 - f0_) * schlick_weight(glm::dot(wo_, m));
    weight = F * ggx_.G2(wo_, wi) / ggx_.G1(wo_);
    return std::isfinite(weight) && weight > 0;
}

float GlossLobe::pdf(const vec3& wi_world) const {
    if (!valid_) return 0;
    const vec3 wi = frame_.to_local(wi_world);
    if (wi.z <= 0) return 0;
    const vec3 m = glm::normalize(wo_ + wi);
    const float c = glm::dot(wo_, m);
    return c > 0 ? ggx_.visible_pdf(wo_, m) / (4 * c) : 0.0f;
}

float GlossLobe::cone_half_angle() const {
    return std::min(kPi, 2 * std::atan(10 * ggx_.alpha()));
}

GlossySurface::GlossySurface(const Hit& hit, const vec3& dir) : lobe_(hit, dir), facing_(hit) {
    rho_ = hit.surface->reflectance_at(hit.uv);
    facing_.ng = facing_normal(hit.ng, dir);
    facing_.ns = facing_normal(hit.ns, dir);
}

vec3 GlossySurface::eval_cos(const vec3& w) const {
    const float c = glm::dot(facing_.ns, w);
    if (c <= 0 || glm::dot(facing_.ng, w) <= 0) return vec3(0);
    return rho_ * (c * kInvPi) + vec3(lobe_.eval_cos(w));
}

float GlossySurface::pdf(const vec3& w) const {
    return 0.5f * std::max(0.0f, glm::dot(facing_.ns, w)) * kInvPi + 0.5f * lobe_.pdf(w);
}

bool GlossySurface::sample(float pick, const vec2& u, vec3& w) const {
    float unused = 0;
    if (pick < 0.5f) return lobe_.sample(u, w, unused);
    w = sample_diffuse(facing_, -facing_.ng, u);
    return true;
}

bool gloss_may_reflect(const GlossLobe& lobe, const vec3& p, const vec3& c, float R) {
    if (!lobe.valid()) return false;
    const vec3 to = c - p;
    const float d = glm::length(to);
    if (d <= R) return true;
    const float angle = std::acos(std::clamp(glm::dot(lobe.mirror(), to / d), -1.0f, 1.0f));
    return angle - std::asin(std::min(1.0f, R / d)) < lobe.cone_half_angle();
}

}  // namespace dp
