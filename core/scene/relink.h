#pragma once
// Files a project names that have moved: which are missing, where a file of the same name now
// is, and how the project stores the new path.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene/project.h"

namespace dp {

/// A file the project reads, with where it resolves to.
struct InputFile {
    InputRef ref;
    std::string stored;              ///< the path as the project file writes it
    std::filesystem::path resolved;  ///< Project::resolve(stored)
    bool missing = false;            ///< no regular file there
};

/// Every file `project` reads (for_each_input's order), each marked missing or not.
std::vector<InputFile> input_files(const Project& project);

/// The files of input_files() that are missing.
std::vector<InputFile> missing_inputs(const Project& project);

/// How a project in `base_dir` stores `file`: relative to the folder when the file lies inside
/// it (the folder can then move as a whole), absolute elsewhere.
std::string path_for_project(const std::filesystem::path& base_dir,
                             const std::filesystem::path& file);

/// Sets the path of input `field` (an InputRef::field of `project`) to `path`, as written.
/// Returns false, changing nothing, when `project` has no such input.
bool set_input_path(Project& project, const std::string& field, const std::string& path);

/// The first regular file named `name` in `folders`, taken in turn, each searched breadth first
/// down to `depth` levels of subfolders (symbolic links to folders are not followed). At most
/// `max_entries` folder entries are looked at in all, so a search started in a large tree
/// (a home folder) ends quickly; nullopt when none is found.
std::optional<std::filesystem::path> find_file_named(
    const std::string& name, const std::vector<std::filesystem::path>& folders, int depth = 2,
    size_t max_entries = 20000);

}  // namespace dp
