// Mesh loading (Assimp behind the project's loader): the first byte picks the format by
// extension, the rest is the file. A loaded mesh has finite vertices and in-range indices.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "geometry/mesh.h"
#include "mesh_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace dp;
    if (size < 1) return 0;
    static const char* const kNames[] = {"input.obj", "input.ply", "input.gltf", "input.glb", "input.stl"};
    const std::string path = fuzz::write_input(data + 1, size - 1, kNames[data[0] % 5]);
    fuzz::expect_only_input_errors([&] {
        const LoadedMesh loaded = load_mesh(path, "objects[0].shape.path");
        fuzz::check_mesh(loaded.mesh, loaded.materials.size());
        for (const FileMaterial& f : loaded.materials)
            fuzz::require(f.embedded_texture < int(loaded.embedded_textures.size()),
                          "a material names a texture past the file's");
    });
    return 0;
}
