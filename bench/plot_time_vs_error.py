#!/usr/bin/env python3
"""Plots run time against error from `diffphoton bench` rows and writes a Markdown summary.

Usage: plot_time_vs_error.py rows.json --out DIR
Writes DIR/<scene>.png (log-log relative RMSE over changed pixels against seconds, each
method, the truth's noise floor) and DIR/summary.md. With rows of the `cycles` method (Blender
3.4 Cycles' shadow catcher), the summary gives each of our methods' speed-up against Cycles: how
many times sooner it reached the same error. Rows of `cycles5` and `cycles5-artist` (Blender 5,
raw and as artists run it) are plotted and tabulated like any method.
"""
import argparse
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

THRESHOLDS = (0.05, 0.02, 0.01)
CYCLES_THRESHOLDS = (0.05, 0.02, 0.01, 0.005)  # levels of the speed-up against Cycles
STYLE = {"differential": ("tab:blue", "differential photon mapping"),
         "differential-denoised": ("navy", "differential, denoised (filter time included)"),
         "differential-photons": ("tab:cyan", "differential, all-photon estimator"),
         "differential-random": ("tab:purple", "differential, no low-discrepancy points"),
         "differential-uniform": ("tab:gray", "differential, no adaptive sampling"),
         "differential-fixed-photons": ("darkgoldenrod", "differential, the project's photons in every pass"),
         "standard": ("tab:red", "standard (two independent simulations)"),
         "standard-correlated": ("tab:orange", "standard, correlated sampling"),
         "cycles": ("tab:green", "Blender 3.4 Cycles, shadow catcher"),
         "cycles5": ("tab:olive", "Blender 5 Cycles, shadow catcher"),
         "cycles5-artist": ("tab:brown", "Blender 5 Cycles as artists run it (denoised)")}
CYCLES_METHODS = ("cycles", "cycles5", "cycles5-artist")
# The Cycles runs our methods' speed-ups are measured against, with their column titles.
CYCLES_REFERENCES = (("cycles", "Cycles 3.4"), ("cycles5-artist", "Cycles 5 as artists run it"))


def add_denoised_rows(doc):
    """`bench --denoise` rows of differential photon mapping as a method of their own: the
    denoised image's error, at the render's time plus the filter's."""
    for r in list(doc["rows"]):
        if r["method"] == "differential" and "rel_rmse_changed_denoised" in r:
            d = dict(r, method="differential-denoised", seconds=r["seconds"] + r.get("denoise_seconds", 0.0),
                     rel_rmse_changed=r["rel_rmse_changed_denoised"])
            d.pop("rel_rmse", None)  # not measured denoised: the no-op scene has no such row
            doc["rows"].append(d)
    doc["rows"] = [r for r in doc["rows"] if r["method"] != "differential-denoised" or "rel_rmse" in r
                   or any(s["scene"] == r["scene"] and s["changed_pixels"] > 0 for s in doc["scenes"])]


def error_key(scene):
    """Changed-pixel error, or the whole image's where nothing changes (the no-op scene)."""
    return "rel_rmse_changed" if scene["changed_pixels"] > 0 else "rel_rmse"


def corrected(error, floor):
    """Error against the exact image: the truth's own noise is independent of a method's error,
    so squared errors add and the truth's part can be taken out in quadrature."""
    return math.sqrt(max(error * error - floor * floor, 0.0))


def time_to_reach(rows, key, target, floor=0.0):
    """Seconds at which the (noise-corrected) error first falls to `target`, interpolated
    log-log; None if never."""
    prev = None
    for r in rows:
        e = corrected(r[key], floor)
        if e <= target:
            if prev is None or prev[1] <= 0 or e <= 0:
                return r["seconds"]
            (t0, e0), (t1, e1) = prev, (r["seconds"], e)
            f = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
        prev = (r["seconds"], e)
    return None


def speedup(t_differential, t_other, other_budget):
    """How many times sooner differential photon mapping reached a level than another method."""
    if t_differential is None or t_differential <= 0:
        return "n/a" if t_other is None else "differential not reached"
    if t_other is None:
        return f"> {other_budget / t_differential:.1f}x (not reached)"
    return f"{t_other / t_differential:.1f}x"


def speedup_against_cycles(t_ours, t_cycles, cycles_final):
    """How many times sooner one of our methods reached a level than Cycles did."""
    if t_ours is None or t_ours <= 0:
        return "n/a" if t_cycles is None else "not reached"
    if t_cycles is None:
        return f"> {cycles_final / t_ours:.1f}x"
    return f"{t_cycles / t_ours:.1f}x"


def fmt_time(t):
    return "not reached" if t is None else (f"{t:.2f} s" if t < 100 else f"{t:.0f} s")


def cycles_cells(references, method, levels):
    """The speed-up-against-Cycles cells of one of our methods' rows, one per reference Cycles
    run present ("" when none is, so that the table keeps its old columns)."""
    out = ""
    for ref, _ in references:
        if method in CYCLES_METHODS:
            out += " | "
        elif ref not in levels:
            out += " | n/a"
        else:
            final = levels[ref][-1]
            out += " | " + " / ".join(speedup_against_cycles(t, tc, final)
                                      for t, tc in zip(levels[method][:-1], levels[ref][:-1]))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rows")
    ap.add_argument("--out", required=True)
    ap.add_argument("--image-prefix", default="", help="prefix of the PNG links in summary.md")
    ap.add_argument("--pairs", help="rows.json of alternating shadow_hard / big_proxy runs")
    ap.add_argument("--note", default="", help="a line about the machine, printed under the table")
    args = ap.parse_args()
    doc = json.load(open(args.rows))
    add_denoised_rows(doc)
    os.makedirs(args.out, exist_ok=True)
    methods = [m for m in STYLE if any(r["method"] == m for r in doc["rows"])]
    references = [(m, title) for m, title in CYCLES_REFERENCES if m in methods]
    with_cycles = bool(references)
    cycles_head = "".join(f" | speed-up against {title} at " + " / ".join(f"{100 * t:g}%" for t in CYCLES_THRESHOLDS)
                          for _, title in references)
    lines = ["| scene | changed px | truth noise | method | " +
             " | ".join(f"time to {int(t * 100)}%" for t in THRESHOLDS) +
             " | time to 2x truth noise | final error (raw) | final time | speed-up at 5% | at 2% | at 2x noise" +
             cycles_head + " |",
             "|---|---|---|---|" + "---|" * len(THRESHOLDS) + "---|---|---|---|---|---|" + "---|" * len(references)]
    pass_times = {}
    for scene in doc["scenes"]:
        name, key = scene["scene"], error_key(scene)
        floor = scene["truth_rel_rmse_changed" if key == "rel_rmse_changed" else "truth_rel_rmse"]
        fig, ax = plt.subplots(figsize=(6, 4), dpi=110)
        reach, reach_cycles_levels = {}, {}
        for m in methods:
            rows = [r for r in doc["rows"] if r["scene"] == name and r["method"] == m]
            if not rows:
                continue
            color, label = STYLE[m]
            t = [r["seconds"] for r in rows]
            ax.loglog(t, [max(corrected(r[key], floor), 1e-6) for r in rows], "o-", ms=3, color=color,
                      label=label)
            ax.loglog(t, [max(r[key], 1e-6) for r in rows], "--", color=color, lw=1)
            reach[m] = [time_to_reach(rows, key, x, floor) for x in THRESHOLDS] + [
                rows[-1][key], rows[-1]["seconds"], time_to_reach(rows, key, 2 * floor),
                corrected(rows[-1][key], floor)]
            reach_cycles_levels[m] = [time_to_reach(rows, key, x, floor) for x in CYCLES_THRESHOLDS] + [rows[-1]["seconds"]]
            if m in CYCLES_METHODS:  # a Cycles "pass" is one render: time per sample of the last one
                pass_times[(name, m)] = rows[-1]["seconds"] / rows[-1]["passes"]
        for run in doc["runs"]:
            if run["scene"] == name and run["method"] not in CYCLES_METHODS:
                pass_times[(name, run["method"])] = run["median_pass_seconds"]
        ax.axhline(floor, color="grey", ls="--", lw=1, label="truth's noise")
        ax.set_xlabel("render time (s)")
        ax.set_ylabel("relative RMSE " + ("over changed pixels" if key == "rel_rmse_changed" else "(whole image)"))
        ax.set_title(f"{name} (dashed: before removing the truth's noise)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, f"{name}.png"))
        plt.close(fig)
        diff = reach.get("differential", [None] * 7)
        for m in methods:
            if m not in reach:
                continue
            r = reach[m]
            lines.append(f"| {name} | {scene['changed_pixels']} | {100 * floor:.2f}% | {m} | " +
                         " | ".join(fmt_time(t) for t in r[:3]) + f" | {fmt_time(r[5])}" +
                         f" | {100 * r[6]:.2f}% ({100 * r[3]:.2f}%) | {r[4]:.1f} s | " +
                         " | ".join(speedup(diff[i], r[i], r[4]) if m != "differential" else ""
                                    for i in (0, 1, 5)) + cycles_cells(references, m, reach_cycles_levels) + " |")
    out = ["Relative RMSE over the pixels the virtual objects change (whole image for the no-op "
           "scene) against render time, with the truth's own noise taken out in quadrature "
           "(sqrt(e^2 - noise^2); the raw figure in brackets and dashed in the plots); times "
           "interpolated log-log between measurements. 'time to 2x truth noise' uses the raw error."
           + (" 'speed-up against Cycles': Cycles' time to each level over the method's ('> Nx': Cycles "
              "never reached it within its budget; see docs/cycles.md for its error floor)."
              if with_cycles else ""), ""]
    out += lines
    if args.note:
        out += ["", "Machine: " + args.note]
    if args.pairs:
        # Alternating short runs of the two scenes, so that both see the same machine load.
        pairs = json.load(open(args.pairs))["runs"]
        big = [r["median_pass_seconds"] for r in pairs if r["scene"] == "big_proxy"]
        small = [r["median_pass_seconds"] for r in pairs if r["scene"] == "shadow_hard"]
        ratios = sorted(b / s for b, s in zip(big, small))
        out += ["", f"Time per differential pass with the 1M-triangle proxy against the same scene "
                f"without it (`big_proxy` / `shadow_hard`, {len(ratios)} alternating pairs of "
                f"short runs): median ratio {ratios[len(ratios) // 2]:.2f} (pairs: "
                + ", ".join(f"{r:.2f}" for r in ratios) + "; target 1.3)."]
    timed = [m for m in methods if m != "differential-denoised"]  # its passes are differential's
    out += ["", "Median time per pass (s)" + ("; for the Cycles methods, seconds per sample per pixel of the last "
                                             "render" if any(m in CYCLES_METHODS for m in methods) else "") + ":",
            "", "| scene | " + " | ".join(timed) + " |",
            "|---|" + "---|" * len(timed)]
    for scene in doc["scenes"]:
        n = scene["scene"]
        out.append(f"| {n} | " + " | ".join(f"{pass_times.get((n, m), float('nan')):.3f}" for m in timed) + " |")
    out += ["", "Plots (solid: changed pixels, truth's noise removed; dashed: raw; grey: the truth's noise):", ""]
    out += [" ".join(f"![{s['scene']}]({args.image_prefix}{s['scene']}.png)" for s in doc["scenes"][i:i + 2])
            for i in range(0, len(doc["scenes"]), 2)]
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write("\n".join(out) + "\n")
    print(f"wrote {args.out}/summary.md and {len(doc['scenes'])} plots")


if __name__ == "__main__":
    main()
