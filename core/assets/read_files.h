#pragma once
// Every file reading a project opens, for the rule that no output replaces an input
// (docs/colour.md, "Outputs never overwrite inputs").
#include <filesystem>
#include <string>
#include <vector>

#include "scene/project.h"

namespace dp {

/// A file a command reads.
struct ReadFile {
    std::filesystem::path path;  ///< as it resolves from the working folder
    /// What it is, for messages: "the project's photo (photo.path)", "the texture named by mesh
    /// chair.obj's material file chair.mtl (objects[0].shape.path)".
    std::string what;
};

/// The files reading `project` opens: `project_file` itself (unless empty), every file the
/// project names (input_files: photo, probe, meshes, albedo textures) and the files those meshes
/// name in turn (mesh_side_files: an OBJ's material files and their textures, a glTF's buffers
/// and images). Missing files are left out: there is nothing there to lose.
std::vector<ReadFile> project_read_files(const Project& project, const std::string& project_file);

}  // namespace dp
