#pragma once
// Assimp's file access for load_mesh (internal to core/geometry).
#include <assimp/DefaultIOSystem.h>

#include <cstdint>
#include <optional>
#include <set>
#include <string>

#include "base/error.h"

namespace dp {

/// Every file Assimp opens for one mesh (the mesh file, a glTF's buffers, an OBJ's MTL) passes
/// check_input_file first: a FIFO, a device or a folder a mesh file names is refused instead of
/// blocking the reader or feeding it without end, and the files together are bounded by
/// kMaxMeshFileBytes. Where Assimp's OBJ reader may read the mesh, each file passes
/// check_material_library too: that reader reads every other file it opens as a material
/// library, and the mesh itself where it names itself as one. Assimp turns exceptions thrown
/// through it into text, so a refusal is kept and thrown by rethrow_refusal once Assimp has
/// returned.
class CheckedIOSystem : public Assimp::DefaultIOSystem {
public:
    /// For the mesh `mesh_path`, named in messages with `field`; `material_libraries`: the OBJ
    /// reader may read it.
    CheckedIOSystem(std::string mesh_path, std::string field, bool material_libraries);

    /// Whether `file` exists, without opening it (opening a FIFO blocks).
    bool Exists(const char* file) const override;
    /// Opens `file` for reading once it passes the checks; null where it is missing or refused.
    Assimp::IOStream* Open(const char* file, const char* mode = "rb") override;
    using Assimp::DefaultIOSystem::Open;

    /// Throws the first refusal, if there was one.
    void rethrow_refusal() const;

private:
    std::string mesh_, field_;
    bool material_libraries_ = false;
    std::set<std::string> counted_;  ///< files whose bytes are in total_, by canonical path
    uint64_t total_ = 0;
    std::optional<InputError> refusal_;
};

}  // namespace dp
