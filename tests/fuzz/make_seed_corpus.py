#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpus (tests/fuzz/corpus/<target>/): small valid files of every
format each loader reads, so fuzzing starts from inputs that reach deep into the parsers.
Standard library only; run from anywhere. JPEG and TIFF seeds are made from the EXR seed by
`diffphoton convert` when a built binary is given (--cli)."""
import argparse, base64, json, os, struct, subprocess, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")


def put(target, name, data):
    d = os.path.join(CORPUS, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def png(w, h, depth=8, colour=2, alpha=False):
    """A PNG with a smooth gradient; colour type 0 (grey), 2 (RGB) or 6 (RGBA)."""
    channels = {0: 1, 2: 3, 6: 4}[colour]
    rows = b""
    for y in range(h):
        row = b"\x00"
        for x in range(w):
            for c in range(channels):
                v = (x * 50 + y * 30 + c * 20) % 256
                row += bytes([v]) if depth == 8 else struct.pack(">H", v * 257)
        rows += row
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, depth, colour, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def exr(w, h, channels=("B", "G", "R"), value=lambda x, y, c: 0.1 + 0.05 * x + 0.1 * y + 0.2 * c):
    """An uncompressed scanline OpenEXR file of FLOAT channels."""
    def attr(name, kind, body):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(body)) + body
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iBBBBii", 2, 0, 0, 0, 0, 1, 1) for c in channels) + b"\0"
    box = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<I", 2)
              + attr("channels", "chlist", chlist) + attr("compression", "compression", b"\0")
              + attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", box)
              + attr("lineOrder", "lineOrder", b"\0") + attr("pixelAspectRatio", "float", struct.pack("<f", 1))
              + attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0))
              + attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    line_bytes = 4 * w * len(channels)
    start = len(header) + 8 * h
    offsets = b"".join(struct.pack("<Q", start + y * (8 + line_bytes)) for y in range(h))
    lines = b""
    for y in range(h):
        data = b"".join(struct.pack("<f", value(x, y, ci)) for ci in range(len(channels)) for x in range(w))
        lines += struct.pack("<ii", y, len(data)) + data
    return header + offsets + lines


def hdr(w, h):
    """A Radiance RGBE file with flat (uncompressed) scanlines."""
    head = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + ("-Y %d +X %d\n" % (h, w)).encode()
    return head + b"".join(bytes([100 + x * 10, 80 + y * 20, 60, 128]) for y in range(h) for x in range(w))


def images(cli):
    put("image", "exr_rgb_4x3", b"\x00" + exr(4, 3))
    put("image", "exr_rgba_2x2", b"\x00" + exr(2, 2, ("A", "B", "G", "R")))
    put("image", "exr_layers_2x2", b"\x00" + exr(2, 2, ("B", "G", "R", "dL.B", "dL.G", "dL.R")))
    put("image", "png_rgb_4x3", b"\x01" + png(4, 3))
    put("image", "png_rgb16_3x2", b"\x01" + png(3, 2, depth=16))
    put("image", "png_grey_3x3", b"\x01" + png(3, 3, colour=0))
    put("image", "png_rgba_2x2", b"\x01" + png(2, 2, colour=6))
    put("image", "hdr_flat_4x2", b"\x03" + hdr(4, 2))
    if cli:
        src = os.path.join(CORPUS, "tmp.exr")
        with open(src, "wb") as f:
            f.write(exr(8, 6))
        for name, prefix in (("tmp.jpg", b"\x02"), ("tmp.png", None)):
            out = os.path.join(CORPUS, name)
            subprocess.run([cli, "convert", src, out], check=True, stdout=subprocess.DEVNULL)
            if prefix:
                with open(out, "rb") as f:
                    jpeg = f.read()
                put("image", "jpg_8x6", prefix + jpeg)
                # EXIF orientation 6 (a phone's portrait photo): the header size turns with it.
                tiff = b"II*\x00" + struct.pack("<IHHHIHHI", 8, 1, 0x0112, 3, 1, 6, 0, 0)
                app1 = b"\xff\xe1" + struct.pack(">H", 8 + len(tiff)) + b"Exif\x00\x00" + tiff
                put("image", "jpg_8x6_orientation6", prefix + jpeg[:2] + app1 + jpeg[2:])
            os.remove(out)
        os.remove(src)


def meshes():
    tetra_v = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    tetra_f = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    obj = "".join("v %g %g %g\n" % v for v in tetra_v) + "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
    obj += "".join("f %d/%d/1 %d/%d/1 %d/%d/1\n" % (a + 1, a % 3 + 1, b + 1, b % 3 + 1, c + 1, c % 3 + 1) for a, b, c in tetra_f)
    put("mesh", "obj_tetra", b"\x00" + obj.encode())
    put("mesh", "obj_quad_groups", b"\x00" + b"o a\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ng g1\nf 1 2 3 4\nf -4 -2 -1\n")
    ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    ply += "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
    ply += "".join("%g %g %g\n" % v for v in tetra_v) + "".join("3 %d %d %d\n" % f for f in tetra_f)
    put("mesh", "ply_ascii_tetra", b"\x01" + ply.encode())
    plyb = (b"ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
            b"property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n")
    plyb += b"".join(struct.pack("<fff", *v) for v in tetra_v) + b"".join(struct.pack("<Biii", 3, *f) for f in tetra_f)
    put("mesh", "ply_binary_tetra", b"\x01" + plyb)
    positions = b"".join(struct.pack("<fff", *v) for v in tetra_v)
    indices = b"".join(struct.pack("<HHH", *f) for f in tetra_f)
    buf = positions + indices
    def gltf(uri):
        return {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
                "nodes": [{"mesh": 0, "translation": [0, 0.5, 0]}],
                "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
                "buffers": [dict({"byteLength": len(buf)}, **({"uri": uri} if uri else {}))],
                "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
                                {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices)}],
                "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                               "min": [0, 0, 0], "max": [1, 1, 1]},
                              {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}]}
    uri = "data:application/octet-stream;base64," + base64.b64encode(buf).decode()
    put("mesh", "gltf_tetra", b"\x02" + json.dumps(gltf(uri)).encode())
    js = json.dumps(gltf(None)).encode()
    js += b" " * ((4 - len(js) % 4) % 4)
    body = buf + b"\0" * ((4 - len(buf) % 4) % 4)
    glb = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(body))
    glb += struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(body), 0x004E4942) + body
    put("mesh", "glb_tetra", b"\x03" + glb)
    stl = "solid t\n" + "".join("facet normal 0 0 1\nouter loop\n" + "".join("vertex %g %g %g\n" % tetra_v[i] for i in f)
                                + "endloop\nendfacet\n" for f in tetra_f) + "endsolid t\n"
    put("mesh", "stl_ascii_tetra", b"\x04" + stl.encode())


def projects():
    base = {
        "schema_version": 1,
        "photo": {"path": "photo.exr", "exposure": 0},
        "probe": {"path": "probe.exr", "format": "latlong", "rotation_deg": [0, 35, 0], "intensity": 1},
        "camera": {"model": "lookat", "eye": [0, 1.5, 4.6], "target": [0, 0.35, 0], "up": [0, 1, 0], "vfov_deg": 40},
        "real": [{"name": "ground", "shape": {"type": "plane", "size": [30, 30]}, "albedo": [0.45, 0.42, 0.38]},
                 {"name": "wall", "shape": {"type": "box", "size": [6, 3, 0.1]},
                  "transform": {"translation": [0, 1.5, -2]}, "albedo": {"texture": "texture.exr"}}],
        "objects": [
            {"name": "clay", "shape": {"type": "sphere", "radius": 0.38},
             "transform": {"translation": [-1.05, 0.38, 0.15]},
             "material": {"type": "diffuse", "albedo": [0.75, 0.18, 0.12]}},
            {"name": "chrome", "shape": {"type": "box", "size": [0.4, 0.4, 0.4]},
             "transform": {"translation": [0.2, 0.2, -0.45], "rotation_deg": [0, 30, 0]},
             "material": {"type": "mirror", "reflectance": [0.92, 0.92, 0.92]}},
            {"name": "glass", "shape": {"type": "sphere", "radius": 0.3},
             "transform": {"translation": [0.75, 0.3, 0.95], "scale": [1, 2, 1]},
             "material": {"type": "glass", "ior": 1.5, "tint": [0.97, 0.99, 1.0]}},
            {"name": "mesh", "shape": {"type": "mesh", "path": "mesh.obj"},
             "transform": {"translation": [0, 0, 0.5]}, "material": {"type": "diffuse", "albedo": {"texture": "texture.exr"}}},
            {"name": "off", "shape": {"type": "sphere", "radius": 0.1}, "visible": False}],
        "render": {"photons_per_pass": 2000, "passes": 1, "time_budget_s": 0, "initial_radius": 0.05,
                   "alpha": 0.6667, "max_depth": 8, "seed": 1, "threads": 0},
    }
    opencv = json.loads(json.dumps(base))
    opencv["camera"] = {"model": "opencv", "fx": 12.1, "fy": 12.0, "cx": 7.5, "cy": 5.5,
                        "distortion": [-0.11, 0.032, 0.0005, -0.0004, 0.001],
                        "rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "translation": [0, 1.5, 4]}
    photons = json.loads(json.dumps(base))
    photons["render"]["estimator"] = "photons"
    photons["probe"]["format"] = "mirrorball"
    for target in ("project", "scene"):
        put(target, "full", json.dumps(base, indent=1))
        put(target, "opencv_camera", json.dumps(opencv))
        put(target, "photon_estimator_mirror_ball", json.dumps(photons))
    with open(os.path.join(HERE, "..", "..", "resources", "sample", "sample.json")) as f:
        put("project", "sample", f.read())


def fspy():
    state = {"calibrationSettingsBase": {"referenceDistanceAxis": "xPositive", "referenceDistance": 2.0,
                                         "referenceDistanceUnit": "Meters"},
             "cameraParameters": {"principalPoint": {"x": 0.05, "y": -0.02},
                                  "cameraTransform": {"rows": [[1, 0, 0, 0.2], [0, 0, -1, -5], [0, 1, 0, 1.6], [0, 0, 0, 1]]},
                                  "horizontalFieldOfView": 1.1, "imageWidth": 4, "imageHeight": 3,
                                  "relativeFocalLength": 1.6}}
    image = png(4, 3)
    for name, unit in (("meters", "Meters"), ("millimetres", "Millimeters"), ("no_unit", "No unit")):
        state["calibrationSettingsBase"]["referenceDistanceUnit"] = unit
        text = json.dumps(state).encode()
        put("fspy", name, b"fspy" + struct.pack("<III", 1, len(text), len(image)) + text + image)
    # A portrait image (its focal length across the height) and fSpy's exported camera
    # parameters JSON (no header, no image: read by content).
    camera = dict(state["cameraParameters"], imageWidth=3, imageHeight=4, horizontalFieldOfView=1.1195)
    state = dict(state, cameraParameters=camera)
    text = json.dumps(state).encode()
    image = png(3, 4)
    put("fspy", "portrait", b"fspy" + struct.pack("<III", 1, len(text), len(image)) + text + image)
    put("fspy", "camera_parameters_json", json.dumps(camera, indent=2))


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--cli", help="a built diffphoton binary, for the JPEG seed")
    args = ap.parse_args()
    images(args.cli)
    meshes()
    projects()
    fspy()
