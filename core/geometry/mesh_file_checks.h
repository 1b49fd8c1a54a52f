#pragma once
// Checks of mesh files before Assimp reads them: Assimp 5.2's readers loop forever on some
// malformed PLY headers, allocate whatever size a glTF buffer declares and crash on a material
// library that sets a material before naming one, so what a file declares is checked first.
#include <string>

namespace dp {

/// Throws InputError(path, field, ...) for a PLY file whose header is not well formed: the
/// "ply" magic, a known format, only comment/obj_info/element/property lines with known types
/// and integer counts, and an end_header line within the first 64 KiB.
void check_ply_header(const std::string& path, const std::string& field);

/// Throws InputError(path, field, ...) for a file that Assimp's MTL reader would crash on: a
/// statement it writes into the current material without checking that there is one (a texture:
/// map_..., bump, disp, norm; an anisotropy) before the file's first material (newmtl). The
/// text is read as that reader reads it: lines end at \n, \r, \f and \0, a UTF-8 mark is
/// dropped, big-endian UTF-16 and UTF-32 are byte-swapped (and not converted further).
void check_material_library(const std::string& path, const std::string& field);

/// Whether the file is a JSON object, as a .gltf file or a .glb file's first chunk: only then
/// may a glTF reader take it, and never Assimp's OBJ reader (OBJ statements are no JSON).
bool is_gltf_json(const std::string& path);

/// Throws InputError for a glTF 2.0 file (.gltf JSON or .glb binary) whose buffers declare more
/// bytes than they hold: a GLB's chunk lengths against the file, an embedded buffer against its
/// chunk or data URI, an external buffer against its file.
void check_gltf_buffers(const std::string& path, const std::string& field);

}  // namespace dp
