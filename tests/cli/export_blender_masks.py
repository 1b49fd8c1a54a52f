"""Object and shadow masks of the exported Blender scene against ours (runs inside Blender, for
bench/cycles/check_conversion.py's EXR reader; used by export_blender.sh).

    blender -b --factory-startup --python-exit-code 1 --python export_blender_masks.py -- \\
        CYCLES.exr OURS.exr REAL_ONLY.exr

CYCLES.exr: the script's --render output (ViewLayer.Combined with the objects' alpha,
ViewLayer.Shadow Catcher); OURS.exr: `diffphoton render --layers` (alpha, dL); REAL_ONLY.exr:
`diffphoton reference --real-only` (L_old). Objects: alpha > 1/2 in each. Shadow, away from the
objects: Cycles' catcher below 0.9 against ours' dL below -0.1 L_old (the same change:
catcher = (L_old + dL) / L_old). Prints both IoUs as `objects_iou X shadow_iou Y` with the
pixel counts.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench", "cycles"))
import check_conversion  # noqa: E402


def iou(a, b):
    inter = sum(1 for x, y in zip(a, b) if x and y)
    union = sum(1 for x, y in zip(a, b) if x or y)
    return inter / union if union else 1.0


def main():
    cycles, ours, real_only = sys.argv[sys.argv.index("--") + 1:][:3]
    read = check_conversion.read_exr
    w, h, cyc_alpha = read(cycles, "ViewLayer.Combined", "A")
    size = (w, h)
    w, h, cyc_catcher = read(cycles, "ViewLayer.Shadow Catcher")
    assert (w, h) == size, f"{cycles}: passes of different sizes"
    w, h, our_alpha = read(ours, "alpha", "R")
    assert (w, h) == size, f"{ours} is {w}x{h}, Cycles' render {size[0]}x{size[1]}"
    _, _, dl = read(ours, "dL")
    _, _, lold = read(real_only)
    cyc_obj = [a > 0.5 for a in cyc_alpha]
    our_obj = [a > 0.5 for a in our_alpha]
    free = [not (a or b) for a, b in zip(cyc_obj, our_obj)]
    cyc_shadow = [f and c < 0.9 for f, c in zip(free, check_conversion.luminance(cyc_catcher))]
    our_shadow = [f and d < -0.1 * l for f, d, l in
                  zip(free, check_conversion.luminance(dl), check_conversion.luminance(lold))]
    print(f"objects_iou {iou(cyc_obj, our_obj):.4f} shadow_iou {iou(cyc_shadow, our_shadow):.4f} "
          f"object_pixels {sum(cyc_obj)} {sum(our_obj)} shadow_pixels {sum(cyc_shadow)} {sum(our_shadow)}",
          flush=True)


main()
