#pragma once
#include <glm/glm.hpp>
#include <cmath>
#include <numbers>

namespace dp {

using glm::dvec3;
using glm::vec2;
using glm::vec3;

inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kInvPi = 1.0f / kPi;

/// A ray in world space; `dir` is unit length.
struct Ray {
    vec3 org;
    vec3 dir;
};

/// Rec. 709 luminance of linear RGB.
inline float luminance(const vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
inline double luminance(const dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

inline bool is_finite(const vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Orthonormal basis around a unit normal (Duff et al. 2017), for local sampling.
struct Frame {
    vec3 t, b, n;
    explicit Frame(const vec3& normal) : n(normal) {
        float sign = std::copysign(1.0f, n.z);
        float a = -1.0f / (sign + n.z);
        float bb = n.x * n.y * a;
        t = vec3(1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x);
        b = vec3(bb, sign + n.y * n.y * a, -n.y);
    }
    vec3 to_world(const vec3& v) const { return t * v.x + b * v.y + n * v.z; }
    vec3 to_local(const vec3& v) const { return vec3(glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)); }
};

}  // namespace dp
