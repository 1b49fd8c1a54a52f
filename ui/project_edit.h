#pragma once
// Pure helpers over dp::Project used by the studio: what an edit changed, new objects, bounds.
#include <string>
#include <vector>

#include "scene/project.h"

namespace dp::ui {

/// What an edit changed, from cheapest to dearest for the renderer.
enum class Change {
    None,      ///< names only: nothing to render
    Settings,  ///< render settings only: the session restarts with them, nothing is rebuilt
    Material,  ///< virtual materials only: RenderScene::with_materials, no BVH rebuild
    Scene,     ///< geometry, transforms, camera or probe pose: rebuild the scene
    Assets,    ///< photo or probe file: reload images, then rebuild
};

/// Classifies the difference between two projects (symmetric, so undo classifies as the edit).
Change classify(const Project& before, const Project& after);

/// The objects an edit from `before` to `after` changed (shape, transform, visibility or
/// material; by index, so added and removed ones count), or false when it changed more than
/// objects (photo, probe, camera, real proxies, render settings): then the whole picture can.
bool edited_objects(const Project& before, const Project& after, std::vector<int>& edited);

/// A name not yet used by the project's objects ("sphere", "sphere 2", ...).
std::string unique_name(const Project& project, const std::string& base);

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
