#pragma once
// Shared measurements for the geometry tests.
#include <algorithm>

#include "geometry/mesh.h"

namespace dp::test {

/// Unnormalised geometric normal of triangle `i`, from cross(v1 - v0, v2 - v0).
inline vec3 geometric_normal(const TriangleMesh& m, size_t i) {
    const glm::uvec3 t = m.triangles[i];
    return glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
}

inline double surface_area(const TriangleMesh& m) {
    double area = 0;
    for (size_t i = 0; i < m.triangle_count(); ++i) {
        area += 0.5 * glm::length(geometric_normal(m, i));
    }
    return area;
}

/// Signed volume by the divergence theorem: positive when a closed mesh is wound outward.
inline double signed_volume(const TriangleMesh& m) {
    double volume = 0;
    for (const glm::uvec3& t : m.triangles) {
        const dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return volume;
}

/// Smallest cosine between a triangle's geometric normal and any of its corners' vertex normals;
/// positive means the shading normals and the winding agree everywhere.
inline float min_winding_agreement(const TriangleMesh& m) {
    float worst = 1.0f;
    for (size_t i = 0; i < m.triangle_count(); ++i) {
        const vec3 g = glm::normalize(geometric_normal(m, i));
        const glm::uvec3 t = m.triangles[i];
        for (unsigned v : {t.x, t.y, t.z}) worst = std::min(worst, glm::dot(g, m.normals[v]));
    }
    return worst;
}

}  // namespace dp::test
