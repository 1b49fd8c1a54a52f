// The Python script `diffphoton export blender` writes (docs/cycles.md, "Hand-off to Blender").
#include "blender_script.h"

#include <cstdio>

namespace dp::cli {

std::string python_string_literal(const std::string& text, bool multiline) {
    const std::string quote = multiline ? "'''" : "'";
    std::string out = quote;
    for (const unsigned char c : text) {
        if (c == '\\' || c == '\'') {
            out += '\\';
            out += char(c);
        } else if (c == '\n' && !multiline) {
            out += "\\n";
        } else if ((c < 0x20 && c != '\n') || c >= 0x7f) {
            // Bytes, not code points: the literal is decoded as UTF-8 below (utf8_literal).
            char buf[8];
            std::snprintf(buf, sizeof(buf), "\\x%02x", c);
            out += buf;
        } else {
            out += char(c);
        }
    }
    return out + quote;
}

namespace {

/// A Python expression giving `text` (UTF-8) back as str: a bytes literal decoded, so that any
/// path survives whatever encoding the script is opened with.
std::string utf8_literal(const std::string& text, bool multiline = false) {
    return "b" + python_string_literal(text, multiline) + ".decode()";
}

constexpr const char* kRule =
    "# ==========================================================================================="
    "==\n";

// The main part of the script. The converter above it defines CyclesScene and ConversionError.
constexpr const char* kMain = R"py(

# =============================================================================================
# The hand-off: builds the scene above's project (catcher mode, as `diffphoton bench` renders).

import argparse
import sys


def hand_off_args():
    # After `--` (blender -b --python SCRIPT -- ARGS), or after the script's name where Blender
    # is a Python module (python SCRIPT ARGS).
    argv = script_args(__file__ if "__file__" in globals() else "")
    ap = argparse.ArgumentParser(
        prog="blender -b --python " + os.path.basename(__file__ if "__file__" in globals() else "scene.py") + " --",
        description="Builds the diffphoton project " + PROJECT_FILE + " as a Cycles scene.")
    ap.add_argument("--blend", default=BLEND, help="save the scene as this .blend file"
                    + (f" (default: {BLEND})" if BLEND else ""))
    ap.add_argument("--samples", type=int, default=SAMPLES, help=f"samples per pixel (default {SAMPLES})")
    ap.add_argument("--render", default="",
                    help="render and write this multilayer EXR: the composite (layer Composite) and the "
                         "view layer's passes (Combined with the objects' alpha, Shadow Catcher)")
    ap.add_argument("--threads", type=int, default=0, help="render threads (0: all cores)")
    return ap.parse_args(argv)


def hand_off():
    args = hand_off_args()
    if bpy.app.version < (3, 4, 0):
        print(f"error: this script needs Blender 3.4 or later (4.2 LTS, 5.x); this is Blender "
              f"{bpy.app.version_string}", file=sys.stderr, flush=True)
        sys.exit(2)
    print(f"building {PROJECT_FILE} in Blender {bpy.app.version_string}", flush=True)
    try:
        cs = CyclesScene(PROJECT_FILE, mode="catcher", threads=args.threads, project=PROJECT)
    except ConversionError as e:
        print(f"error: {e}", file=sys.stderr, flush=True)
        sys.exit(2)
    scene = cs.scene
    scene.name = os.path.splitext(os.path.basename(PROJECT_FILE))[0]
    c = scene.cycles
    c.samples = max(1, args.samples)
    c.seed = int(PROJECT.get("render", {}).get("seed", 1)) % (1 << 31)  # Cycles' seed is 32-bit
    # An artist previews in the viewport: a few samples there, the full count in renders.
    c.preview_samples = min(c.samples, 32)
    if args.blend:
        # Absolute paths, as docs/cycles.md says: Blender's default remaps them relative to
        # the .blend, which breaks when the .blend moves without the photo and probe.
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.blend), relative_remap=False)
        print(f"saved {os.path.abspath(args.blend)}", flush=True)
    if args.render:
        settings = scene.render.image_settings
        if hasattr(settings, "media_type"):  # Blender 5: multilayer is a media type of its own
            settings.media_type = "MULTI_LAYER_IMAGE"
        settings.file_format = "OPEN_EXR_MULTILAYER"
        settings.color_mode = "RGBA"
        bpy.ops.render.render(write_still=False)
        bpy.data.images["Render Result"].save_render(os.path.abspath(args.render), scene=scene)
        print(f"rendered {os.path.abspath(args.render)}", flush=True)


hand_off()
)py";

}  // namespace

std::string blender_script(const BlenderScriptInputs& in) {
    std::string s;
    s += "# A diffphoton project as a Blender Cycles scene, written by `diffphoton export "
         "blender`.\n#\n";
    s += "#   blender -b --python " + in.script_name +
         " -- [--blend OUT.blend] [--render OUT.exr]  (headless)\n";
    s += "#   blender --python " + in.script_name + "  (to work on it)\n#\n";
    s += "# Parts: the converter (bench/cycles/dp_cycles.py of diffphoton, verbatim), the\n";
    s += "# project (paths made absolute), and the hand-off at the end. Conventions:\n";
    s += "# docs/cycles.md.\n\n";
    s += kRule;
    s += "# The converter\n\n";
    s += in.converter_source;
    if (!s.empty() && s.back() != '\n') s += '\n';
    s += "\n\n";
    s += kRule;
    s += "# The project\n\n";
    s += "PROJECT_FILE = " + utf8_literal(in.project_file) + "\n";
    // JSON inside a string literal rather than as Python: true/false/null and any key survive.
    s += "PROJECT = json.loads(" + utf8_literal(in.project.dump(1), true) + ")\n";
    s += "SAMPLES = " + std::to_string(in.samples) + "\n";
    s += "BLEND = " + utf8_literal(in.blend) + "\n";
    s += kMain;
    return s;
}

}  // namespace dp::cli
