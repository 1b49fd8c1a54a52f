#pragma once
// Checks of mesh files before Assimp reads them: Assimp 5.2's readers loop forever on some
// malformed PLY headers and allocate whatever size a glTF buffer declares, so what a file
// declares is checked against what it holds first.
#include <string>

namespace dp {

/// Throws InputError(path, field, ...) for a PLY file whose header is not well formed: the
/// "ply" magic, a known format, only comment/obj_info/element/property lines with known types
/// and integer counts, and an end_header line within the first 64 KiB.
void check_ply_header(const std::string& path, const std::string& field);

/// Throws InputError for a glTF 2.0 file (.gltf JSON or .glb binary) whose buffers declare more
/// bytes than they hold: a GLB's chunk lengths against the file, an embedded buffer against its
/// chunk or data URI, an external buffer against its file.
void check_gltf_buffers(const std::string& path, const std::string& field);

}  // namespace dp
