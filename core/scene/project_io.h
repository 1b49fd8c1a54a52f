#pragma once
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/project.h"

namespace dp {

/// Reads and validates a project file (layout in docs/project-format.md). `base_dir` becomes the
/// absolute folder of `path`. Throws InputError naming the file and the JSON field path (e.g.
/// "objects[2].material.type") for unreadable files, invalid JSON, missing or unknown keys,
/// wrong types, unknown enum values, out-of-range or non-finite numbers and duplicate keys.
Project load_project(const std::string& path);

/// Writes `project` as pretty JSON (2-space indent); paths are written as stored.
/// Throws InputError if the file cannot be written.
void save_project(const Project& project, const std::string& path);

/// Validates an already parsed document. `file_for_errors` only labels error messages;
/// `base_dir` is stored in the result for Project::resolve.
Project parse_project(const nlohmann::json& doc, const std::string& file_for_errors,
                      std::filesystem::path base_dir);

/// The document save_project writes (keys sorted, as nlohmann::json keeps them).
nlohmann::json to_json(const Project& project);

}  // namespace dp
