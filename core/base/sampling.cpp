#include "base/sampling.h"

#include <algorithm>

namespace dp {

vec2 sample_concentric_disk(vec2 u) {
    vec2 o = 2.0f * u - vec2(1.0f);
    if (o.x == 0 && o.y == 0) return vec2(0);
    float r, theta;
    if (std::abs(o.x) > std::abs(o.y)) {
        r = o.x;
        theta = (kPi / 4) * (o.y / o.x);
    } else {
        r = o.y;
        theta = kPi / 2 - (kPi / 4) * (o.x / o.y);
    }
    return r * vec2(std::cos(theta), std::sin(theta));
}

vec3 sample_cosine_hemisphere(vec2 u) {
    vec2 d = sample_concentric_disk(u);
    float z = std::sqrt(std::max(0.0f, 1 - d.x * d.x - d.y * d.y));
    return vec3(d.x, d.y, z);
}

vec3 sample_uniform_sphere(vec2 u) {
    float z = 1 - 2 * u.x;
    float r = std::sqrt(std::max(0.0f, 1 - z * z));
    float phi = 2 * kPi * u.y;
    return vec3(r * std::cos(phi), r * std::sin(phi), z);
}

}  // namespace dp
