#pragma once
// The files a mesh file names besides itself (an OBJ's material libraries and their textures, a
// glTF's buffers and images): inputs of a render as much as the mesh is, which no output may
// replace.
#include <filesystem>
#include <string>
#include <vector>

namespace dp {

/// A file that reading a mesh opens besides the mesh file itself.
struct MeshSideFile {
    enum class Kind {
        MaterialFile,  ///< an OBJ's material library (.mtl)
        Texture,       ///< a texture map a material library names
        Buffer,        ///< a glTF buffer (.bin)
        Image,         ///< a glTF image
        MeshTexture,   ///< a texture an FBX file names itself
    };
    std::filesystem::path path;  ///< where it resolves, as the mesh reader looks for it
    Kind kind = Kind::MaterialFile;
    std::filesystem::path material_file;  ///< Texture: the material library that names it
};

/// The existing files that reading `mesh_path` opens besides it, found from the file's text
/// without decoding the mesh: an OBJ's material libraries (`mtllib`, or the `<name>.mtl`
/// Assimp falls back to when a named one is missing) and every texture map they name, and a
/// glTF's (.gltf or .glb) external buffers and images. A path that could be read two ways (a
/// name with spaces, a texture relative to the OBJ's or to the MTL's folder, a URI with "%20"
/// decoded or as written) is listed both ways. An FBX's external textures are found from its
/// texture file name properties (binary or ASCII), each also as a bare name beside the mesh.
/// Other formats (PLY, STL) name no files.
/// An unreadable mesh lists none (its reader reports it).
std::vector<MeshSideFile> mesh_side_files(const std::string& mesh_path);

}  // namespace dp
