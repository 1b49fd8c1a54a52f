#pragma once
// Pure helpers over dp::Project used by the studio: new objects, names, bounds (what an edit
// changed is the core's: scene/project_diff.h).
#include <string>
#include <vector>

#include "scene/project.h"
#include "scene/project_diff.h"

namespace dp::ui {

/// A name not yet used by the project's objects ("sphere", "sphere 2", ...).
std::string unique_name(const Project& project, const std::string& base);

/// A name not yet used by the project's lights ("point light", "point light 2", ...).
std::string unique_light_name(const Project& project, const std::string& base);

/// The light kind as the studio names it: "Point", "Spot", "Area (rectangle)", "Area (disk)".
const char* light_kind_label(VirtualLight::Kind kind);

/// A name not yet used by the project's real proxies ("ground", "ground 2", ...).
std::string unique_real_name(const Project& project, const std::string& base);

/// Bounding sphere of an object in world space (mesh objects use `mesh_radius` in local units,
/// the radius of the loaded mesh's bounds; 1 if unknown).
void bounding_sphere(const VirtualObject& object, vec3& center, float& radius,
                     float mesh_radius = 1.0f);

/// Copy of `project` whose file paths are absolute, for a project written away from its folder
/// (the autosave file).
Project with_absolute_paths(const Project& project);

}  // namespace dp::ui
