#!/usr/bin/env python3
"""Cross-check diffphoton's reference path tracer against Mitsuba 3.

Reads a diffphoton project (docs/project-format.md), builds the same scene for Mitsuba 3
(perspective sensor, envmap emitter, rectangle/cube/sphere/obj/ply shapes, diffuse/conductor/
dielectric BSDFs, the principled material as principled/roughplastic/roughdielectric blends, a
.gltf mesh's own metallic-roughness material with its base colour, metallic-roughness and normal
textures as bitmap textures under Mitsuba's normalmap, the virtual lights as point/spot emitters
and emitting rectangles and disks), renders it with Mitsuba's path tracer and with `diffphoton reference` (the
virtual objects included, full global illumination), each as two independent half-spp images,
and reports the relative RMSE between the two truths next to each one's own noise.

A developer tool: it needs `pip install mitsuba numpy OpenEXR` (the scalar_rgb variant needs no
LLVM; OpenEXR reads the probes, see read_exr_openexr) and is not part of the build or of CI.
See docs/crosscheck.md.

    python3 bench/crosscheck/mitsuba_crosscheck.py resources/sample/sample.json \\
        --diffphoton build/app/diffphoton --width 160 --spp 1024 --out /tmp/crosscheck
    python3 bench/crosscheck/mitsuba_crosscheck.py --check-orientation \\
        --diffphoton build/app/diffphoton --out /tmp/orientation
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import time

import numpy as np

try:
    import mitsuba as mi
except ImportError:  # pragma: no cover - developer tool
    sys.exit("error: this check needs Mitsuba 3: pip install mitsuba numpy")

# The glTF part lives in its own file and reads this module's helpers: run as a script, this
# module must be the one it imports.
sys.modules.setdefault("mitsuba_crosscheck", sys.modules[__name__])
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gltf_mitsuba as gltf  # noqa: E402


# ---------------------------------------------------------------------------------------------
# Conventions (docs/project-format.md)


def rot_x(deg):
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]], dtype=np.float64)


def rot_y(deg):
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]], dtype=np.float64)


def rot_z(deg):
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]], dtype=np.float64)


def euler_xyz_deg(r):
    """d_world = Rz * Ry * Rx * d_local (X applied first), as core/probe euler_xyz_deg."""
    return rot_z(r[2]) @ rot_y(r[1]) @ rot_x(r[0])


def mat4(r3=None, t=None, s=None):
    m = np.eye(4)
    if s is not None:
        m = np.diag([s[0], s[1], s[2], 1.0])
    if r3 is not None:
        r = np.eye(4)
        r[:3, :3] = r3
        m = r @ m
    if t is not None:
        tr = np.eye(4)
        tr[:3, 3] = t
        m = tr @ m
    return m


def object_matrix(transform):
    """M = T * Rz * Ry * Rx * S."""
    transform = transform or {}
    return mat4(euler_xyz_deg(transform.get("rotation_deg", [0, 0, 0])), transform.get("translation", [0, 0, 0]),
                transform.get("scale", [1, 1, 1]))


def latlong_direction(u, v):
    """Probe-space direction of lat-long coordinates (u, v) in [0, 1): diffphoton's convention."""
    theta, phi = math.pi * v, 2 * math.pi * (u - 0.5)
    return np.array([math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi)])


# Mitsuba's envmap looks up a local direction d at u = atan2(d.x, -d.z) / 2 pi, v = acos(d.y) / pi
# (verified by --check-orientation): its u is diffphoton's u - 1/2, a half turn about +Y. So the
# emitter's to_world is the probe rotation followed by... preceded by a 180 degree turn about Y.
MITSUBA_ENVMAP_FROM_PROBE = rot_y(180.0)
# Rows differ too: Mitsuba's v is a bitmap row index over (H - 1), ours over H (see emitter_dict).


def luminance(img):
    return 0.2126 * img[..., 0] + 0.7152 * img[..., 1] + 0.0722 * img[..., 2]


# ---------------------------------------------------------------------------------------------
# Images


def read_exr_openexr(path):
    """RGB of an EXR through the OpenEXR Python bindings, or None when they are missing.

    Mitsuba 3.9.1's bundled OpenEXR decodes DWAB-compressed float EXRs (Blender's studio-light
    probes) with wrong chroma: same luminance, colour shifted (see docs/crosscheck.md). Debian's
    OpenEXR 3.1, which diffphoton uses, and OpenEXR 3.5 agree with each other."""
    try:
        import OpenEXR
    except ImportError:
        return None
    with OpenEXR.File(path) as f:
        ch = f.channels()
        if "RGB" in ch:
            return np.asarray(ch["RGB"].pixels, dtype=np.float32)
        if all(c in ch for c in "RGB"):
            return np.dstack([np.asarray(ch[c].pixels, dtype=np.float32) for c in "RGB"])
    return None


def read_rgb(path):
    a = read_exr_openexr(path) if path.lower().endswith(".exr") else None
    if a is None:
        a = np.array(mi.Bitmap(path), dtype=np.float32)
    if a.ndim == 2:
        a = a[..., None]
    if a.shape[2] == 1:
        a = np.repeat(a, 3, axis=2)
    a = a[..., :3]
    return np.where(np.isfinite(a), a, 0.0).astype(np.float32)


def write_rgb(path, a):
    mi.Bitmap(np.ascontiguousarray(a, dtype=np.float32), pixel_format=mi.Bitmap.PixelFormat.RGB).write(path)


def image_size(path):
    w, h = mi.Bitmap(path).size()
    return int(w), int(h)


# ---------------------------------------------------------------------------------------------
# Project -> Mitsuba


class Unsupported(Exception):
    pass


def resolve(base_dir, p):
    return p if os.path.isabs(p) else os.path.normpath(os.path.join(base_dir, p))


def camera_pose(cam, width, height):
    """World-to-camera R (rows: right, down, forward), camera centre, fx, fy, cx, cy."""
    if cam.get("model", "lookat") == "lookat":
        eye = np.array(cam["eye"], dtype=np.float64)
        target = np.array(cam["target"], dtype=np.float64)
        up = np.array(cam.get("up", [0, 1, 0]), dtype=np.float64)
        fwd = target - eye
        fwd /= np.linalg.norm(fwd)
        right = np.cross(fwd, up)
        right /= np.linalg.norm(right)
        down = np.cross(fwd, right)
        f = 0.5 * height / math.tan(0.5 * math.radians(cam.get("vfov_deg", 45.0)))
        return np.array([right, down, fwd]), eye, f, f, 0.5 * (width - 1), 0.5 * (height - 1)
    if any(abs(k) > 0 for k in cam.get("distortion", [])):
        raise Unsupported("camera.distortion: Mitsuba's perspective sensor has no lens distortion")
    r = np.array(cam["rotation"], dtype=np.float64)
    t = np.array(cam["translation"], dtype=np.float64)
    return r, -r.T @ t, cam["fx"], cam["fy"], cam["cx"], cam["cy"]


def sensor_dict(cam, width, height, spp):
    r, centre, fx, fy, cx, cy = camera_pose(cam, width, height)
    if abs(fx - fy) > 1e-4 * fy:
        raise Unsupported("camera: fx != fy (Mitsuba's perspective sensor has square pixels)")
    to_world = np.eye(4)
    # Mitsuba's camera looks along local +Z with +X to the left of the image and +Y up.
    to_world[:3, 0] = -r[0]
    to_world[:3, 1] = -r[1]
    to_world[:3, 2] = r[2]
    to_world[:3, 3] = centre
    return {
        "type": "perspective",
        "to_world": mi.ScalarTransform4f(to_world),
        "fov_axis": "y",
        "fov": math.degrees(2 * math.atan(0.5 * height / fy)),
        # Offsets in film units: a pixel centre (i + 0.5) / W maps to the ray of the centred
        # camera at (i + 0.5) / W + offset; diffphoton's pixel i has its centre at x = i.
        "principal_point_offset_x": (0.5 * (width - 1) - cx) / width,
        "principal_point_offset_y": (0.5 * (height - 1) - cy) / height,
        "near_clip": 1e-4,
        "film": {
            "type": "hdrfilm",
            "width": width,
            "height": height,
            "rfilter": {"type": "box"},  # diffphoton jitters uniformly inside the pixel
            "pixel_format": "rgb",
        },
        "sampler": {"type": SAMPLER, "sample_count": spp},
    }


def emitter_dict(probe, base_dir, upsample):
    if probe.get("format", "latlong") != "latlong":
        raise Unsupported("probe.format: only lat-long probes (unwrap mirror balls first)")
    # Mitsuba rejects negative radiance samples; diffphoton never samples such pixels either
    # (their largest magnitude in the Blender probes is ~1e-3).
    img = np.maximum(read_rgb(resolve(base_dir, probe["path"])), 0.0)
    # diffphoton's probe is piecewise constant per pixel, row j covering theta in
    # [j, j + 1) pi / H. Mitsuba interpolates bilinearly and puts row k of its bitmap at
    # theta = k pi / (H' - 1), columns at pixel centres. With H' = m H + 1 rows, row m j lies
    # on our boundary between rows j - 1 and j (it gets their mean) and the m - 1 rows between
    # boundaries inside pixel j (its value): the interpolation ramps are symmetric about our
    # edges, so each pixel keeps its direction and flux. (Repeating rows m times instead would
    # lift a one-pixel sun at 43 degrees by 0.09 degrees: 0.15% more light on the ground.)
    h, w = img.shape[:2]
    # The ramps are 1/m of a pixel wide: visible where the camera sees a sharp probe edge
    # (a horizon) directly, so small probes get a larger m (about 2048 rows in all).
    m = max(1, upsample) if upsample > 0 else max(1, 2048 // h)
    k = np.arange(m * h + 1)
    inside = img[np.minimum(k // m, h - 1)]
    below = img[np.maximum(k // m - 1, 0)]
    rows = np.where((k % m == 0)[:, None, None], 0.5 * (inside + below), inside)
    img = np.repeat(rows, m, axis=1).astype(np.float32)
    to_world = np.eye(4)
    to_world[:3, :3] = euler_xyz_deg(probe.get("rotation_deg", [0, 0, 0])) @ MITSUBA_ENVMAP_FROM_PROBE
    return {
        "type": "envmap",
        "bitmap": mi.Bitmap(np.ascontiguousarray(img), pixel_format=mi.Bitmap.PixelFormat.RGB),
        "scale": float(probe.get("intensity", 1.0)),
        "to_world": mi.ScalarTransform4f(to_world),
    }


def rgb(c):
    return {"type": "rgb", "value": [float(x) for x in c]}


def diffuse_bsdf(albedo, where):
    if not isinstance(albedo, list):
        raise Unsupported(f"{where}: only constant [r, g, b] albedos (not textures or 'estimate')")
    # diffphoton clamps reflectance to [0, 0.98] (Surface::reflectance_at); its surfaces are
    # two-sided.
    clamped = [min(max(float(a), 0.0), 0.98) for a in albedo]
    return {"type": "twosided", "material": {"type": "diffuse", "reflectance": rgb(clamped)}}


def material_bsdf(m, where):
    kind = m.get("type", "diffuse")
    if kind == "diffuse":
        return diffuse_bsdf(m.get("albedo", [0.5, 0.5, 0.5]), where + ".albedo")
    if kind == "mirror":
        return {"type": "twosided", "material": {"type": "conductor", "material": "none",
                                                 "specular_reflectance": rgb(m.get("reflectance", [0.95] * 3))}}
    if kind == "glass":
        # diffphoton applies `tint` once per pass through the object (on the way in); Mitsuba
        # applies specular_transmittance at every crossing, so each crossing takes sqrt(tint).
        tint = [math.sqrt(float(t)) for t in m.get("tint", [1, 1, 1])]
        return {"type": "dielectric", "int_ior": float(m.get("ior", 1.5)), "ext_ior": 1.0,
                "specular_transmittance": rgb(tint)}
    if kind == "principled":
        return principled_bsdf(m, where)
    raise Unsupported(f"{where}.type: {kind}")


# principled_at (core/assets/principled_scatter.cpp) raises every roughness to this.
SPECULAR_ROUGHNESS = 0.03


_PLASTIC_SCALE = {}
# Set by --plastic-raw: leave roughplastic's own normalisation (energy lost with roughness).
PLASTIC_RAW = False
# Set by --sampler: Mitsuba's sampler. Ours places the pixel samples on a rotated R2 sequence
# (reference_camera_ray), so that a pixel partly covered by something bright (a sun's glint on
# smooth metal) is far less noisy in ours than with Mitsuba's `independent`; a stratified
# sampler (`multijitter`, `ldsampler`) lowers Mitsuba's noise there, though not to ours
# (docs/crosscheck.md, textured glTF objects). Any of them is unbiased.
SAMPLER = "independent"


def roughplastic_energy_scale(alpha, ior):
    """The factor on roughplastic's diffuse_reflectance that makes a white plastic return all
    the light at normal incidence, as ours does (docs/crosscheck.md).

    Mitsuba normalises the base by 1 / (eta^2 (1 - R_int)), R_int its single-scattering rough
    internal reflectance: a white roughplastic keeps 0.98 at alpha 0.0009 but 0.84 at 0.16
    and 0.34 at 1 (mitsuba3 issue #1155 met the same in a furnace). Ours weights the base by
    (1 - E(mu_o)) (1 - E(mu_i)) / (1 - E_avg), white returning exactly what the layer does not
    reflect. Mitsuba's base term is t(mu_o) t(mu_i) times a constant, so one factor makes the
    same form: (1 - glossy albedo) / diffuse albedo of a white base, both at normal incidence,
    integrated here from Mitsuba's own BSDF (the diffuse in mu by the midpoint rule, the
    glossy by 20,000 stratified visible-normal samples)."""
    key = (round(alpha, 8), round(ior, 8))
    if key in _PLASTIC_SCALE:
        return _PLASTIC_SCALE[key]
    b = mi.load_dict({"type": "roughplastic", "distribution": "ggx", "alpha": alpha, "int_ior": ior,
                      "ext_ior": 1.0, "nonlinear": False, "diffuse_reflectance": rgb([1, 1, 1])})
    si = mi.SurfaceInteraction3f()
    si.n = mi.Normal3f(0, 0, 1)
    si.sh_frame = mi.Frame3f(si.n)
    si.wi = mi.Vector3f(0, 0, 1)
    diffuse = mi.BSDFContext(mi.TransportMode.Radiance, mi.BSDFFlags.DiffuseReflection)
    glossy = mi.BSDFContext(mi.TransportMode.Radiance, mi.BSDFFlags.GlossyReflection)
    n, m = 2000, 20000
    d = sum(b.eval(diffuse, si, mi.Vector3f(math.sqrt(1 - mu * mu), 0, mu))[0]
            for mu in ((k + 0.5) / n for k in range(n))) * 2 * math.pi / n
    g = sum(b.sample(glossy, si, 0.5, mi.Point2f((k + 0.5) / m, (k * 0.6180339887) % 1.0))[1][0]
            for k in range(m)) / m
    _PLASTIC_SCALE[key] = (1 - g) / d
    return _PLASTIC_SCALE[key]


def principled_bsdf(m, where):
    """diffphoton's principled material (docs/materials.md) as a blend of Mitsuba BSDFs.

    Ours is mix(dielectric, conductor, metallic), the dielectric a GGX reflection layer with
    the exact Fresnel over mix(Lambert, rough transmission, transmission). In Mitsuba:

    - conductor: `principled` with metallic 1 (its metallic Fresnel is Schlick's with
      F0 = base_color, ours too; GGX with alpha = roughness^2, as ours). `roughconductor` has
      the exact conductor Fresnel of a complex index instead, a different curve.
    - dielectric, opaque: `roughplastic` (GGX reflection with the exact Fresnel; a Lambert
      base weighted by the layer's rough transmittance at both ends and normalised by its
      internal reflectance: the same form as ours, (1 - E(mu_o)) (1 - E(mu_i)) / (1 - E_avg)).
      Mitsuba's `principled` has a Disney diffuse (retro-reflection) instead.
    - dielectric, transmissive: `roughdielectric` with specular_transmittance = base colour
      at every crossing, as ours.
    - 0 < transmission < 1: blendbsdf(roughplastic, roughdielectric, transmission): both
      share the same reflection layer, so the blend is ours' structure.
    - 0 < metallic < 1: blendbsdf(dielectric, conductor, metallic), exactly ours' mix.

    What differs (docs/crosscheck.md): Mitsuba's Smith masking-shadowing is separable
    (G1 G1), ours height-correlated; ours adds Kulla-Conty multiple scattering to the metal,
    Mitsuba does not; the plastic's base normalisation differs in detail. The base colour is
    clamped to [0, 0.98] and the roughness raised to 0.03, as principled_at does."""
    base = m.get("base_colour", [0.5, 0.5, 0.5])
    if not isinstance(base, list):
        raise Unsupported(f"{where}.base_colour: only constant [r, g, b] base colours (not textures)")
    base = [min(max(float(c), 0.0), 0.98) for c in base]
    metallic = min(max(float(m.get("metallic", 0.0)), 0.0), 1.0)
    roughness = max(min(max(float(m.get("roughness", 0.5)), 0.0), 1.0), SPECULAR_ROUGHNESS)
    ior = min(max(float(m.get("ior", 1.5)), 1.01), 5.0)
    transmission = min(max(float(m.get("transmission", 0.0)), 0.0), 1.0)
    alpha = roughness * roughness
    if metallic < 1 and (abs(float(m.get("specular", 1.0)) - 1) > 1e-6 or
                         any(abs(float(c) - 1) > 1e-6 for c in m.get("specular_colour", [1, 1, 1]))):
        raise Unsupported(f"{where}.specular: only the default specular 1 (KHR_materials_specular "
                          "has no counterpart in roughplastic/roughdielectric)")

    def blend(a, b, w):  # (1 - w) a + w b
        if w <= 0:
            return a
        if w >= 1:
            return b
        return {"type": "blendbsdf", "weight": {"type": "rgb", "value": [w, w, w]}, "bsdf_0": a, "bsdf_1": b}

    conductor = None
    if metallic > 0:
        # Front side only (the metal's lobe is), so two-sided as ours.
        conductor = {"type": "twosided", "material": {
            "type": "principled", "base_color": rgb(base), "metallic": 1.0, "roughness": roughness,
            "eta": ior, "spec_tint": 0.0}}
    dielectric = None
    if metallic < 1:
        scale = 1.0 if PLASTIC_RAW else roughplastic_energy_scale(alpha, ior)
        if transmission < 1 and scale * max(base) > 1:
            # Mitsuba refuses RGB reflectances above 1.
            raise Unsupported(f"{where}.base_colour: {max(base)} times roughplastic's energy scale "
                              f"{scale:.3f} exceeds 1 (use --plastic-raw)")
        plastic = {"type": "twosided", "material": {
            "type": "roughplastic", "distribution": "ggx", "alpha": alpha, "int_ior": ior, "ext_ior": 1.0,
            "nonlinear": False, "diffuse_reflectance": rgb([scale * c for c in base])}}
        glass = {"type": "roughdielectric", "distribution": "ggx", "alpha": alpha, "int_ior": ior,
                 "ext_ior": 1.0, "specular_transmittance": rgb(base)}
        dielectric = blend(plastic, glass, transmission)
        if 0 < transmission and metallic > 0:
            raise Unsupported(f"{where}: metallic and transmission both in (0, 1)")
    if conductor is None:
        return dielectric
    if dielectric is None:
        return conductor
    return blend(dielectric, conductor, metallic)


def emission_dict(m):
    e = m.get("emission", [0, 0, 0]) if m.get("type") == "principled" else [0, 0, 0]
    if not any(float(x) > 0 for x in e):
        return None
    return {"type": "area", "radiance": rgb(e)}


def shape_dict(shape, transform, base_dir, where):
    m = object_matrix(transform)
    kind = shape["type"]
    if kind == "plane":
        sx, sz = shape["size"]
        # Mitsuba's rectangle spans [-1, 1]^2 in local XY with normal +Z; ours is XZ, normal +Y.
        local = mat4(rot_x(-90.0), None, [0.5 * sx, 0.5 * sz, 1.0])
        return {"type": "rectangle", "to_world": mi.ScalarTransform4f(m @ local)}
    if kind == "box":
        s = shape["size"]
        return {"type": "cube", "to_world": mi.ScalarTransform4f(m @ mat4(None, None, [0.5 * x for x in s]))}
    if kind == "sphere":
        scale = (transform or {}).get("scale", [1, 1, 1])
        if max(scale) - min(scale) > 1e-6 * max(scale):
            raise Unsupported(f"{where}: non-uniformly scaled sphere")
        r = float(shape["radius"])
        return {"type": "sphere", "to_world": mi.ScalarTransform4f(m @ mat4(None, None, [r, r, r]))}
    if kind == "mesh":
        path = resolve(base_dir, shape["path"])
        ext = os.path.splitext(path)[1].lower()
        if ext not in (".obj", ".ply"):
            raise Unsupported(f"{where}.path: Mitsuba reads OBJ and PLY only ({path}; .gltf is converted)")
        # The file's axes and unit first (Shape::file_frame), as ours places a mesh.
        return {"type": ext[1:], "filename": path, "to_world": mi.ScalarTransform4f(m @ gltf.file_frame(shape))}
    raise Unsupported(f"{where}.type: {kind}")


# Mitsuba's spot shines along its local +Z, its rectangle and disk lie in local XY facing +Z;
# ours' lights shine along local -Y, the area kinds lying in local XZ. A quarter turn about X
# takes +Z to -Y (and +Y to +Z).
LIGHT_FROM_MITSUBA = rot_x(90.0)


def light_dicts(light, where):
    """A virtual light (core/assets/virtual_lights.cpp) as Mitsuba emitters or shapes: a point of
    intensity colour P / (4 pi) W/sr; a spot of that intensity inside its cone (a hard edge only);
    a rect or disk face of radiance colour P / (pi A), one-sided, along the light's local -Y. The
    rotation places the light, the scale stretches an area light's face only."""
    kind = light.get("type")
    t = light.get("transform") or {}
    r3 = euler_xyz_deg(t.get("rotation_deg", [0, 0, 0]))
    pos = [float(x) for x in t.get("translation", [0, 0, 0])]
    colour = [max(float(c), 0.0) for c in light.get("colour", [1, 1, 1])]
    power = max(float(light.get("power_w", 100.0)), 0.0)
    if kind in ("point", "spot"):
        intensity = rgb([c * power / (4 * math.pi) for c in colour])
        if kind == "point":
            return {"type": "point", "position": pos, "intensity": intensity}
        blend = float(light.get("spot_blend", 0.15))
        if blend > 0:
            # Ours fades the edge by Blender's smoothstep on the cosine; Mitsuba's spot fades
            # linearly in angle: not the same light, so not compared.
            raise Unsupported(f"{where}.spot_blend: only hard-edged spots (spot_blend 0) match Mitsuba's falloff")
        half = 0.5 * min(max(float(light.get("spot_angle_deg", 45.0)), 1e-3), 180.0)
        return {"type": "spot", "intensity": intensity, "cutoff_angle": half, "beam_width": half,
                "to_world": mi.ScalarTransform4f(mat4(r3 @ LIGHT_FROM_MITSUBA, pos))}
    if kind not in ("rect", "disk"):
        raise Unsupported(f"{where}.type: {kind}")
    if not light.get("visible", True):
        # Mitsuba's emitting face is a shape every ray sees; ours' hidden face is seen by none.
        raise Unsupported(f"{where}.visible: a hidden area light (Mitsuba's face is always seen)")
    size = light.get("size", [0.5, 0.5] if kind == "rect" else [0.5])
    scale = t.get("scale", [1, 1, 1])
    sx = float(size[0]) * float(scale[0])
    sz = float(size[1] if kind == "rect" else size[0]) * float(scale[2])
    area = sx * sz if kind == "rect" else 0.25 * math.pi * sx * sz
    radiance = [c * power / (math.pi * area) for c in colour] if area > 0 else [0.0, 0.0, 0.0]
    to_world = mat4(r3 @ LIGHT_FROM_MITSUBA, pos, [0.5 * sx, 0.5 * sz, 1.0])
    # Unlike ours' lights, the face is geometry in Mitsuba: it blocks light and shows a black
    # back; place it where that does not matter (docs/crosscheck.md).
    return {"type": "rectangle" if kind == "rect" else "disk", "to_world": mi.ScalarTransform4f(to_world),
            "bsdf": {"type": "diffuse", "reflectance": rgb([0, 0, 0])},
            "emitter": {"type": "area", "radiance": rgb(radiance)}}


def scene_dict(project, base_dir, width, height, spp, upsample):
    max_depth = int(project.get("render", {}).get("max_depth", 8))
    scene = {
        "type": "scene",
        # diffphoton traces max_depth segments and adds next-event estimation at the last
        # vertex: paths of up to max_depth + 1 segments, Mitsuba's max_depth.
        "integrator": {"type": "path", "max_depth": max_depth + 1, "rr_depth": 5},
        "sensor": sensor_dict(project["camera"], width, height, spp),
        "probe": emitter_dict(project["probe"], base_dir, upsample),
    }
    for i, r in enumerate(project.get("real", [])):
        s = shape_dict(r["shape"], r.get("transform"), base_dir, f"real[{i}].shape")
        s["bsdf"] = diffuse_bsdf(r.get("albedo", [0.5, 0.5, 0.5]), f"real[{i}].albedo")
        scene[f"real_{i}"] = s
    for i, o in enumerate(project.get("objects", [])):
        if not o.get("visible", True):
            continue
        if gltf.is_gltf_object(o):
            # Each primitive a PLY; its file material where material_source is "file".
            def project_bsdf(o=o, i=i):
                if emission_dict(o.get("material", {})):
                    raise Unsupported(f"objects[{i}].material.emission: on a glTF mesh")
                return material_bsdf(o.get("material", {}), f"objects[{i}].material")
            parts = gltf.gltf_shapes(o, base_dir, f"objects[{i}]", project_bsdf,
                                o.get("material_source", "project") == "file")
            for k, (s, _) in enumerate(parts):
                scene[f"object_{i}_{k}"] = s
            continue
        if o.get("material_source", "project") == "file":
            raise Unsupported(f"objects[{i}].material_source: file materials are mapped for .gltf meshes only")
        s = shape_dict(o["shape"], o.get("transform"), base_dir, f"objects[{i}].shape")
        s["bsdf"] = material_bsdf(o.get("material", {}), f"objects[{i}].material")
        emitter = emission_dict(o.get("material", {}))
        if emitter:
            s["emitter"] = emitter
        scene[f"object_{i}"] = s
    for i, light in enumerate(project.get("lights", [])):
        scene[f"light_{i}"] = light_dicts(light, f"lights[{i}]")
    return scene


# ---------------------------------------------------------------------------------------------
# Runs


def prepared_project(project_path, width, workdir):
    """A copy of the project with absolute paths and, if `width` is given, a black photo of that
    width (the photo only sets the image size for a reference render) and scaled intrinsics."""
    with open(project_path) as f:
        project = json.load(f)
    base_dir = os.path.dirname(os.path.abspath(project_path))
    photo = resolve(base_dir, project["photo"]["path"])
    w0, h0 = image_size(photo)
    w, h = w0, h0
    if width:
        w, h = width, max(1, round(h0 * width / w0))
        s = w / w0
        cam = project["camera"]
        if cam.get("model", "lookat") == "opencv":
            cam["fx"] *= s
            cam["fy"] *= s
            cam["cx"] = (cam["cx"] + 0.5) * s - 0.5
            cam["cy"] = (cam["cy"] + 0.5) * s - 0.5
        photo = os.path.join(workdir, "photo.exr")
        write_rgb(photo, np.zeros((h, w, 3), np.float32))
    project["photo"]["path"] = photo
    project["probe"]["path"] = resolve(base_dir, project["probe"]["path"])
    for lst in ("real", "objects"):
        for e in project.get(lst, []):
            if e["shape"]["type"] == "mesh":
                e["shape"]["path"] = resolve(base_dir, e["shape"]["path"])
    out = os.path.join(workdir, "project.json")
    with open(out, "w") as f:
        json.dump(project, f, indent=2)
    return project, out, w, h


def render_mitsuba(project, base_dir, w, h, spp, seed, upsample):
    scene = mi.load_dict(scene_dict(project, base_dir, w, h, spp, upsample))
    t0 = time.time()
    img = np.array(mi.render(scene, spp=spp, seed=seed), dtype=np.float32)[..., :3]
    return img, time.time() - t0


def render_ours(diffphoton, project_path, out, spp, seed):
    t0 = time.time()
    subprocess.run([diffphoton, "reference", project_path, "-o", out, "--spp", str(spp), "--seed", str(seed)],
                   check=True, stdout=subprocess.DEVNULL)
    return read_rgb(out), time.time() - t0


def rmse(a, b):
    return float(np.sqrt(np.mean((a.astype(np.float64) - b) ** 2)))


def compare(ours, mitsuba):
    """Relative RMSE between the two full-spp truths (each the mean of its two halves) and each
    one's noise estimated from its halves: RMSE(half1 - half2) / 2 is the RMSE of the mean."""
    o = 0.5 * (ours[0] + ours[1])
    m = 0.5 * (mitsuba[0] + mitsuba[1])
    norm = float(np.mean(luminance(0.5 * (o + m))))
    rel = rmse(o, m) / norm
    noise_o = 0.5 * rmse(ours[0], ours[1]) / norm
    noise_m = 0.5 * rmse(mitsuba[0], mitsuba[1]) / norm
    expected = math.hypot(noise_o, noise_m)
    # The same after a 2x2 box filter: halves the noise, keeps a bias (a convention error shows
    # up as a difference that does not shrink).
    def pool(x):
        hh, ww = (x.shape[0] // 2) * 2, (x.shape[1] // 2) * 2
        x = x[:hh, :ww]
        return 0.25 * (x[0::2, 0::2] + x[1::2, 0::2] + x[0::2, 1::2] + x[1::2, 1::2])
    rel4 = rmse(pool(o), pool(m)) / norm
    exp4 = math.hypot(0.5 * rmse(pool(ours[0]), pool(ours[1])) / norm,
                      0.5 * rmse(pool(mitsuba[0]), pool(mitsuba[1])) / norm)

    # Rare caustic paths (a diffuse bounce that finds the sun through glass or a mirror) make
    # single-pixel fireflies that dominate the RMSE at any affordable spp. The same numbers
    # with every image's pixels clamped to 20x the mean luminance: a convention error still
    # shows, firefly noise mostly does not.
    cap = 20.0 * norm

    def clamp(x):
        lum = luminance(x)[..., None]
        return np.where(lum > cap, x * (cap / np.maximum(lum, 1e-30)), x)
    oc = [clamp(x) for x in ours]
    mc = [clamp(x) for x in mitsuba]
    rel_c = rmse(0.5 * (oc[0] + oc[1]), 0.5 * (mc[0] + mc[1])) / norm
    exp_c = math.hypot(0.5 * rmse(oc[0], oc[1]) / norm, 0.5 * rmse(mc[0], mc[1]) / norm)
    return {
        "relative_rmse": rel,
        "noise_ours": noise_o,
        "noise_mitsuba": noise_m,
        "noise_expected": expected,
        "excess_over_noise": math.sqrt(max(0.0, rel ** 2 - expected ** 2)),
        "relative_rmse_2x2": rel4,
        "noise_expected_2x2": exp4,
        "relative_rmse_clamped": rel_c,
        "noise_expected_clamped": exp_c,
        "mean_luminance_ours": float(np.mean(luminance(o))),
        "mean_luminance_mitsuba": float(np.mean(luminance(m))),
        "mean_ratio_ours_over_mitsuba": float(np.mean(luminance(o)) / np.mean(luminance(m))),
    }, o, m


def object_mask(project, w, h):
    """Pixels whose centre ray hits a virtual sphere (the other shapes are not masked)."""
    r, centre, fx, fy, cx, cy = camera_pose(project["camera"], w, h)
    ys, xs = np.mgrid[0:h, 0:w].astype(np.float64)
    d = np.stack([(xs - cx) / fx, (ys - cy) / fy, np.ones_like(xs)], axis=-1) @ r
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    mask = np.zeros((h, w), bool)
    for o in project.get("objects", []):
        if not o.get("visible", True) or o["shape"]["type"] != "sphere":
            continue
        tr = o.get("transform") or {}
        c = np.array(tr.get("translation", [0, 0, 0]), dtype=np.float64)
        rad = float(o["shape"]["radius"]) * float(tr.get("scale", [1, 1, 1])[0])
        oc = centre - c
        b = d @ oc
        mask |= (b * b - (oc @ oc - rad * rad) > 0) & (b < 0)
    return mask


def region_figures(ours, mitsuba, mask, norm):
    """Mean luminance ratio, relative RMSE and its expected value from noise over a pixel set."""
    o = 0.5 * (ours[0] + ours[1])
    m = 0.5 * (mitsuba[0] + mitsuba[1])
    if not mask.any():
        return None
    sel = lambda x: x[mask]
    rel = rmse(sel(o), sel(m)) / norm
    expected = math.hypot(0.5 * rmse(sel(ours[0]), sel(ours[1])) / norm,
                          0.5 * rmse(sel(mitsuba[0]), sel(mitsuba[1])) / norm)
    lo, lm = luminance(o)[mask], luminance(m)[mask]
    chan = [float(np.mean(o[..., c][mask]) / np.mean(m[..., c][mask])) for c in range(3)]
    return {"pixels": int(mask.sum()), "relative_rmse": rel, "noise_expected": expected,
            "excess_over_noise": math.sqrt(max(0.0, rel ** 2 - expected ** 2)),
            "mean_ratio_ours_over_mitsuba": float(np.mean(lo) / np.mean(lm)),
            "mean_ratio_rgb": chan}


def with_regions(result, project, ours, mits, base_dir):
    h, w = ours[0].shape[:2]
    mask = object_mask(project, w, h)
    gmask, metallic = gltf.gltf_object_hits(project, base_dir, w, h)
    if gmask is not None:
        mask |= gmask
    norm = 0.5 * (result["mean_luminance_ours"] + result["mean_luminance_mitsuba"])
    result["object_region"] = region_figures(ours, mits, mask, norm)
    result["outside_objects"] = region_figures(ours, mits, ~mask, norm)
    if metallic is not None and np.isfinite(metallic).any():
        # A textured glTF object by its metallic factor at the pixel's centre.
        with np.errstate(invalid="ignore"):
            result["object_metallic"] = region_figures(ours, mits, mask & (metallic >= 0.99), norm)
            result["object_dielectric"] = region_figures(ours, mits, mask & (metallic <= 0.01), norm)
            result["object_mixed"] = region_figures(ours, mits, mask & (metallic > 0.01) & (metallic < 0.99), norm)
    return result


def reanalyse(args):
    """The figures again from the half images a previous run left in --out."""
    with open(os.path.join(args.out, "project.json")) as f:
        project = json.load(f)
    ours = [read_rgb(os.path.join(args.out, f"ours_{k}.exr")) for k in (0, 1)]
    mits = [read_rgb(os.path.join(args.out, f"mitsuba_{k}.exr")) for k in (0, 1)]
    result, _, _ = compare(ours, mits)
    with_regions(result, project, ours, mits, args.out)
    print(json.dumps(result, indent=2))
    return 0


def crosscheck(args):
    os.makedirs(args.out, exist_ok=True)
    project, project_path, w, h = prepared_project(args.project, args.width, args.out)
    base_dir = os.path.dirname(project_path)
    half = max(1, args.spp // 2)
    print(f"{args.project}: {w}x{h}, {2 * half} spp as two halves of {half}", flush=True)
    ours, mits, t_ours, t_mits = [], [], 0.0, 0.0
    for k, seed in enumerate((1, 2)):
        ours_path = os.path.join(args.out, f"ours_{k}.exr")
        if args.reuse_ours and os.path.exists(ours_path):
            img, dt = read_rgb(ours_path), 0.0  # same project, spp and seed: the same image
        else:
            img, dt = render_ours(args.diffphoton, project_path, ours_path, half, seed)
        ours.append(img)
        t_ours += dt
        print(f"  diffphoton half {k + 1}: {dt:.1f} s", flush=True)
        img, dt = render_mitsuba(project, base_dir, w, h, half, seed, args.upsample)
        write_rgb(os.path.join(args.out, f"mitsuba_{k}.exr"), img)
        mits.append(img)
        t_mits += dt
        print(f"  mitsuba half {k + 1}: {dt:.1f} s", flush=True)
    result, o, m = compare(ours, mits)
    write_rgb(os.path.join(args.out, "ours.exr"), o)
    write_rgb(os.path.join(args.out, "mitsuba.exr"), m)
    write_rgb(os.path.join(args.out, "difference.exr"), o - m)
    result.update({"project": args.project, "width": w, "height": h, "spp": 2 * half,
                   "seconds_ours": t_ours, "seconds_mitsuba": t_mits, "mitsuba": mi.__version__,
                   "variant": mi.variant(), "plastic_raw": PLASTIC_RAW, "sampler": SAMPLER})
    with_regions(result, project, ours, mits, base_dir)
    with open(os.path.join(args.out, "crosscheck.json"), "w") as f:
        json.dump(result, f, indent=2)
    print(json.dumps(result, indent=2))
    return 0


# ---------------------------------------------------------------------------------------------
# Orientation check: one bright probe texel, a camera aimed at it with an off-centre principal
# point. Both renderers must put the texel on the principal point.


def bright_spot(img):
    lum = luminance(img)
    mask = lum > 0.5 * lum.max()
    ys, xs = np.nonzero(mask)
    wts = lum[mask]
    return float(np.sum(xs * wts) / np.sum(wts)), float(np.sum(ys * wts) / np.sum(wts))


def check_orientation(args):
    os.makedirs(args.out, exist_ok=True)
    pw, ph, ti, tj = 256, 128, 171, 37
    rotation = [12.0, 35.0, -7.0]
    probe = np.zeros((ph, pw, 3), np.float32)
    probe[tj, ti] = [100.0, 80.0, 60.0]
    write_rgb(os.path.join(args.out, "probe.exr"), probe)
    w, h = 96, 64
    write_rgb(os.path.join(args.out, "photo.exr"), np.zeros((h, w, 3), np.float32))
    # The texel centre's world direction under diffphoton's convention.
    d = euler_xyz_deg(rotation) @ latlong_direction((ti + 0.5) / pw, (tj + 0.5) / ph)
    up = np.array([0.0, 1.0, 0.0])
    right = np.cross(d, up)
    right /= np.linalg.norm(right)
    down = np.cross(d, right)
    r = np.array([right, down, d])
    cx, cy = 0.5 * (w - 1) + 13.3, 0.5 * (h - 1) - 9.6  # off-centre: a flipped axis would show
    f = 0.5 * h / math.tan(math.radians(12.0))
    centre = np.array([0.3, 1.2, -0.4])
    project = {
        "schema_version": 1,
        "photo": {"path": "photo.exr"},
        "probe": {"path": "probe.exr", "rotation_deg": rotation},
        "camera": {"model": "opencv", "fx": f, "fy": f, "cx": cx, "cy": cy, "rotation": r.tolist(),
                   "translation": (-r @ centre).tolist()},
    }
    path = os.path.join(args.out, "orientation.json")
    with open(path, "w") as f_:
        json.dump(project, f_, indent=2)
    ours, _ = render_ours(args.diffphoton, path, os.path.join(args.out, "ours.exr"), 16, 1)
    mits, _ = render_mitsuba(project, args.out, w, h, 16, 1, args.upsample)
    write_rgb(os.path.join(args.out, "mitsuba.exr"), mits)
    so, sm = bright_spot(ours), bright_spot(mits)
    print(f"texel ({ti}, {tj}) of a {pw}x{ph} probe rotated {rotation} deg: world direction {np.round(d, 4)}")
    print(f"expected at the principal point ({cx:.2f}, {cy:.2f})")
    print(f"diffphoton: ({so[0]:.2f}, {so[1]:.2f})   mitsuba: ({sm[0]:.2f}, {sm[1]:.2f})")
    ok = all(abs(a - b) < 1.0 for a, b in ((so[0], cx), (so[1], cy), (sm[0], cx), (sm[1], cy)))
    print("orientation: " + ("OK" if ok else "MISMATCH"))
    return 0 if ok else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("project", nargs="?", help="diffphoton project (JSON)")
    ap.add_argument("--diffphoton", default=shutil.which("diffphoton"), help="diffphoton executable")
    ap.add_argument("--out", default="crosscheck-out", help="folder for images and crosscheck.json")
    ap.add_argument("--spp", type=int, default=1024, help="samples per pixel of each full truth")
    ap.add_argument("--width", type=int, default=0, help="render at this width (height scaled); 0: the photo's")
    ap.add_argument("--upsample", type=int, default=0,
                    help="probe rows and columns per diffphoton pixel for Mitsuba (0: about 2048 rows)")
    ap.add_argument("--variant", default="scalar_rgb", help="Mitsuba variant")
    ap.add_argument("--check-orientation", action="store_true", help="verify the probe/camera conventions")
    ap.add_argument("--plastic-raw", action="store_true",
                    help="opaque principled: roughplastic without the energy scale (see roughplastic_energy_scale)")
    ap.add_argument("--sampler", default="independent",
                    help="Mitsuba's sampler: independent, stratified, multijitter, ldsampler (see SAMPLER)")
    ap.add_argument("--reuse-ours", action="store_true",
                    help="keep diffphoton halves already in --out (from a run of the same project and spp)")
    ap.add_argument("--reanalyse", action="store_true",
                    help="only recompute the figures from the half images of an earlier run in --out")
    args = ap.parse_args()
    if not args.diffphoton:
        ap.error("--diffphoton: the diffphoton executable is needed")
    mi.set_variant(args.variant)
    global PLASTIC_RAW, SAMPLER
    PLASTIC_RAW = args.plastic_raw
    SAMPLER = args.sampler
    try:
        if args.check_orientation:
            return check_orientation(args)
        if args.reanalyse:
            return reanalyse(args)
        if not args.project:
            ap.error("a project file is needed (or --check-orientation)")
        return crosscheck(args)
    except Unsupported as e:
        sys.exit(f"error: {e}")


if __name__ == "__main__":
    sys.exit(main())
