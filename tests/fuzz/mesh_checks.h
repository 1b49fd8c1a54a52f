#pragma once
// What a loaded mesh promises, for the mesh fuzz targets: finite vertices, indices within them,
// normals and UVs one per vertex, triangle materials within the file's.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "geometry/mesh.h"

namespace dp::fuzz {

/// Aborts (a finding) where `m`, loaded with `materials` materials from its file, breaks a promise.
inline void check_mesh(const TriangleMesh& m, size_t materials) {
    for (const vec3& p : m.positions)
        require(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z),
                "a loaded mesh has a non-finite vertex");
    for (const glm::uvec3& t : m.triangles)
        require(t.x < m.positions.size() && t.y < m.positions.size() && t.z < m.positions.size(),
                "a loaded mesh indexes past its vertices");
    require(m.normals.empty() || m.normals.size() == m.positions.size(), "normals do not match positions");
    require(m.uvs.empty() || m.uvs.size() == m.positions.size(), "uvs do not match positions");
    require(m.triangle_materials.empty() || m.triangle_materials.size() == m.triangles.size(),
            "triangle materials do not match triangles");
    for (uint32_t k : m.triangle_materials)
        require(k == kNoFileMaterial || k < materials, "a triangle names a material past the file's");
}

}  // namespace dp::fuzz
