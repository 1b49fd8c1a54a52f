#!/usr/bin/env python3
"""The progressive renderer (`diffphoton render`) against the truths of a cross-check.

Takes a project and the folder a `mitsuba_crosscheck.py` run left (ours_0/1.exr from
`diffphoton reference`, mitsuba_0/1.exr from Mitsuba 3, two independent halves each), makes
the photograph the differential render needs (`diffphoton reference --real-only`, two halves:
the crosscheck scenes' own photos are black placeholders), renders the project with
`diffphoton render` at several pass counts and reports, against each truth:

- relative RMSE over the whole image (RMSE of render - truth over mean truth luminance), next
  to the truth's and the photograph's own noise (half the RMSE between their halves);
- the same after a 9x9 box filter over the image (noise falls about ninefold, a bias does
  not), with the truth's and the photo's filtered noise: a smoothed error that keeps falling
  with passes is no bias at that level;
- the mean luminance ratio render / truth over the pixels that see a virtual sphere, and over
  the real surfaces the objects darken by more than 5% in the truth (their shadows).

Developer tool, like mitsuba_crosscheck.py (docs/crosscheck.md):

    python3 bench/crosscheck/progressive_check.py resources/bench/crosscheck/gold_ball.json \\
        --truth /tmp/xc-gold_ball --diffphoton build/app/diffphoton --passes 16 64 256 \\
        --out /tmp/pc-gold_ball
"""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba as mi  # noqa: E402

import mitsuba_crosscheck as xc  # noqa: E402


def read(path):
    import OpenEXR
    with OpenEXR.File(path) as f:
        ch = f.channels()
        for key in ("RGB", "RGBA"):
            if key in ch:
                return np.asarray(ch[key].pixels, dtype=np.float64)[..., :3]
        return np.dstack([np.asarray(ch[c].pixels, dtype=np.float64) for c in "RGB"])


def box(x, k):
    """k x k box filter, 'valid' part only (no edge handling to bias the figure)."""
    c = np.cumsum(np.cumsum(np.pad(x, ((1, 0), (1, 0), (0, 0))), axis=0), axis=1)
    return (c[k:, k:] - c[:-k, k:] - c[k:, :-k] + c[:-k, :-k]) / (k * k)


def rmse(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("project")
    ap.add_argument("--truth", required=True, help="output folder of a mitsuba_crosscheck.py run")
    ap.add_argument("--diffphoton", required=True)
    ap.add_argument("--passes", type=int, nargs="+", default=[16, 64, 256])
    ap.add_argument("--photo-spp", type=int, default=16384, help="samples per pixel of the photograph (two halves)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--smooth", type=int, default=9)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    mi.set_variant("scalar_rgb")
    os.makedirs(args.out, exist_ok=True)

    with open(os.path.join(args.truth, "project.json")) as f:
        project = json.load(f)
    truth_project = os.path.join(args.truth, "project.json")
    halves = {"ours": [read(os.path.join(args.truth, f"ours_{k}.exr")) for k in (0, 1)],
              "mitsuba": [read(os.path.join(args.truth, f"mitsuba_{k}.exr")) for k in (0, 1)]}

    # The photograph: the real scene alone, two halves.
    photo_halves = []
    for k, seed in enumerate((101, 102)):
        path = os.path.join(args.out, f"photo_{k}.exr")
        if not os.path.exists(path):
            subprocess.run([args.diffphoton, "reference", truth_project, "--real-only", "-o", path, "--spp",
                            str(args.photo_spp // 2), "--seed", str(seed)], check=True, stdout=subprocess.DEVNULL)
        photo_halves.append(read(path))
    photo = 0.5 * (photo_halves[0] + photo_halves[1])
    photo_path = os.path.join(args.out, "photo.exr")
    xc.write_rgb(photo_path, photo)
    project["photo"]["path"] = photo_path
    project_path = os.path.join(args.out, "project.json")
    with open(project_path, "w") as f:
        json.dump(project, f, indent=2)

    h, w = photo.shape[:2]
    mask = xc.object_mask(project, w, h)
    k = args.smooth
    result = {"project": args.project, "truth": args.truth, "width": w, "height": h, "photo_spp": args.photo_spp,
              "smooth": k, "object_pixels": int(mask.sum()), "truths": {}, "renders": []}
    truths = {name: 0.5 * (hv[0] + hv[1]) for name, hv in halves.items()}
    for name, hv in halves.items():
        t = truths[name]
        norm = float(np.mean(xc.luminance(t)))
        result["truths"][name] = {
            "mean_luminance": norm,
            "noise": 0.5 * rmse(hv[0], hv[1]) / norm,
            "noise_smoothed": 0.5 * rmse(box(hv[0], k), box(hv[1], k)) / norm,
            "photo_noise": 0.5 * rmse(photo_halves[0], photo_halves[1]) / norm,
            "photo_noise_smoothed": 0.5 * rmse(box(photo_halves[0], k), box(photo_halves[1], k)) / norm,
        }
    for name, t in truths.items():
        # The real surfaces the objects darken by more than 5% (their shadows), in this truth.
        shade = ~mask & (xc.luminance(t - photo) < -0.05 * xc.luminance(t))
        result["truths"][name]["shadow_pixels"] = int(shade.sum())
        if shade.any():  # how far the truth's own halves are from their mean there
            hv = halves[name]
            lum = [float(np.mean(xc.luminance(x)[shade])) for x in hv]
            result["truths"][name]["shadow_noise"] = abs(lum[0] - lum[1]) / (lum[0] + lum[1])
        hv = halves[name]
        lum = [float(np.mean(xc.luminance(x)[mask])) for x in hv]
        result["truths"][name]["object_noise"] = abs(lum[0] - lum[1]) / (lum[0] + lum[1])
    for n in args.passes:
        path = os.path.join(args.out, f"render_{n}.exr")
        if not os.path.exists(path):
            subprocess.run([args.diffphoton, "render", project_path, "-o", path, "--passes", str(n), "--seed",
                            str(args.seed)], check=True, stdout=subprocess.DEVNULL)
        r = read(path)
        row = {"passes": n}
        for name, t in truths.items():
            norm = result["truths"][name]["mean_luminance"]
            tn = result["truths"][name]
            smoothed = rmse(box(r, k), box(t, k)) / norm
            shade = ~mask & (xc.luminance(t - photo) < -0.05 * xc.luminance(t))
            row[name] = {
                "relative_rmse": rmse(r, t) / norm,
                "relative_rmse_smoothed": smoothed,
                # What the truth's and the photo's smoothed noise do not explain (the render's
                # own noise is left in).
                "smoothed_excess": math.sqrt(max(0.0, smoothed ** 2 - tn["noise_smoothed"] ** 2 -
                                                 tn["photo_noise_smoothed"] ** 2)),
                "shadow_mean_ratio": float(np.mean(xc.luminance(r)[shade]) / np.mean(xc.luminance(t)[shade]))
                if shade.any() else None,
                "mean_ratio": float(np.mean(xc.luminance(r)) / np.mean(xc.luminance(t))),
                "object_mean_ratio": float(np.mean(xc.luminance(r)[mask]) / np.mean(xc.luminance(t)[mask])),
                "outside_mean_ratio": float(np.mean(xc.luminance(r)[~mask]) / np.mean(xc.luminance(t)[~mask])),
            }
        result["renders"].append(row)
        print(json.dumps(row), flush=True)
    with open(os.path.join(args.out, "progressive.json"), "w") as f:
        json.dump(result, f, indent=2)
    print(json.dumps(result["truths"], indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
