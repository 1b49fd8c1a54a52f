#pragma once
// Every file reading a project opens, for the rule that no output replaces an input
// (docs/colour.md, "Outputs never overwrite inputs").
#include <filesystem>
#include <string>
#include <sys/types.h>
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

/// The files a command reads, each known by its identity on disk (device and inode), so that
/// an output reached through a symbolic link, a hard link or another spelling of the path is
/// still recognised as one of them.
class ReadSet {
public:
    /// `path`, described by `what` ("the input image"); a missing file is left out.
    void add(const std::string& path, const std::string& what);
    /// The project file (unless `project_file` is empty) and every file the project reads,
    /// the side files of its meshes included (project_read_files).
    void add_project(const Project& project, const std::string& project_file);
    /// The input that `path` is, or nullptr when it is none (or does not exist).
    const ReadFile* find(const std::string& path) const;

private:
    struct Entry {
        ReadFile file;
        dev_t device;
        ino_t inode;
    };
    std::vector<Entry> entries_;
};

}  // namespace dp
