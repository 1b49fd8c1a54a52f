#pragma once
// The materials of a mesh file as Assimp hands them over, before the assets map them onto the
// project's kinds: the loader's half of "materials from the file".
#include <string>
#include <vector>

#include "geometry/mesh.h"

struct aiScene;

namespace dp {

/// The scene's materials as FileMaterial, one per Assimp material (same indices). Colour
/// textures are resolved against the folder of `mesh_path`; textures stored in the file are
/// copied into `embedded` (FileMaterial::embedded_texture indexes it). `made_up[i]` is true for
/// the materials Assimp invents for triangles the file gives none (an OBJ without MTL, glTF
/// primitives without a material, every PLY and STL face). What cannot be read is said in
/// `warnings`.
std::vector<FileMaterial> read_file_materials(const aiScene& scene, const std::string& mesh_path,
                                              std::vector<EmbeddedTexture>& embedded,
                                              std::vector<bool>& made_up,
                                              std::vector<std::string>& warnings);

/// Keeps the materials some triangle uses, renumbering `mesh.triangle_materials`; clears them
/// all (and the embedded textures) when no triangle has one.
void keep_used_materials(LoadedMesh& mesh);

}  // namespace dp
