"""Checks that dp_cycles.py converts a diffphoton project faithfully (runs inside Blender 3.4, or
with Blender 5's Python: `.deps/bpy5/bin/python bench/cycles/check_conversion.py CHECK ...`).

    blender -b --factory-startup --python-exit-code 1 -P bench/cycles/check_conversion.py -- \\
        orientation --diffphoton build/app/diffphoton --out /tmp/cyc-orientation
    blender ... -P bench/cycles/check_conversion.py -- real-only out/bench/scenes/mirrors/scene.json \\
        --diffphoton build/app/diffphoton --width 128 --spp 1024 --out /tmp/cyc-real-mirrors
    blender ... -P bench/cycles/check_conversion.py -- composite out/bench/scenes/shadow_hard \\
        --diffphoton build/app/diffphoton --spp 1024 --out /tmp/cyc-composite
    blender ... -P bench/cycles/check_conversion.py -- materials \\
        --diffphoton build/app/diffphoton --spp 1024 --lold-spp 4096 --out /tmp/cyc-materials

orientation: probes that are black but one texel, an OpenCV camera aimed near it with an
  off-centre principal point (and, in a second camera, fx != fy): both renderers must put the
  texel where ours' projection says.
real-only: the real scene alone (proxies as plain diffuse, no catcher, no objects, the probe
  visible) in Cycles against `diffphoton reference --real-only`, which makes the photographs.
composite: the shadow-catcher composite against the scene's truth (standard differential
  rendering, truth-a.exr and truth-b.exr) where the camera sees an object, and against ours'
  multiplicative composite on real pixels (see check_composite).
materials: both of the above on a scene made here with textured proxies, tinted glass, a
  coloured mirror and a textured non-uniformly scaled sphere (see check_materials).

Each image is the mean of two halves with seeds 1 and 2, so that each renderer's own noise is
estimated from the halves (RMSE(half 1 - half 2) / 2 is the RMSE of their mean). Reports the
relative RMSE between the two, the noise expected if both are right, the same after a 2x2 box
filter (noise halves, a systematic difference does not) and the ratio of mean luminances;
writes check.json beside the images. See docs/cycles.md.
"""
import argparse
import array
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import time
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dp_cycles  # noqa: E402


# ---------------------------------------------------------------------------------------------
# EXR: a reader for the scanline files both renderers write here (ours' layered truths too,
# which Blender's image loader does not open), and a writer of plain RGB float files.


def _read_cstr(buf, pos):
    end = buf.index(b"\0", pos)
    return buf[pos:end].decode(), end + 1


def _read_header(buf, pos):
    """The attributes of one EXR header from `pos` and the position after it."""
    attrs = {}
    while True:
        name, pos = _read_cstr(buf, pos)
        if not name:
            return attrs, pos
        kind, pos = _read_cstr(buf, pos)
        size = struct.unpack_from("<i", buf, pos)[0]
        attrs[name] = (kind, buf[pos + 4:pos + 4 + size])
        pos += 4 + size


def _channels(attrs):
    stored, data, p = [], attrs["channels"][1], 0
    while data[p] != 0:
        name, p = _read_cstr(data, p)
        stored.append((name, struct.unpack_from("<i", data, p)[0]))
        p += 16
    return stored


def read_exr(path, layer="", channels="RGB"):
    """(width, height, floats interleaved as `channels`, rows top-down) of one layer ("" = R, G,
    B) of a scanline EXR with no, ZIPS or ZIP compression and half or float channels; single-part
    (Blender 3.4) or multi-part (Blender 5 writes a part per layer)."""
    with open(path, "rb") as f:
        buf = f.read()
    if struct.unpack_from("<I", buf, 0)[0] != 20000630:
        raise ValueError(f"{path}: not an EXR file")
    multipart = bool(struct.unpack_from("<I", buf, 4)[0] & 0x1000)
    headers, pos = [], 8
    while True:
        attrs, pos = _read_header(buf, pos)
        headers.append(attrs)
        if not multipart or buf[pos] == 0:
            break
    pos += 1 if multipart else 0
    want = [layer + "." + c if layer else c for c in channels]
    # The offset tables follow the headers, one per part, each as long as the part's chunks.
    tables = []
    for attrs in headers:
        xmin, ymin, xmax, ymax = struct.unpack("<4i", attrs["dataWindow"][1])
        lines = 16 if attrs["compression"][1][0] == 3 else 1
        chunks = (ymax - ymin + 1 + lines - 1) // lines
        tables.append(struct.unpack_from(f"<{chunks}Q", buf, pos))
        pos += 8 * chunks
    names = [c[0] for attrs in headers for c in _channels(attrs)]
    planes = {}
    for attrs, offsets in zip(headers, tables):
        stored = _channels(attrs)
        if not any(name in want for name, _ in stored):
            continue
        compression = attrs["compression"][1][0]
        if compression not in (0, 2, 3):
            raise ValueError(f"{path}: compression {compression} is not supported here (none, ZIPS, ZIP)")
        xmin, ymin, xmax, ymax = struct.unpack("<4i", attrs["dataWindow"][1])
        w, h = xmax - xmin + 1, ymax - ymin + 1
        lines = 16 if compression == 3 else 1
        for name, _ in stored:
            if name in want:
                planes[name] = array.array("f", bytes(4 * w * h))
        for off in offsets:
            off += 4 if multipart else 0  # a multi-part chunk starts with its part number
            y, size = struct.unpack_from("<ii", buf, off)
            raw = buf[off + 8:off + 8 + size]
            n_lines = min(lines, ymax - y + 1)
            expected = sum(w * (2 if t == 1 else 4) for _, t in stored) * n_lines
            if compression and size < expected:
                t = bytearray(zlib.decompress(raw))
                for i in range(1, len(t)):
                    t[i] = (t[i - 1] + t[i] - 128) & 0xFF
                half = (len(t) + 1) // 2
                out = bytearray(len(t))
                out[0::2] = t[:half]
                out[1::2] = t[half:]
                raw = bytes(out)
            p = 0
            for ly in range(n_lines):
                row = y - ymin + ly
                for name, ptype in stored:
                    nbytes = w * (2 if ptype == 1 else 4)
                    if name in planes:
                        fmt = f"<{w}e" if ptype == 1 else (f"<{w}f" if ptype == 2 else f"<{w}I")
                        planes[name][row * w:(row + 1) * w] = array.array("f", struct.unpack_from(fmt, raw, p))
                    p += nbytes
    for c in want:
        if c not in planes:
            raise ValueError(f"{path}: no channel {c} (channels: {', '.join(names)})")
    out = array.array("f", bytes(4 * len(want) * w * h))
    for k, c in enumerate(want):
        out[k::len(want)] = planes[c]
    return w, h, out


# ---------------------------------------------------------------------------------------------
# Statistics over RGB float arrays (pure Python: Blender's Python has no numpy here)


def luminance(rgb):
    return array.array("d", (0.2126 * rgb[i] + 0.7152 * rgb[i + 1] + 0.0722 * rgb[i + 2]
                             for i in range(0, len(rgb), 3)))


def mean(a, b):
    return array.array("f", ((x + y) * 0.5 for x, y in zip(a, b)))


def rmse(a, b, mask=None):
    if mask is None:
        return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)) / len(a))
    se, n = 0.0, 0
    for p, m in enumerate(mask):
        if m:
            for c in range(3):
                se += (a[3 * p + c] - b[3 * p + c]) ** 2
            n += 3
    return math.sqrt(se / max(n, 1))


def mean_lum(rgb, mask=None):
    lum = luminance(rgb)
    if mask is None:
        return sum(lum) / len(lum)
    vals = [v for v, m in zip(lum, mask) if m]
    return sum(vals) / max(len(vals), 1)


def pool2(rgb, w, h):
    """2x2 box filter (odd last row/column dropped)."""
    w2, h2 = w // 2, h // 2
    out = array.array("f", bytes(12 * w2 * h2))
    for y in range(h2):
        top, bottom = 3 * (2 * y) * w, 3 * (2 * y + 1) * w
        for x in range(w2):
            for c in range(3):
                k = 3 * 2 * x + c
                out[3 * (y * w2 + x) + c] = 0.25 * (rgb[top + k] + rgb[top + k + 3] +
                                                    rgb[bottom + k] + rgb[bottom + k + 3])
    return out


def clamped(rgb, ceiling):
    return array.array("f", (min(x, ceiling) for x in rgb))


def bench_ceiling(photo):
    """`diffphoton bench` clamps every channel at 8 times the photo's 99.9th-percentile
    luminance before measuring (a few pixels that see the sun in a mirror decide nothing)."""
    lum = sorted(luminance(photo))
    return 8.0 * lum[min(len(lum) - 1, int(0.999 * len(lum)))]


def compare(ours, cycles, w, h, mask=None, names=("ours", "cycles"), ceiling=None):
    """Relative RMSE between the two means (pixels in `mask`, all if None) against each one's
    noise from its halves, plain and after a 2x2 box filter, and the ratio of mean luminances;
    with `ceiling`, every channel is clamped there first."""
    if ceiling is not None:
        ours, cycles = [clamped(x, ceiling) for x in ours], [clamped(x, ceiling) for x in cycles]
    o, c = mean(*ours), mean(*cycles)
    norm = mean_lum(mean(o, c), mask)
    rel = rmse(o, c, mask) / norm
    noise_o = 0.5 * rmse(ours[0], ours[1], mask) / norm
    noise_c = 0.5 * rmse(cycles[0], cycles[1], mask) / norm
    expected = math.hypot(noise_o, noise_c)
    result = {
        "relative_rmse": rel,
        f"noise_{names[0]}": noise_o,
        f"noise_{names[1]}": noise_c,
        "noise_expected": expected,
        "excess_over_noise": math.sqrt(max(0.0, rel ** 2 - expected ** 2)),
        f"mean_ratio_{names[0]}_over_{names[1]}": mean_lum(o, mask) / mean_lum(c, mask),
        # The ratio's own noise: each mean's standard error from its halves' difference.
        "mean_ratio_noise": mean_ratio_noise(ours, cycles, mask),
    }
    if mask is None:
        po, pc = [pool2(x, w, h) for x in ours], [pool2(x, w, h) for x in cycles]
        mo, mc = mean(*po), mean(*pc)
        result["relative_rmse_2x2"] = rmse(mo, mc) / norm
        result["noise_expected_2x2"] = math.hypot(0.5 * rmse(po[0], po[1]) / norm, 0.5 * rmse(pc[0], pc[1]) / norm)
    return result


def mean_ratio_noise(ours, cycles, mask):
    """Standard error of the ratio of mean luminances. Pixels are independent, so the error of
    one renderer's mean luminance is std(lum half 1 - lum half 2) / (2 sqrt(pixels)); the two
    renderers' relative errors add in quadrature."""
    def rel_err(pair):
        everywhere = [True] * (len(pair[0]) // 3)
        d = [a - b for a, b, m in zip(luminance(pair[0]), luminance(pair[1]), mask or everywhere) if m]
        mu = sum(d) / len(d)
        sd = math.sqrt(sum((x - mu) ** 2 for x in d) / max(len(d) - 1, 1))
        return sd / (2 * math.sqrt(len(d))) / mean_lum(mean(*pair), mask)
    return math.hypot(rel_err(ours), rel_err(cycles))


# ---------------------------------------------------------------------------------------------
# Runs


def run_ours(diffphoton, args):
    r = subprocess.run([diffphoton] + args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"error: {' '.join([diffphoton] + args)} failed ({r.returncode}):\n{r.stderr}")


def prepared_project(project_path, width, workdir, diffphoton):
    """A copy of the project with absolute paths and, if `width` is given, a black photo of that
    width (the photo only sets the size of a real-only render) and intrinsics scaled to it."""
    with open(project_path) as f:
        project = json.load(f)
    base = os.path.dirname(os.path.abspath(project_path))
    res = lambda p: dp_cycles.resolve(base, p)  # noqa: E731
    project["photo"]["path"] = res(project["photo"]["path"])
    project["probe"]["path"] = res(project["probe"]["path"])
    for lst in ("real", "objects"):
        for e in project.get(lst, []):
            if e["shape"]["type"] == "mesh":
                e["shape"]["path"] = res(e["shape"]["path"])
            alb = e.get("albedo", e.get("material", {}).get("albedo"))
            if isinstance(alb, dict) and "texture" in alb:
                alb["texture"] = res(alb["texture"])
    if width:
        w0, h0 = exr_size(project["photo"]["path"])
        w, h = width, max(1, round(h0 * width / w0))
        cam = project["camera"]
        if cam.get("model", "lookat") == "opencv":
            s = w / w0
            cam["fx"], cam["fy"] = cam["fx"] * s, cam["fy"] * s
            cam["cx"], cam["cy"] = (cam["cx"] + 0.5) * s - 0.5, (cam["cy"] + 0.5) * s - 0.5
        photo = os.path.join(workdir, "black.exr")
        run_ours(diffphoton, ["make-test-image", photo, "--size", str(w), str(h), "--value", "0", "0", "0"])
        project["photo"]["path"] = photo
    out = os.path.join(workdir, "project.json")
    with open(out, "w") as f:
        json.dump(project, f, indent=1)
    return out


def exr_size(path):
    w, h, _ = read_exr(path)
    return w, h


def cycles_halves(project, mode, spp, out, threads, tag="cycles"):
    cs = dp_cycles.CyclesScene(project, mode=mode, threads=threads)
    imgs, seconds = [], 0.0
    for k, seed in enumerate((1, 2)):
        path = os.path.join(out, f"{tag}_{k}.exr")
        seconds += cs.render(spp, seed, path)
        imgs.append(read_exr(path)[2])
        print(f"  cycles half {k + 1}: {spp} spp", flush=True)
    return imgs, seconds


def check_real_only(args):
    os.makedirs(args.out, exist_ok=True)
    project = prepared_project(args.project, args.width, args.out, args.diffphoton)
    half = max(1, args.spp // 2)
    ours, t_ours = [], 0.0
    for k, seed in enumerate((1, 2)):
        path = os.path.join(args.out, f"ours_{k}.exr")
        t0 = time.time()
        run_ours(args.diffphoton, ["reference", project, "--real-only", "--spp", str(half), "--seed", str(seed),
                                   "--threads", str(args.threads), "-o", path])
        t_ours += time.time() - t0
        ours.append(read_exr(path)[2])
        print(f"  diffphoton half {k + 1}: {half} spp", flush=True)
    cyc, t_cyc = cycles_halves(project, "real-only", half, args.out, args.threads)
    w, h = exr_size(os.path.join(args.out, "ours_0.exr"))
    result = compare(ours, cyc, w, h)
    result.update({"check": "real-only", "project": args.project, "width": w, "height": h, "spp": 2 * half,
                   "seconds_ours": t_ours, "seconds_cycles": t_cyc})
    return report(args, result)


def check_composite(args):
    """Cycles' composite is photo * (L_new / L_old) on real pixels (its Shadow Catcher pass is
    that ratio); the truth is photo + (L_new - L_old). The two differ wherever the photo is not
    exactly L_old: the synthetic photos carry their own path-tracing noise. So real pixels are
    compared with ours' multiplicative composite photo * (1 + (truth - photo) / L_old), L_old
    from `diffphoton reference --real-only`, and the additive-multiplicative gap is reported;
    pixels that see an object (alpha 1: no photo in either) are compared with the truth."""
    os.makedirs(args.out, exist_ok=True)
    scene = os.path.join(args.project, "scene.json")
    truth = [read_exr(os.path.join(args.project, f"truth-{p}.exr"))[2] for p in "ab"]
    alpha = [read_exr(os.path.join(args.project, f"truth-{p}.exr"), "alpha")[2] for p in "ab"]
    w, h, photo = read_exr(os.path.join(args.project, "photo.exr"))
    half = max(1, args.spp // 2)
    cyc, t_cyc = cycles_halves(scene, "catcher", half, args.out, args.threads)
    l_old = []
    for k, seed in enumerate((11, 12)):
        path = os.path.join(args.out, f"l_old_{k}.exr")
        run_ours(args.diffphoton, ["reference", scene, "--real-only", "--spp", str(max(1, args.lold_spp // 2)),
                                   "--seed", str(seed), "--threads", str(args.threads), "-o", path])
        l_old.append(read_exr(path)[2])
        print(f"  diffphoton L_old half {k + 1}", flush=True)
    mult = [array.array("f", (p * (1 + (t - p) / lo) if lo > 0 else p for p, t, lo in zip(photo, tr, lo_k)))
            for tr, lo_k in zip(truth, l_old)]
    # Changed pixels as `diffphoton bench` counts them: seen through an object, or the truth's
    # luminance differs from the photo's by more than 1%.
    a_mean = [0.5 * (x + y) for x, y in zip(alpha[0][0::3], alpha[1][0::3])]
    t_mean, lum_p = luminance(mean(*truth)), luminance(photo)
    changed = [abs(t - p) > 0.01 * max(p, 1e-3) or al > 0 for t, p, al in zip(t_mean, lum_p, a_mean)]
    objects = [c and al >= 0.999 for c, al in zip(changed, a_mean)]
    real = [c and al == 0 for c, al in zip(changed, a_mean)]
    names = ("truth", "cycles")
    ceiling = bench_ceiling(photo)
    gap = rmse(mean(*mult), mean(*truth), real) / mean_lum(mean(*truth), real)
    result = {"check": "composite", "scene": args.project, "width": w, "height": h, "spp": 2 * half,
              "l_old_spp": 2 * max(1, args.lold_spp // 2), "seconds_cycles": t_cyc,
              "changed_pixels": sum(changed), "object_pixels": sum(objects), "real_changed_pixels": sum(real),
              "objects_against_truth": compare(truth, cyc, w, h, objects, names),
              "real_changed_against_multiplicative": compare(mult, cyc, w, h, real, ("multiplicative", "cycles")),
              "real_changed_against_truth": compare(truth, cyc, w, h, real, names),
              "changed_against_truth": compare(truth, cyc, w, h, changed, names),
              "gap_additive_multiplicative_real_changed": gap,
              # The same at the bench's ceiling, where caustic fireflies would decide the above.
              "ceiling": ceiling,
              "clamped_objects_against_truth": compare(truth, cyc, w, h, objects, names, ceiling),
              "clamped_real_changed_against_multiplicative": compare(mult, cyc, w, h, real,
                                                                     ("multiplicative", "cycles"), ceiling),
              "clamped_changed_against_truth": compare(truth, cyc, w, h, changed, names, ceiling)}
    return report(args, result)


MATERIALS_SCENE = {
    "schema_version": 1,
    "photo": {"path": "photo.exr"},
    "probe": {"path": "city-clamped.exr", "rotation_deg": [5, 35, -3], "intensity": 0.8},
    "camera": {"model": "lookat", "eye": [0.3, 1.5, 4.0], "target": [0, 0.4, 0], "vfov_deg": 40},
    "real": [
        {"name": "floor", "shape": {"type": "plane", "size": [8, 8]}, "albedo": {"texture": "ramps.exr"}},
        {"name": "crate", "shape": {"type": "box", "size": [0.6, 0.5, 0.4]},
         "transform": {"translation": [1.3, 0.25, -0.6], "rotation_deg": [0, 25, 0]},
         "albedo": {"texture": "ramps.exr"}},
        {"name": "ball", "shape": {"type": "sphere", "radius": 0.3},
         "transform": {"translation": [-1.3, 0.3, -0.5], "rotation_deg": [20, 70, -15]},
         "albedo": {"texture": "ramps.exr"}}],
    "objects": [
        {"name": "glass", "shape": {"type": "sphere", "radius": 0.35}, "transform": {"translation": [-0.4, 0.35, 0.3]},
         "material": {"type": "glass", "ior": 1.5, "tint": [0.6, 0.8, 1.0]}},
        {"name": "mirror", "shape": {"type": "box", "size": [0.4, 0.4, 0.4]},
         "transform": {"translation": [0.5, 0.2, 0.2], "rotation_deg": [0, 30, 0]},
         "material": {"type": "mirror", "reflectance": [0.9, 0.85, 0.8]}},
        {"name": "clay", "shape": {"type": "sphere", "radius": 0.25},
         "transform": {"translation": [0.1, 0.25, -0.7], "scale": [1.2, 1, 1]},
         "material": {"type": "diffuse", "albedo": {"texture": "ramps.exr"}}}],
    "render": {"max_depth": 8, "seed": 1},
}


def check_materials(args):
    """Textures on a plane, a box and an exact (rotated) sphere proxy, a tinted glass ball, a
    coloured mirror box and a textured, non-uniformly scaled sphere, under a rotated city probe
    clamped to 4 (its one-texel sun would bury everything in caustic fireflies): the real-only
    check, then photo and truth made here and the composite check, 128x72."""
    os.makedirs(args.out, exist_ok=True)
    w, h = 64, 32
    ramps = array.array("f", bytes(16 * w * h))
    for y in range(h):  # rows bottom-up: file row h - 1 - y
        for x in range(w):
            row = h - 1 - y
            ramps[4 * (y * w + x):4 * (y * w + x) + 4] = array.array(
                "f", [0.1 + 0.8 * (x + 0.5) / w, 0.1 + 0.8 * (row + 0.5) / h, 0.3 + 0.4 * ((x // 8 + row // 8) % 2), 1])
    save_exr(dp_cycles.float_image("ramps", w, h, ramps), os.path.join(args.out, "ramps.exr"))
    city = dp_cycles.bpy.data.images.load("/usr/share/blender/datafiles/studiolights/world/city.exr")
    px = array.array("f", (min(max(x, 0.0), 4.0) for x in dp_cycles.pixels_of(city)))
    save_exr(dp_cycles.float_image("city", city.size[0], city.size[1], px), os.path.join(args.out, "city-clamped.exr"))
    run_ours(args.diffphoton, ["make-test-image", os.path.join(args.out, "photo.exr"), "--size", "128", "72",
                               "--value", "0", "0", "0"])
    scene = os.path.join(args.out, "scene.json")
    with open(scene, "w") as f:
        json.dump(MATERIALS_SCENE, f, indent=1)
    real = argparse.Namespace(**vars(args))
    real.project, real.width, real.out = scene, 0, os.path.join(args.out, "real-only")
    os.makedirs(real.out, exist_ok=True)
    check_real_only(real)
    run_ours(args.diffphoton, ["reference", scene, "--real-only", "--spp", "1024", "--seed", "7",
                               "--threads", str(args.threads), "-o", os.path.join(args.out, "photo.exr")])
    for part, seed in (("a", 101), ("b", 202)):
        run_ours(args.diffphoton, ["render", scene, "--method", "standard-correlated", "--passes", "1024",
                                   "--seed", str(seed), "--threads", str(args.threads), "--layers",
                                   "-o", os.path.join(args.out, f"truth-{part}.exr")])
    comp = argparse.Namespace(**vars(args))
    comp.project, comp.out = args.out, os.path.join(args.out, "composite")
    return check_composite(comp)


def report(args, result):
    result["blender"] = dp_cycles.bpy.app.version_string
    with open(os.path.join(args.out, "check.json"), "w") as f:
        json.dump(result, f, indent=2)
    print(json.dumps(result, indent=2))
    return 0


def spot_centroid(rgb, w, h):
    lum = luminance(rgb)
    peak = max(lum)
    if peak <= 0:
        return float("nan"), float("nan")  # the texel is not in view
    sx = sy = sw = 0.0
    for i, v in enumerate(lum):
        if v > 0.5 * peak:
            sx += (i % w) * v
            sy += (i // w) * v
            sw += v
    return sx / sw, sy / sw


def check_orientation(args):
    """One bright texel, cameras whose principal point is off-centre and aimed near that texel's
    direction: ours' projection of the texel centre predicts where both renderers show it."""
    from mathutils import Vector
    os.makedirs(args.out, exist_ok=True)
    pw, ph, w, h = 256, 128, 96, 64
    rotation = [12.0, 35.0, -7.0]
    run_ours(args.diffphoton, ["make-test-image", os.path.join(args.out, "photo.exr"), "--size", str(w), str(h),
                               "--value", "0", "0", "0"])
    cases, ok = [], True
    for ti, tj, aspect in ((171, 37, 1.0), (178, 40, 0.8)):
        probe = array.array("f", bytes(4 * 4 * pw * ph))
        probe[3::4] = array.array("f", [1.0]) * (pw * ph)
        k = 4 * ((ph - 1 - tj) * pw + ti)  # Blender's rows are bottom-up
        probe[k:k + 3] = array.array("f", [100.0, 80.0, 60.0])
        probe_path = os.path.join(args.out, f"probe-{ti}-{tj}.exr")
        img = dp_cycles.float_image("probe", pw, ph, probe)
        save_exr(img, probe_path)
        # The camera looks along the first texel's direction, slightly off so that the second
        # texel (and fx != fy) is tested away from the principal point too.
        aim = dp_cycles.euler_xyz_deg(rotation) @ dp_cycles.latlong_direction(171.5 / pw, 37.5 / ph)
        d = dp_cycles.euler_xyz_deg(rotation) @ dp_cycles.latlong_direction((ti + 0.5) / pw, (tj + 0.5) / ph)
        right = aim.cross(Vector((0, 1, 0))).normalized()
        down = aim.cross(right)
        r = [list(right), list(down), list(aim)]
        cx, cy = 0.5 * (w - 1) + 13.3, 0.5 * (h - 1) - 9.6
        fy = 0.5 * h / math.tan(math.radians(12.0))
        fx = fy * aspect
        centre = Vector((0.3, 1.2, -0.4))
        cam = Vector((right.dot(d), down.dot(d), aim.dot(d)))
        expected = (fx * cam.x / cam.z + cx, fy * cam.y / cam.z + cy)
        project = {"schema_version": 1, "photo": {"path": "photo.exr"},
                   "probe": {"path": os.path.basename(probe_path), "rotation_deg": rotation},
                   "camera": {"model": "opencv", "fx": fx, "fy": fy, "cx": cx, "cy": cy, "rotation": r,
                              "translation": list(-(dp_cycles.Matrix(r) @ centre))}}
        path = os.path.join(args.out, f"orientation-{ti}-{tj}.json")
        with open(path, "w") as f:
            json.dump(project, f, indent=1)
        ours_exr = os.path.join(args.out, f"ours-{ti}-{tj}.exr")
        run_ours(args.diffphoton, ["reference", path, "--real-only", "--spp", "16", "-o", ours_exr])
        so = spot_centroid(read_exr(ours_exr)[2], w, h)
        cyc_exr = os.path.join(args.out, f"cycles-{ti}-{tj}.exr")
        dp_cycles.CyclesScene(path, mode="real-only", threads=args.threads).render(16, 1, cyc_exr)
        sc = spot_centroid(read_exr(cyc_exr)[2], w, h)
        good = all(abs(a - b) < 0.5 for a, b in ((so[0], expected[0]), (so[1], expected[1]),
                                                 (sc[0], expected[0]), (sc[1], expected[1])))
        ok &= good
        cases.append({"texel": [ti, tj], "fx_over_fy": aspect, "expected": expected, "ours": so, "cycles": sc})
        print(f"texel ({ti}, {tj}) of a {pw}x{ph} probe rotated {rotation} deg, fx/fy {aspect}: "
              f"expected ({expected[0]:.2f}, {expected[1]:.2f})  diffphoton ({so[0]:.2f}, {so[1]:.2f})  "
              f"cycles ({sc[0]:.2f}, {sc[1]:.2f})  {'OK' if good else 'MISMATCH'}", flush=True)
    with open(os.path.join(args.out, "check.json"), "w") as f:
        json.dump({"check": "orientation", "cases": cases, "ok": ok}, f, indent=2)
    print("orientation: " + ("OK" if ok else "MISMATCH"))
    return 0 if ok else 1


def save_exr(img, path):
    scene = dp_cycles.bpy.context.scene
    s = scene.render.image_settings
    s.file_format, s.color_mode, s.color_depth, s.exr_codec = "OPEN_EXR", "RGB", "32", "ZIP"
    img.save_render(path, scene=scene)


def main():
    argv = dp_cycles.script_args(__file__)
    ap = argparse.ArgumentParser(prog="check_conversion.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("check", choices=("orientation", "real-only", "composite", "materials"))
    ap.add_argument("project", nargs="?", help="real-only: a project; composite: a bench scene folder")
    ap.add_argument("--diffphoton", default=shutil.which("diffphoton"), help="diffphoton executable")
    ap.add_argument("--out", required=True, help="folder for the images and check.json")
    ap.add_argument("--spp", type=int, default=1024, help="samples per pixel of each renderer (two halves)")
    ap.add_argument("--width", type=int, default=0, help="real-only: render at this width (0: the photo's)")
    ap.add_argument("--threads", type=int, default=0, help="threads of both renderers (0: all cores)")
    ap.add_argument("--lold-spp", type=int, default=2048,
                    help="composite: samples per pixel of ours' real-only L_old (two halves)")
    args = ap.parse_args(argv)
    if not args.diffphoton:
        ap.error("--diffphoton: the diffphoton executable is needed")
    if args.check in ("real-only", "composite") and not args.project:
        ap.error(f"{args.check}: a project (real-only) or scene folder (composite) is needed")
    try:
        return {"orientation": check_orientation, "real-only": check_real_only,
                "composite": check_composite, "materials": check_materials}[args.check](args)
    except dp_cycles.ConversionError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
