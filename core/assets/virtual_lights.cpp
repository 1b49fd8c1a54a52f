#include "assets/virtual_lights.h"

#include <algorithm>
#include <cmath>

#include "base/euler.h"
#include "base/sampling.h"

namespace dp {

namespace {

using Kind = VirtualLight::Kind;

PlacedLight place(const VirtualLight& l, int index) {
    PlacedLight p;
    p.kind = l.kind;
    p.index = index;
    p.position = l.transform.translation;
    // Rotation only: a light's scale stretches its face, never its direction.
    const glm::mat3 R = euler_xyz_deg(l.transform.rotation_deg);
    p.axis = glm::normalize(R * vec3(0, -1, 0));
    const vec3 colour = glm::max(l.colour, vec3(0.0f));
    const double power = std::max(0.0f, l.power_w);
    switch (l.kind) {
        case Kind::Point:
        case Kind::Spot: {
            // Blender's convention: a spot shines as the point of the same power, cut to its cone.
            p.intensity = colour * float(power / (4.0 * kPi));
            double solid_angle = 4.0 * kPi;
            if (l.kind == Kind::Spot) {
                const double half = 0.5 * double(std::clamp(l.spot_angle_deg, 1e-3f, 180.0f)) * kPi / 180.0;
                p.cos_half = float(std::cos(half));
                const double edge = (1.0 - p.cos_half) * std::clamp(l.spot_blend, 0.0f, 1.0f);
                p.smooth = edge > 0 ? float(1.0 / edge) : 0.0f;
                solid_angle = 2.0 * kPi * (1.0 - p.cos_half);
            }
            p.power = luminance(dvec3(p.intensity)) * solid_angle;
            break;
        }
        case Kind::Rect:
        case Kind::Disk: {
            const float sx = l.size.x * l.transform.scale.x;
            const float sz = (l.kind == Kind::Disk ? l.size.x : l.size.y) * l.transform.scale.z;
            p.u = R * vec3(1, 0, 0) * (0.5f * sx);
            p.v = R * vec3(0, 0, 1) * (0.5f * sz);
            p.area = l.kind == Kind::Rect ? sx * sz : 0.25f * kPi * sx * sz;
            p.visible = l.visible;
            if (p.area > 0 && std::isfinite(p.area)) p.radiance = colour * float(power / (kPi * double(p.area)));
            p.power = luminance(dvec3(p.radiance)) * kPi * double(p.area);
            break;
        }
    }
    if (!std::isfinite(p.power)) p.power = 0;
    return p;
}

/// A point of an area light's face from two uniform numbers, uniform by area.
vec3 point_on_face(const PlacedLight& l, const vec2& u) {
    if (l.kind == Kind::Rect) return l.position + (2 * u.x - 1) * l.u + (2 * u.y - 1) * l.v;
    const vec2 d = sample_concentric_disk(u);
    return l.position + d.x * l.u + d.y * l.v;
}

/// Radius of the sphere around an area light's face.
float face_radius(const PlacedLight& l) {
    return l.kind == Kind::Rect ? glm::length(l.u + l.v) : std::max(glm::length(l.u), glm::length(l.v));
}

}  // namespace

float PlacedLight::spot_falloff(const vec3& w) const {
    if (kind != Kind::Spot) return 1.0f;
    const float c = glm::dot(w, axis);
    if (c <= cos_half) return 0.0f;
    if (smooth <= 0) return 1.0f;
    const float x = std::min(1.0f, (c - cos_half) * smooth);
    return x * x * (3 - 2 * x);
}

LightSet::LightSet(const std::vector<VirtualLight>& lights, std::vector<EmissiveShape> emitters)
    : emitters_(std::move(emitters)) {
    std::vector<double> power;
    for (size_t i = 0; i < lights.size(); ++i) {
        lights_.push_back(place(lights[i], int(i)));
        power.push_back(lights_.back().power);
    }
    for (size_t k = 0; k < emitters_.size(); ++k) {
        power.push_back(emitters_[k].power);
        const size_t object = size_t(std::max(0, emitters_[k].object));
        if (emitter_of_.size() <= object) emitter_of_.resize(object + 1, -1);
        emitter_of_[object] = int(k);
    }
    table_ = AliasTable(power);
}

namespace {

/// A point uniform on the emitter's surface, its unit outward normal, from three numbers.
void point_on_emitter(const EmissiveShape& e, double u0, const vec2& u, vec3& p, vec3& n) {
    if (!e.mesh) {
        n = sample_uniform_sphere(u);
        p = e.center + e.radius * n;
        return;
    }
    const size_t k = e.by_area.sample(u0);
    const glm::uvec3 t = e.mesh->triangles[e.triangles[k]];
    const vec3 &a = e.mesh->positions[t.x], &b = e.mesh->positions[t.y], &c = e.mesh->positions[t.z];
    const float su = std::sqrt(u.x);
    p = a * (1 - su) + b * (su * (1 - u.y)) + c * (su * u.y);
    n = glm::normalize(glm::cross(b - a, c - a));
}

}  // namespace

/// The cone of directions from x that meets sphere (c, R), when x is outside it.
bool sphere_cone(const vec3& x, const vec3& c, float R, float& cos_max, float& solid_angle) {
    const vec3 to = c - x;
    const float d2 = glm::dot(to, to);
    if (!(d2 > R * R * 1.0001f)) return false;
    cos_max = std::sqrt(std::max(0.0f, 1 - R * R / d2));
    solid_angle = 2 * kPi * (1 - cos_max);
    return solid_angle > 0;
}

LightSample LightSet::sample_emitter(const EmissiveShape& e, const vec3& x, const vec2& u) const {
    LightSample s;
    float cos_max = 0, solid_angle = 0;
    if (!e.mesh && sphere_cone(x, e.center, e.radius, cos_max, solid_angle)) {
        // A sphere by the cone it fills: every sample meets its near side.
        const vec3 axis = glm::normalize(e.center - x);
        const float cos_t = 1 - u.x * (1 - cos_max), sin_t = std::sqrt(std::max(0.0f, 1 - cos_t * cos_t));
        const float phi = 2 * kPi * u.y;
        s.dir = Frame(axis).to_world(vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t));
        const vec3 oc = x - e.center;
        const float b = glm::dot(oc, s.dir), cc = glm::dot(oc, oc) - e.radius * e.radius;
        s.dist = -b - std::sqrt(std::max(0.0f, b * b - cc));
        s.weight = e.radiance * solid_angle;
        s.pdf = 1 / solid_angle;
        return s;
    }
    // The triangle from the first number, rescaled, the point from it and the second.
    double u0 = u.x;
    float ux = u.x;
    if (e.mesh) {
        double rest = 0;
        e.by_area.sample(u0, &rest);
        ux = float(rest);
    }
    vec3 p, n;
    point_on_emitter(e, u0, vec2(ux, u.y), p, n);
    const vec3 to = p - x;
    const float d2 = glm::dot(to, to);
    if (!(d2 > 0) || !std::isfinite(d2)) return s;
    s.dist = std::sqrt(d2);
    s.dir = to / s.dist;
    // Both sides emit, as the camera sees them (a closed shape's inner side is hidden anyway).
    const float cos_l = std::abs(glm::dot(s.dir, n));
    if (cos_l <= 0) return s;
    s.weight = e.radiance * float(double(cos_l) * e.area / d2);
    s.pdf = float(d2 / (double(cos_l) * e.area));
    return s;
}

float LightSet::emitter_pdf(int e, const vec3& origin, const vec3& dir, float t, const vec3& ng) const {
    if (e < 0 || size_t(e) >= emitters_.size()) return 0;
    const EmissiveShape& shape = emitters_[size_t(e)];
    float cos_max = 0, solid_angle = 0;
    if (!shape.mesh && sphere_cone(origin, shape.center, shape.radius, cos_max, solid_angle)) return 1 / solid_angle;
    const float c = std::abs(glm::dot(dir, ng));
    return c > 0 ? float(double(t) * t / (double(c) * emitters_[size_t(e)].area)) : 0.0f;
}

LightSample LightSet::sample(size_t i, const vec3& x, const vec2& u) const {
    if (i >= lights_.size()) return sample_emitter(emitters_[i - lights_.size()], x, u);
    const PlacedLight& l = lights_[i];
    LightSample s;
    if (l.power <= 0) return s;
    const vec3 p = l.is_area() ? point_on_face(l, u) : l.position;
    const vec3 to = p - x;
    const float d2 = glm::dot(to, to);
    if (!(d2 > 0) || !std::isfinite(d2)) return s;
    s.dist = std::sqrt(d2);
    s.dir = to / s.dist;
    if (!l.is_area()) {
        s.weight = l.intensity * (l.spot_falloff(-s.dir) / d2);
        return s;
    }
    const float cos_l = -glm::dot(s.dir, l.axis);
    if (cos_l <= 0) return s;
    s.weight = l.radiance * (cos_l * l.area / d2);  // radiance over the solid-angle density
    s.pdf = d2 / (cos_l * l.area);
    return s;
}

vec3 LightSet::emitted(const Ray& ray, float tmax, float* t_out, float* pdf) const {
    vec3 L(0);
    float best = tmax;
    if (pdf) *pdf = 0;
    for (const PlacedLight& l : lights_) {
        if (!l.is_area() || !l.visible || l.power <= 0) continue;
        const float denom = glm::dot(ray.dir, l.axis);
        if (denom >= 0) continue;  // its back, or edge-on: a light's back is not seen
        const float t = glm::dot(l.position - ray.org, l.axis) / denom;
        if (!(t > 0) || t >= best) continue;
        const vec3 q = ray.org + t * ray.dir - l.position;
        const float a = glm::dot(q, l.u) / glm::dot(l.u, l.u), b = glm::dot(q, l.v) / glm::dot(l.v, l.v);
        const bool inside = l.kind == Kind::Rect ? std::abs(a) <= 1 && std::abs(b) <= 1 : a * a + b * b <= 1;
        if (!inside) continue;
        best = t;
        L = l.radiance;
        if (pdf) *pdf = t * t / (-denom * l.area);
    }
    if (t_out) *t_out = best;
    return L;
}

LightPhoton LightSet::emit(Rng& rng, double inv_count, float offset) const {
    LightPhoton e;
    if (table_.total() <= 0) return e;
    const size_t i = table_.sample(rng.uniform_double());
    const double scale = inv_count / table_.pmf(i);
    if (i >= lights_.size()) return emit_emitter(emitters_[i - lights_.size()], rng, scale, offset);
    const PlacedLight& l = lights_[i];
    const vec2 u(rng.uniform(), rng.uniform());
    if (l.is_area()) {
        // Cosine-weighted about the axis from a point uniform on the face: flux L pi A.
        const vec3 p = point_on_face(l, vec2(rng.uniform(), rng.uniform()));
        e.ray = Ray{p + l.axis * offset, Frame(l.axis).to_world(sample_cosine_hemisphere(u))};
        e.flux = vec3(dvec3(l.radiance) * (kPi * double(l.area) * scale));
    } else if (l.kind == Kind::Spot) {
        // Uniform inside the cone, weighted by the soft edge.
        const float cos_t = 1 - u.x * (1 - l.cos_half), sin_t = std::sqrt(std::max(0.0f, 1 - cos_t * cos_t));
        const float phi = 2 * kPi * u.y;
        const vec3 w = Frame(l.axis).to_world(vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t));
        e.ray = Ray{l.position, w};
        e.flux = vec3(dvec3(l.intensity) * (double(l.spot_falloff(w)) * 2.0 * kPi * (1.0 - l.cos_half) * scale));
    } else {
        e.ray = Ray{l.position, sample_uniform_sphere(u)};
        e.flux = vec3(dvec3(l.intensity) * (4.0 * kPi * scale));
    }
    e.valid = e.flux != vec3(0) && is_finite(e.flux);
    return e;
}

LightPhoton LightSet::emit_emitter(const EmissiveShape& e, Rng& rng, double scale, float offset) const {
    LightPhoton ph;
    vec3 p, n;
    const double u0 = rng.uniform_double();
    point_on_emitter(e, u0, vec2(rng.uniform(), rng.uniform()), p, n);
    if (rng.uniform() < 0.5f) n = -n;  // either side, each half the flux 2 pi A L
    ph.ray = Ray{p + n * offset, Frame(n).to_world(sample_cosine_hemisphere(vec2(rng.uniform(), rng.uniform())))};
    ph.flux = vec3(dvec3(e.radiance) * (2.0 * kPi * e.area * scale));
    ph.valid = ph.flux != vec3(0) && is_finite(ph.flux);
    return ph;
}

double LightSet::irradiance_bound(const vec3& p, const vec3& n) const {
    double sum = 0;
    for (const EmissiveShape& e : emitters_) {
        const vec3 to = e.center - p;
        const double d2 = glm::dot(to, to), r2 = double(e.radius) * e.radius;
        if (glm::dot(n, to) < -e.radius) continue;
        const double solid_angle = d2 > r2 ? 2.0 * kPi * (1.0 - std::sqrt(1.0 - r2 / d2)) : 2.0 * kPi;
        sum += luminance(dvec3(e.radiance)) * std::min(solid_angle, double(kPi));
    }
    for (const PlacedLight& l : lights_) {
        if (l.power <= 0) continue;
        const vec3 to = l.position - p;
        const double d2 = glm::dot(to, to);
        if (!l.is_area()) {
            if (glm::dot(n, to) <= 0 || !(d2 > 0)) continue;
            const float falloff = l.spot_falloff(-to / float(std::sqrt(d2)));
            sum += luminance(dvec3(l.intensity)) * falloff / d2;
            continue;
        }
        const float R = face_radius(l);
        // Behind its face's plane, or with the whole face below the point's horizon: nothing.
        if (glm::dot(p - l.position, l.axis) <= 0 || glm::dot(n, to) < -R) continue;
        const double r2 = double(R) * R;
        const double solid_angle = d2 > r2 ? 2.0 * kPi * (1.0 - std::sqrt(1.0 - r2 / d2)) : 2.0 * kPi;
        sum += luminance(dvec3(l.radiance)) * std::min(solid_angle, double(kPi));
    }
    return sum;
}

void LightSet::bounds(size_t i, vec3& center, float& radius) const {
    if (i >= lights_.size()) {
        center = emitters_[i - lights_.size()].center;
        radius = emitters_[i - lights_.size()].radius;
        return;
    }
    const PlacedLight& l = lights_[i];
    center = l.position;
    radius = l.is_area() ? face_radius(l) : 0.0f;
}

}  // namespace dp
