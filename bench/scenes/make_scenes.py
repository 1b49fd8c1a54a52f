#!/usr/bin/env python3
"""Generates the benchmark scenes: for each, a project (scene.json) that both methods render,
a synthetic photograph path-traced from a possibly more detailed description of the real world
(detail.json), and two independent halves of a converged ground truth (truth-a.exr,
truth-b.exr): standard differential rendering of detail.json at many samples per pixel. Each
half first samples every pixel, then spends the rest of its samples on the pixels the objects
change (`render --focus-after`), so the truth's own noise over those pixels stays well below
the errors it judges.

Where detail.json equals scene.json the real proxies are exact and both methods converge to the
truth; the mirror scene's photograph has a tiled floor its proxy models as one colour, as a
photograph has detail no proxy captures.

Usage: make_scenes.py --diffphoton build/app/diffphoton --out out/bench/scenes [--only NAME]
"""
import argparse
import copy
import json
import math
import os
import struct
import subprocess
import sys
import time
import zlib

WIDTH, HEIGHT = 256, 144
PHOTO_SPP = 8192  # a quiet photograph: Cycles' composite multiplies it, ours adds to it
BLENDER_PROBES = "/usr/share/blender/datafiles/studiolights/world"


def run(cmd):
    print("+", " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def base_project(probe, photons=100000):
    return {
        "schema_version": 1,
        "photo": {"path": "photo.exr", "exposure": 0},
        "probe": probe,
        "camera": {"model": "lookat", "eye": [0, 1.4, 4.2], "target": [0, 0.35, 0],
                   "up": [0, 1, 0], "vfov_deg": 40},
        "real": [{"name": "ground", "shape": {"type": "plane", "size": [12, 12]},
                  "albedo": [0.5, 0.5, 0.5]}],
        "objects": [],
        "render": {"photons_per_pass": photons, "passes": 16, "alpha": 0.6667,
                   "max_depth": 8, "seed": 1, "threads": 0},
    }


def sphere(name, pos, radius, material):
    return {"name": name, "shape": {"type": "sphere", "radius": radius},
            "transform": {"translation": pos}, "material": material}


def diffuse(rgb):
    return {"type": "diffuse", "albedo": rgb}


def sun_probe_spec(file):
    return {"path": file, "format": "latlong", "rotation_deg": [0, 0, 0], "intensity": 1}


def blender_probe(name, yaw):
    return {"path": f"{BLENDER_PROBES}/{name}.exr", "format": "latlong",
            "rotation_deg": [0, yaw, 0], "intensity": 1}


def write_torus_knot(path, p=2, q=3, segments=240, sides=24, tube=0.09):
    """A (p, q) torus knot tube: segments * sides * 2 triangles, as OBJ."""
    def centre(t):
        r = 0.35 + 0.15 * math.cos(q * t)
        return (r * math.cos(p * t), 0.15 * math.sin(q * t), r * math.sin(p * t))

    verts = []
    for i in range(segments):
        t = 2 * math.pi * i / segments
        c, c2 = centre(t), centre(t + 1e-3)
        tang = [c2[k] - c[k] for k in range(3)]
        n = math.sqrt(sum(x * x for x in tang))
        tang = [x / n for x in tang]
        up = (0.0, 1.0, 0.0)
        b = [tang[1] * up[2] - tang[2] * up[1], tang[2] * up[0] - tang[0] * up[2], tang[0] * up[1] - tang[1] * up[0]]
        bn = math.sqrt(sum(x * x for x in b))
        b = [x / bn for x in b]
        nrm = [b[1] * tang[2] - b[2] * tang[1], b[2] * tang[0] - b[0] * tang[2], b[0] * tang[1] - b[1] * tang[0]]
        for j in range(sides):
            a = 2 * math.pi * j / sides
            verts.append([c[k] + tube * (math.cos(a) * nrm[k] + math.sin(a) * b[k]) for k in range(3)])
    with open(path, "w") as f:
        f.write(f"# ({p},{q}) torus knot, {segments * sides * 2} triangles\n")
        for v in verts:
            f.write("v %.6f %.6f %.6f\n" % tuple(v))
        for i in range(segments):
            for j in range(sides):
                a = i * sides + j + 1
                b = ((i + 1) % segments) * sides + j + 1
                c = ((i + 1) % segments) * sides + (j + 1) % sides + 1
                d = i * sides + (j + 1) % sides + 1
                f.write(f"f {a} {b} {c}\nf {a} {c} {d}\n")
    return segments * sides * 2


def write_terrain_ply(path, n=708, width=40.0, height=8.0):
    """An n x n grid of gentle hills standing as a backdrop: 2 (n-1)^2 triangles, binary PLY."""
    with open(path, "wb") as f:
        tris = 2 * (n - 1) ** 2
        f.write(("ply\nformat binary_little_endian 1.0\n"
                 f"element vertex {n * n}\nproperty float x\nproperty float y\nproperty float z\n"
                 f"element face {tris}\nproperty list uchar int vertex_indices\nend_header\n").encode())
        rows = []
        for i in range(n):
            y = height * i / (n - 1)
            for j in range(n):
                x = width * (j / (n - 1) - 0.5)
                z = 0.6 * math.sin(0.9 * x) * math.cos(1.3 * y)
                rows.append(struct.pack("<fff", x, y, z))
        f.write(b"".join(rows))
        faces = []
        for i in range(n - 1):
            for j in range(n - 1):
                a = i * n + j
                faces.append(struct.pack("<Biii", 3, a, a + 1, a + n + 1))
                faces.append(struct.pack("<Biii", 3, a, a + n + 1, a + n))
        f.write(b"".join(faces))
    return 2 * (n - 1) ** 2


def write_png(path, width, height, pixel):
    """An 8-bit RGB PNG, pixel(x, y) -> (r, g, b) in [0, 255], written with zlib and struct."""
    rows = bytearray()
    for y in range(height):
        rows.append(0)  # filter: none
        for x in range(width):
            rows.extend(bytes(max(0, min(255, int(round(c)))) for c in pixel(x, y)))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(bytes(rows), 9)))
        f.write(chunk(b"IEND", b""))


def write_textured_gltf(folder, name="ball", radius=0.5, segments=64, rings=32, tex=(256, 128)):
    """A UV sphere as glTF 2.0 (name.gltf + name.bin; positions, normals, UVs, 16-bit indices)
    with a metallic-roughness material of three PNG side files: the base colour (sRGB; a
    checker of teal and cream), the metallic-roughness texture (linear; G roughness, B metallic:
    latitude bands of polished metal and rough dielectric) and a tangent-space normal map
    (a grid of round bumps). Returns the triangle count."""
    pos, nrm, uv = [], [], []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2 * math.pi * j / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            nrm.append(n)
            pos.append(tuple(radius * c for c in n))
            uv.append((j / segments, i / rings))  # glTF: v from the image's top row
    idx = []
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            for tri in ((a, b, b + 1), (a, b + 1, a + 1)):
                p0, p1, p2 = (pos[k] for k in tri)
                e1 = [p1[k] - p0[k] for k in range(3)]
                e2 = [p2[k] - p0[k] for k in range(3)]
                g = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
                if sum(g[k] * g[k] for k in range(3)) < 1e-18:
                    continue  # degenerate at a pole
                if sum(g[k] * p0[k] for k in range(3)) < 0:
                    tri = (tri[0], tri[2], tri[1])  # counter-clockwise seen from outside
                idx.extend(tri)
    blobs = [b"".join(struct.pack("<fff", *v) for v in pos), b"".join(struct.pack("<fff", *v) for v in nrm),
             b"".join(struct.pack("<ff", *v) for v in uv), b"".join(struct.pack("<H", k) for k in idx)]
    views, offset, data = [], 0, b""
    for blob in blobs:
        data += blob + b"\0" * (-len(blob) % 4)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob)})
        offset = len(data)
    with open(os.path.join(folder, name + ".bin"), "wb") as f:
        f.write(data)
    n = len(pos)
    gltf = {
        "asset": {"version": "2.0", "generator": "diffphoton bench/scenes/make_scenes.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": name}],
        "buffers": [{"uri": name + ".bin", "byteLength": len(data)}],
        "bufferViews": views[:3] + [dict(views[3], target=34963)],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
             "min": [-radius] * 3, "max": [radius] * 3},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": len(idx), "type": "SCALAR"}],
        "meshes": [{"name": name, "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                                  "indices": 3, "material": 0}]}],
        "materials": [{"name": "striped metal and paint",
                       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                "metallicRoughnessTexture": {"index": 1},
                                                "baseColorFactor": [1, 1, 1, 1],
                                                "metallicFactor": 1, "roughnessFactor": 1},
                       "normalTexture": {"index": 2, "scale": 1}}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
        "textures": [{"source": k, "sampler": 0} for k in range(3)],
        "images": [{"uri": f"{name}_{t}.png"} for t in ("basecolor", "metalrough", "normal")],
    }
    with open(os.path.join(folder, name + ".gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
    w, h = tex
    teal, cream = (30, 130, 140), (235, 215, 170)
    write_png(os.path.join(folder, f"{name}_basecolor.png"), w, h,
              lambda x, y: teal if ((x * 16 // w) + (y * 8 // h)) % 2 else cream)
    # Six latitude bands: polished metal (roughness 0.25, metallic 1) and rough paint (0.8, 0).
    write_png(os.path.join(folder, f"{name}_metalrough.png"), w, h,
              lambda x, y: (255, 0.25 * 255, 255) if (y * 6 // h) % 2 == 0 else (255, 0.8 * 255, 0))

    def bump_normal(x, y):
        # Height: a round bump in each of 24 x 12 cells; the normal from its gradient.
        cu, cv = (x + 0.5) * 24 / w % 1 - 0.5, (y + 0.5) * 12 / h % 1 - 0.5
        r2 = cu * cu + cv * cv
        k = 3.0 * math.exp(-r2 / 0.05)  # slope scale of a Gaussian bump
        nx, ny = k * cu, -k * cv
        l = math.sqrt(nx * nx + ny * ny + 1)
        return tuple(127.5 * (1 + c / l) for c in (nx, ny, 1.0))
    write_png(os.path.join(folder, f"{name}_normal.png"), w, h, bump_normal)
    return len(idx) // 3


def scenes(out):
    """name -> (scene project, detail project or None, (samples over every pixel, samples per
    pixel in all on the changed ones), size)."""
    s = {}
    hard = base_project(sun_probe_spec("sun-hard.exr"))
    hard["objects"] = [sphere("ball", [0, 0.5, 0], 0.5, diffuse([0.7, 0.6, 0.5]))]
    s["shadow_hard"] = (hard, None, (1024, 32768))

    soft = copy.deepcopy(hard)
    soft["probe"] = sun_probe_spec("sun-soft.exr")
    s["shadow_soft"] = (soft, None, (1024, 32768))

    caustic = base_project(sun_probe_spec("sun-caustic.exr"))
    caustic["objects"] = [sphere("glass", [0, 0.45, 0], 0.45,
                                 {"type": "glass", "ior": 1.5, "tint": [1, 1, 1]})]
    s["caustic"] = (caustic, None, (4096, 65536))

    mirrors = base_project(blender_probe("city", 35))
    mirrors["objects"] = [
        sphere("mirror left", [-0.75, 0.35, 0.1], 0.35, {"type": "mirror", "reflectance": [0.92, 0.92, 0.92]}),
        sphere("mirror right", [0.8, 0.3, -0.2], 0.3, {"type": "mirror", "reflectance": [0.9, 0.9, 0.9]}),
        sphere("clay", [0.05, 0.3, 0.45], 0.3, diffuse([0.75, 0.2, 0.12])),
    ]
    tiles = [[0.25, 0.25, 0.25], [0.6, 0.55, 0.5]]
    mirrors["real"][0]["albedo"] = [sum(c) / 2 for c in zip(*tiles)]
    detail = copy.deepcopy(mirrors)
    detail["real"][0]["albedo"] = {"texture": "tiles.png"}
    s["mirrors"] = (mirrors, detail, (1024, 32768))

    bleed = base_project(blender_probe("courtyard", 0))
    bleed["real"].append({"name": "wall", "shape": {"type": "box", "size": [3, 1.6, 0.1]},
                          "transform": {"translation": [0, 0.8, -0.75]}, "albedo": [0.8, 0.8, 0.8]})
    bleed["objects"] = [{"name": "knot", "shape": {"type": "mesh", "path": "knot.obj"},
                         "transform": {"translation": [0, 0.42, -0.2], "scale": [1.3, 1.3, 1.3]},
                         "material": diffuse([0.85, 0.12, 0.08])}]
    s["bleeding"] = (bleed, None, (1024, 8192))

    five = base_project(blender_probe("city", 35))
    five["camera"].update({"eye": [0, 3.2, 7.5], "target": [0, 0, 0], "vfov_deg": 55})
    five["real"][0]["shape"]["size"] = [20, 20]
    five["objects"] = [sphere(f"ball {i}", [x, 0.15, z], 0.15, diffuse(c)) for i, (x, z, c) in enumerate([
        (-3.2, 0.5, [0.8, 0.3, 0.2]), (-1.5, -2.0, [0.3, 0.7, 0.3]), (0.2, 1.8, [0.2, 0.3, 0.8]),
        (1.9, -1.2, [0.8, 0.8, 0.3]), (3.4, 1.0, [0.7, 0.7, 0.7])])]
    s["five_objects"] = (five, None, (1024, 16384))

    big = copy.deepcopy(hard)
    big["real"].append({"name": "hills", "shape": {"type": "mesh", "path": "hills.ply"},
                        "transform": {"translation": [0, 0, -9]}, "albedo": [0.35, 0.45, 0.3]})
    s["big_proxy"] = (big, None, (1024, 16384))

    noop = copy.deepcopy(hard)
    noop["objects"] = []
    s["noop"] = (noop, None, (256, 256))

    # A diffuse knot standing 0.12 m in front of a white wall: the wall in its shadow and seen
    # through its holes, and the floor under it, take light the knot hides from other real
    # surfaces as much as from the probe.
    knot = base_project(blender_probe("city", 35))
    knot["camera"].update({"eye": [0.3, 1.1, 3.2], "target": [0, 0.55, -0.5]})
    knot["real"].append({"name": "wall", "shape": {"type": "box", "size": [4, 2.2, 0.1]},
                         "transform": {"translation": [0, 1.1, -1.05]}, "albedo": [0.8, 0.8, 0.78]})
    knot["objects"] = [{"name": "knot", "shape": {"type": "mesh", "path": "knot.obj"},
                        "transform": {"translation": [0, 0.68, -0.62], "rotation_deg": [90, 0, 0],
                                      "scale": [1.1, 1.1, 1.1]},
                        "material": diffuse([0.6, 0.6, 0.6])}]
    s["knot_wall"] = (knot, None, (1024, 8192))

    # A glass ball on a grey floor before a wall, under a probe with a sun.
    glass_wall = base_project(blender_probe("city", 35))
    glass_wall["real"][0]["albedo"] = [0.4, 0.4, 0.4]
    glass_wall["real"].append({"name": "wall", "shape": {"type": "box", "size": [4, 2, 0.1]},
                               "transform": {"translation": [0, 1.0, -0.85]}, "albedo": [0.7, 0.7, 0.7]})
    glass_wall["objects"] = [sphere("glass", [0, 0.4, -0.3], 0.4, {"type": "glass", "ior": 1.5, "tint": [1, 1, 1]})]
    s["glass_wall"] = (glass_wall, None, (4096, 65536))

    # Production framing: a 1920x1080 photograph in which the object covers about 5% of the
    # frame, so that skipping the pixels it cannot change counts.
    prod = base_project(blender_probe("city", 35))
    prod["camera"].update({"eye": [0, 1.5, 4.5], "target": [0, 0.5, 0], "vfov_deg": 40})
    prod["real"][0]["shape"]["size"] = [30, 30]
    prod["real"][0]["albedo"] = [0.45, 0.43, 0.4]
    prod["objects"] = [sphere("clay", [0, 0.5, 0], 0.5, diffuse([0.7, 0.35, 0.2]))]
    prod["render"]["photons_per_pass"] = 300000
    s["production"] = (prod, None, (64, 2048), (1920, 1080))

    # The materials set (SET=materials bash bench/time_vs_error.sh): new materials and lights.
    # A rough gold ball: a glossy metal reflecting the probe and the floor.
    gold = base_project(blender_probe("city", 35))
    gold["objects"] = [sphere("gold", [0, 0.5, 0], 0.5, {"type": "principled", "base_colour": [1.0, 0.77, 0.34],
                                                          "metallic": 1, "roughness": 0.35})]
    s["gold_ball"] = (gold, None, (4096, 65536))

    # A frosted glass ball under a sun: rough transmission and its soft caustic.
    frosted = base_project(sun_probe_spec("sun-frosted.exr"))
    frosted["objects"] = [sphere("frosted glass", [0, 0.45, 0], 0.45,
                                 {"type": "principled", "base_colour": [1, 1, 1], "metallic": 0,
                                  "roughness": 0.2, "transmission": 1, "ior": 1.5})]
    # Twice the caustic scene's samples on the changed pixels: at 320 spp the halves' noise
    # there was 25% of the mean, about 1.8% at 65536 spp, too close to the errors judged.
    s["frosted_glass"] = (frosted, None, (4096, 131072))

    # A glTF 2.0 ball with its own textured material (base colour, metallic-roughness, normal).
    textured = base_project(blender_probe("city", 35))
    textured["objects"] = [{"name": "textured ball", "shape": {"type": "mesh", "path": "ball.gltf"},
                            "transform": {"translation": [0, 0.5, 0]}, "material_source": "file",
                            "material": diffuse([0.5, 0.5, 0.5])}]
    s["textured_gltf"] = (textured, None, (2048, 32768))

    # A warm area lamp near a real wall in a dim room, over a small diffuse ball: the lamp's
    # light on the wall and the floor and the ball's shadow in it are the change.
    lamp = base_project(blender_probe("city", 35))
    lamp["probe"]["intensity"] = 0.25
    lamp["camera"].update({"eye": [0.3, 1.1, 3.2], "target": [0, 0.55, -0.5]})
    lamp["real"].append({"name": "wall", "shape": {"type": "box", "size": [4, 2.2, 0.1]},
                         "transform": {"translation": [0, 1.1, -1.05]}, "albedo": [0.8, 0.8, 0.78]})
    lamp["objects"] = [sphere("ball", [0.3, 0.22, -0.55], 0.22, diffuse([0.7, 0.7, 0.7]))]
    lamp["lights"] = [{"name": "lamp", "type": "rect", "transform": {"translation": [-0.2, 1.7, 0.4],
                                                                     "rotation_deg": [45, 0, 0]},
                       "colour": [1.0, 0.8, 0.6], "power_w": 60, "size": [0.4, 0.3]}]
    s["lamp_wall"] = (lamp, None, (1024, 16384))

    # A clay ball on a polished real floor: the floor's gloss layer reflects the ball.
    polished = base_project(blender_probe("city", 35))
    polished["real"][0]["albedo"] = [0.35, 0.33, 0.3]
    polished["real"][0]["gloss"] = {"specular": 0.06, "roughness": 0.15}
    polished["objects"] = [sphere("clay", [0, 0.5, 0], 0.5, diffuse([0.75, 0.2, 0.12]))]
    s["polished_floor"] = (polished, None, (2048, 32768))
    return s


def make_inputs(name, folder, exe):
    if name in ("shadow_hard", "big_proxy", "noop"):
        run([exe, "make-test-image", os.path.join(folder, "sun-hard.exr"), "--size", "1024", "512",
             "--probe-sun", "--sun-dir", "0.45", "0.8", "0.4", "--sun-irradiance", "3",
             "--sun-radius-deg", "0.5", "--value", "0.35", "0.4", "0.5", "--sky-zenith", "0.12", "0.2", "0.45"])
    if name == "shadow_soft":
        run([exe, "make-test-image", os.path.join(folder, "sun-soft.exr"), "--size", "1024", "512",
             "--probe-sun", "--sun-dir", "0.45", "0.8", "0.4", "--sun-irradiance", "3",
             "--sun-radius-deg", "6", "--value", "0.35", "0.4", "0.5", "--sky-zenith", "0.12", "0.2", "0.45"])
    if name == "caustic":
        run([exe, "make-test-image", os.path.join(folder, "sun-caustic.exr"), "--size", "1024", "512",
             "--probe-sun", "--sun-dir", "0.5", "0.75", "0.45", "--sun-irradiance", "3",
             "--sun-radius-deg", "1.5", "--value", "0.35", "0.4", "0.5", "--sky-zenith", "0.12", "0.2", "0.45"])
    if name == "mirrors":
        run([exe, "make-test-image", os.path.join(folder, "tiles.png"), "--size", "480", "480",
             "--checker", "24", "--value", "0.25", "0.25", "0.25", "--value2", "0.6", "0.55", "0.5"])
    if name in ("bleeding", "knot_wall"):
        print("knot.obj:", write_torus_knot(os.path.join(folder, "knot.obj")), "triangles", flush=True)
    if name == "big_proxy":
        print("hills.ply:", write_terrain_ply(os.path.join(folder, "hills.ply")), "triangles", flush=True)
    if name == "frosted_glass":
        run([exe, "make-test-image", os.path.join(folder, "sun-frosted.exr"), "--size", "1024", "512",
             "--probe-sun", "--sun-dir", "0.5", "0.75", "0.45", "--sun-irradiance", "3",
             "--sun-radius-deg", "1.5", "--value", "0.35", "0.4", "0.5", "--sky-zenith", "0.12", "0.2", "0.45"])
    if name == "textured_gltf":
        print("ball.gltf:", write_textured_gltf(folder), "triangles", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--diffphoton", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--only", action="append", help="make only these scenes")
    ap.add_argument("--force", action="store_true", help="remake scenes that are already complete")
    ap.add_argument("--spp-scale", type=float, default=1.0, help="scales every truth's samples")
    ap.add_argument("--photo-spp", type=int, default=PHOTO_SPP, help="samples per pixel of each photograph")
    args = ap.parse_args()
    exe = os.path.abspath(args.diffphoton)
    for name, spec in scenes(args.out).items():
        scene, detail, (base_spp, total_spp) = spec[:3]
        width, height = spec[3] if len(spec) > 3 else (WIDTH, HEIGHT)
        if args.only and name not in args.only:
            continue
        t0 = time.time()
        folder = os.path.join(args.out, name)
        if not args.force and os.path.exists(os.path.join(folder, "truth.json")):
            print(f"{name}: complete (use --force to remake)")
            continue
        os.makedirs(folder, exist_ok=True)
        make_inputs(name, folder, exe)
        detail = detail or scene
        for file, project in (("scene.json", scene), ("detail.json", detail)):
            with open(os.path.join(folder, file), "w") as f:
                json.dump(project, f, indent=1)
        detail_path = os.path.join(folder, "detail.json")
        photo = os.path.join(folder, "photo.exr")
        run([exe, "make-test-image", photo, "--size", str(width), str(height)])  # sets the size
        # The renderer never writes over an input (the project's photo): render beside it, then replace it.
        rendered = os.path.join(folder, "photo-rendered.exr")
        run([exe, "reference", detail_path, "--real-only", "--spp", str(args.photo_spp), "--seed", "7", "-o", rendered])
        os.replace(rendered, photo)
        # Passes of 16 samples: the per-pass overhead would dominate a focused pass of one sample.
        spp_per_pass = 16
        base = max(1, int(base_spp * args.spp_scale) // (2 * spp_per_pass))
        half = max(base, int(total_spp * args.spp_scale) // (2 * spp_per_pass))
        for part, seed in (("a", 101), ("b", 202)):
            run([exe, "render", detail_path, "--method", "standard-correlated", "--passes", str(half), "--seed",
                 str(seed), "--samples-per-pass", str(spp_per_pass), "--focus-after", str(base), "--layers",
                 "-o", os.path.join(folder, f"truth-{part}.exr")])
        with open(os.path.join(folder, "truth.json"), "w") as f:
            json.dump({"samples_per_pixel_everywhere": 2 * base * spp_per_pass,
                       "samples_per_pixel_changed": 2 * half * spp_per_pass,
                       "photo_samples_per_pixel": args.photo_spp, "seconds": time.time() - t0}, f)
        print(f"{name}: {time.time() - t0:.0f} s", flush=True)


if __name__ == "__main__":
    sys.exit(main())
