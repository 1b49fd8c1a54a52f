#pragma once
// How large a mesh load_mesh reads: bounded before Assimp allocates what a file declares, so
// that a mesh too large for the machine is refused with its figures instead of ending in an
// out-of-memory failure read as a corrupt file.
#include <cstdint>
#include <string>

namespace dp {

/// The most bytes load_mesh reads for one mesh: the mesh file and the files it names (a glTF's
/// buffers, an OBJ's MTL) together, 4 GiB. Assimp holds a file whole while it parses it, and
/// an OBJ of kMaxMeshTriangles triangles is about 3 GB.
inline constexpr uint64_t kMaxMeshFileBytes = uint64_t(4) << 30;

/// The most triangles a mesh may have: 2^26 (67 million), fewer where they would take more
/// than half of this machine's memory at kMeshBytesPerTriangle, or where the environment's
/// DP_MAX_MESH_TRIANGLES asks for fewer (never more).
inline constexpr uint64_t kMaxMeshTriangles = uint64_t(1) << 26;
/// Peak bytes a triangle takes while it is read and placed: Assimp's copy, ours, and the BVH.
inline constexpr double kMeshBytesPerTriangle = 256;
uint64_t max_mesh_triangles();

/// Throws InputError naming `path` and `field` when `triangles` is over max_mesh_triangles; the
/// message gives the count (`what`: "triangles", "faces (declared in its header)"), the limit and why.
void check_mesh_triangles(const std::string& path, const std::string& field, uint64_t triangles,
                          const std::string& what = "triangles");

}  // namespace dp
