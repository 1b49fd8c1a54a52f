// Mesh loading (Assimp behind the project's loader): the first byte picks the format by
// extension, the rest is the file. A loaded mesh has finite vertices and in-range indices.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "geometry/mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace dp;
    if (size < 1) return 0;
    static const char* const kNames[] = {"input.obj", "input.ply", "input.gltf", "input.glb", "input.stl"};
    const std::string path = fuzz::write_input(data + 1, size - 1, kNames[data[0] % 5]);
    fuzz::expect_only_input_errors([&] {
        const LoadedMesh loaded = load_mesh(path, "objects[0].shape.path");
        const TriangleMesh& m = loaded.mesh;
        for (const vec3& p : m.positions)
            fuzz::require(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z),
                          "a loaded mesh has a non-finite vertex");
        for (const glm::uvec3& t : m.triangles)
            fuzz::require(t.x < m.positions.size() && t.y < m.positions.size() && t.z < m.positions.size(),
                          "a loaded mesh indexes past its vertices");
        fuzz::require(m.normals.empty() || m.normals.size() == m.positions.size(), "normals do not match positions");
        fuzz::require(m.uvs.empty() || m.uvs.size() == m.positions.size(), "uvs do not match positions");
        fuzz::require(
            m.triangle_materials.empty() || m.triangle_materials.size() == m.triangles.size(),
            "triangle materials do not match triangles");
        for (uint32_t k : m.triangle_materials)
            fuzz::require(k == kNoFileMaterial || k < loaded.materials.size(),
                          "a triangle names a material past the file's");
        for (const FileMaterial& f : loaded.materials)
            fuzz::require(f.embedded_texture < int(loaded.embedded_textures.size()),
                          "a material names a texture past the file's");
    });
    return 0;
}
