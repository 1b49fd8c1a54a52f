#pragma once
// The `cycles` method of `diffphoton bench`: Blender Cycles with the real proxies as shadow
// catchers, rendered by bench/cycles/cycles_render.py (see docs/cycles.md).
#include <memory>
#include <string>
#include <vector>

#include "assets/pass_renderer.h"

namespace dp::cli {

/// What a Cycles run needs besides the scene.
struct CyclesRun {
    std::string blender;        ///< the Blender executable
    double budget_seconds = 0;  ///< stop after the first render that takes this long
    int threads = 0;            ///< render threads; 0 uses every core
};

/// The Blender executable: `option` (--blender) if given, else $DP_BLENDER if set, else
/// `blender` on PATH. "" when the chosen one is not an executable file.
std::string find_blender(const std::string& option);

/// Looks for Blender once per bench run when `methods` holds "cycles": if there is none, prints
/// "cycles: skipped, Blender not found (...)" and removes "cycles" from `methods`. Returns the
/// executable, or "" when the method is not run.
std::string prepare_cycles_method(std::vector<std::string>& methods, const std::string& blender_option);

/// Cycles' renders of the scene (its folder's scene.json) at 1, 2, 4, ... samples per pixel,
/// one per render_pass(), so that the bench measures them like the other methods' passes:
/// passes() and samples_per_pixel are the render's samples per pixel, stats().seconds that
/// render's own time (Cycles' scene sync and BVH build included, Blender's start-up and the
/// conversion not), image() its shadow-catcher composite. Blender runs once, on the first
/// call. render_pass() returns false when the renders are used up, on Ctrl-C, or when Blender
/// failed (then with a message on stderr that names the scene). The composite has no layers:
/// dL_layer() and alpha_layer() are zero images.
std::unique_ptr<PassRenderer> make_cycles_renderer(std::shared_ptr<const RenderScene> scene, const CyclesRun& run);

}  // namespace dp::cli
