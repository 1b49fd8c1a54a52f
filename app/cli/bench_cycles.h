#pragma once
// The Cycles methods of `diffphoton bench`: Blender Cycles with the real proxies as shadow
// catchers, rendered by bench/cycles/cycles_render.py (see docs/cycles.md). `cycles` runs
// Debian's Blender 3.4; `cycles5` and `cycles5-artist` run Blender 5 as a Python module (PyPI
// bpy), the latter as artists run it (denoised, adaptive, guided, light tree, MNEE).
#include <memory>
#include <string>
#include <vector>

#include "assets/pass_renderer.h"

namespace dp::cli {

/// The Cycles methods' names, in the order the help lists them.
inline const std::vector<std::string> kCyclesMethods = {"cycles", "cycles5", "cycles5-artist"};

bool is_cycles_method(const std::string& method);

/// What a Cycles run needs besides the scene.
struct CyclesRun {
    std::string method;         ///< "cycles", "cycles5" or "cycles5-artist"
    std::string program;        ///< Blender 3.4's executable (cycles), else Blender 5's Python
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

/// The Python of a Blender 5 module install (PyPI bpy): $DP_BPY5_PYTHON if set, else
/// .deps/bpy5/bin/python in a folder above the executable or in the source tree (where
/// scripts/install-deps.sh --bench makes it). "" when the chosen one is not an executable file.
std::string find_bpy5_python();

/// As prepare_cycles_method for "cycles5" and "cycles5-artist": without Blender 5, prints
/// "METHOD: skipped, Blender 5 not found (...)" for each and removes them. Returns the Python,
/// or "" when neither method is run.
std::string prepare_cycles5_methods(std::vector<std::string>& methods);

/// Cycles' renders of the scene (its folder's scene.json) at 1, 2, 4, ... samples per pixel
/// (cycles5-artist: at most that many, adaptive sampling may stop pixels sooner; denoised),
/// one per render_pass(), so that the bench measures them like the other methods' passes:
/// passes() and samples_per_pixel are the render's samples per pixel, stats().seconds that
/// render's own time (Cycles' scene sync and BVH build included, Blender's start-up and the
/// conversion not), image() its shadow-catcher composite. Blender (or Blender 5's Python) runs
/// once, on the first call. render_pass() returns false when the renders are used up, on
/// Ctrl-C, or when Blender failed (then with a message on stderr that names the scene). The composite has no layers:
/// dL_layer() and alpha_layer() are zero images.
std::unique_ptr<PassRenderer> make_cycles_renderer(std::shared_ptr<const RenderScene> scene, const CyclesRun& run);

}  // namespace dp::cli
