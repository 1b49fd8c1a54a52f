"""Renders a diffphoton project with Blender Cycles (shadow catcher) at increasing samples per
pixel until a time budget is spent: the `cycles` (Blender 3.4), `cycles5` and `cycles5-artist`
(Blender 5 as a Python module) methods of `diffphoton bench`.

    blender -b --factory-startup --python-exit-code 1 -P bench/cycles/cycles_render.py -- \\
        SCENE.json --out DIR [--budget SECONDS] [--threads N] [--seed S] [--spp 1,2,4]
    .deps/bpy5/bin/python bench/cycles/cycles_render.py SCENE.json --out DIR [...] [--artist]

One Blender process converts the scene once (dp_cycles.py), then renders 1, 2, 4, 8, ... spp
(or the --spp list), each a fresh render with the same seed, and writes DIR/cycles-<spp>.exr
(the composite, linear RGB) and DIR/renders.json: {"renders": [{spp, seconds, exr}, ...]},
rewritten after every render. `seconds` is the wall time of the render call (Cycles' scene sync
and BVH build included, Blender's start-up and the conversion not). It stops after the first
render that takes the budget or longer. Prints one "cycles-render: {json}" line per render.
`--artist` (Blender 5 only): Cycles as artists run it, Open Image Denoise with albedo and normal
guides, adaptive sampling (threshold 0.01), path guiding, the light tree and MNEE shadow
caustics (dp_cycles.CyclesScene.artist_settings); the spp are then each render's maximum.
Exit code 2: the project cannot be converted (the message names the file and field), or
--artist under a Blender older than 5.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dp_cycles  # noqa: E402


def parse_args():
    argv = dp_cycles.script_args(__file__)
    ap = argparse.ArgumentParser(prog="cycles_render.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("project", help="diffphoton project (scene.json)")
    ap.add_argument("--out", required=True, help="folder for the EXRs and renders.json")
    ap.add_argument("--budget", type=float, default=120.0, help="stop after a render of this many seconds")
    ap.add_argument("--threads", type=int, default=0, help="render threads (0: all cores)")
    ap.add_argument("--seed", type=int, default=None, help="Cycles seed (default: the project's render.seed)")
    ap.add_argument("--spp", default="", help="comma-separated samples per pixel (default 1, 2, 4, ...)")
    ap.add_argument("--max-spp", type=int, default=1 << 20, help="never more samples per pixel than this")
    ap.add_argument("--artist", action="store_true",
                    help="Blender 5: denoising, adaptive sampling, path guiding, light tree, MNEE")
    return ap.parse_args(argv)


def spp_schedule(args):
    if args.spp:
        return sorted({int(x) for x in args.spp.split(",") if x.strip()})
    out, n = [], 1
    while n <= args.max_spp:
        out.append(n)
        n *= 2
    return out


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    try:
        cs = dp_cycles.CyclesScene(args.project, mode="catcher", threads=args.threads, artist=args.artist)
    except (dp_cycles.ConversionError, dp_cycles.ArtistUnsupported) as e:
        print(f"error: {e}", file=sys.stderr, flush=True)
        sys.exit(2)
    seed = args.seed if args.seed is not None else int(cs.project.get("render", {}).get("seed", 1))
    # Cycles' seed is a 32-bit int; ours is 64-bit.
    seed = seed % (1 << 31)
    renders = []
    for spp in spp_schedule(args):
        exr = os.path.join(os.path.abspath(args.out), f"cycles-{spp}.exr")
        seconds = cs.render(spp, seed, exr)
        row = {"spp": spp, "seconds": seconds, "exr": exr}
        renders.append(row)
        with open(os.path.join(args.out, "renders.json"), "w") as f:
            json.dump({"project": os.path.abspath(args.project), "seed": seed, "threads": args.threads,
                       "blender": bpy_version(), "artist": args.artist, "renders": renders}, f, indent=1)
        print("cycles-render: " + json.dumps(row), flush=True)
        if seconds >= args.budget:
            break


def bpy_version():
    import bpy
    return bpy.app.version_string


main()
