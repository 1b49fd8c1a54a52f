#pragma once
#include <memory>
#include <string>

#include "assets/render_scene.h"
#include "scene/project.h"

namespace dp::cli {

/// Parses "X,Y" (the --pixel flag) into integers; throws InputError naming the flag.
void parse_pixel(const std::string& text, int& x, int& y);

/// Renders exactly pass `pass` of `scene` with its render settings and prints one pixel's
/// photo, delta, dL and alpha: the pass is reproducible from (seed, pass) alone, so a pixel
/// that looks wrong in a full render can be examined in isolation.
int debug_pixel(std::shared_ptr<const RenderScene> scene, const RenderSettings& settings,
                const std::string& project_path, int x, int y, int pass);

}  // namespace dp::cli
