#pragma once
#include <QString>

#include "assets/asset_library.h"
#include "scene/project.h"

namespace dp::ui {

/// Why the core would refuse to render `project`, or an empty string when it would not. Runs
/// the core's own checks, in the order a render meets them: the project file's field rules
/// (parse_project: finite numbers, eye apart from target, ...), the placed scene's extent and the
/// camera's position (RenderScene and check_scene, on a scene built at 32 pixels wide through
/// `library`, so the files are decoded once and shared with the renderer, and with a stand-in
/// probe), and the render settings' memory and gather-radius limits (check_render_limits; the
/// memory of the full-size image itself is left to the render). Cheap enough for one typed edit
/// on the UI thread once the files are loaded; a file that cannot be read is a problem too.
QString scene_problem(AssetLibrary& library, const Project& project);

}  // namespace dp::ui
