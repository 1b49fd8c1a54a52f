#pragma once
#include <string>

#include "assets/render_scene.h"

namespace dp {

/// Checks a compiled scene for set-ups that project validation alone cannot see. Today: the
/// camera must not sit inside real geometry (rays from the camera centre that hit the back
/// faces of real proxies in every direction), which would hide the whole photo from the
/// renderer. Throws InputError labelled with `file_for_errors` and the field of the camera
/// position ("camera.eye" or "camera.translation").
void check_scene(const RenderScene& scene, const std::string& file_for_errors = "");

}  // namespace dp
