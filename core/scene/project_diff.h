#pragma once
// What an edit from one project state to another changed, for a renderer deciding what to keep.
#include <vector>

#include "scene/project.h"

namespace dp {

/// What an edit changed, from cheapest to dearest for the renderer.
enum class Change {
    None,      ///< names only: nothing to render
    Settings,  ///< render settings only: the session restarts with them, nothing is rebuilt
    Material,  ///< virtual materials or lights only: RenderScene::with_materials, no BVH rebuild
    Scene,     ///< geometry, transforms, camera or probe pose: rebuild the scene
    Assets,    ///< photo or probe file: reload images, then rebuild
};

/// Classifies the difference between two projects (symmetric, so undo classifies as the edit).
Change classify(const Project& before, const Project& after);

/// The objects an edit from `before` to `after` changed (shape, transform, visibility or
/// material; by index, so added and removed ones count), or false when it changed more than
/// objects (photo, probe, camera, real proxies, lights, render settings): then the whole picture can.
bool edited_objects(const Project& before, const Project& after, std::vector<int>& edited);

}  // namespace dp
