#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpus (tests/fuzz/corpus/<target>/): small valid files of every
format each loader reads, so fuzzing starts from inputs that reach deep into the parsers.
Standard library only; run from anywhere. With a built binary (--cli), the JPEG seeds are made
from the EXR seed by `diffphoton convert`, and the merge seeds are shards `diffphoton render
--pass-range` writes."""
import argparse, base64, json, os, shutil, struct, subprocess, tempfile, zlib

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


def tiff_rgb(w, h, pixels=None):
    """An uncompressed 8-bit RGB baseline TIFF, one strip; `pixels` (the strip) defaults to a
    gradient of the declared size."""
    if pixels is None:
        pixels = bytes((x * 40 + y * 20 + c * 60) % 256 for y in range(h) for x in range(w) for c in range(3))
    tags = [(256, 4, 1, w), (257, 4, 1, h), (258, 3, 3, None), (259, 3, 1, 1), (262, 3, 1, 2),
            (273, 4, 1, None), (277, 3, 1, 3), (278, 4, 1, h), (279, 4, 1, len(pixels)), (284, 3, 1, 1)]
    ifd_size = 2 + 12 * len(tags) + 4
    bits_at = 8 + ifd_size
    strip_at = bits_at + 6
    ifd = struct.pack("<H", len(tags))
    for tag, kind, count, value in tags:
        if tag == 258:
            value = bits_at
        elif tag == 273:
            value = strip_at
        ifd += struct.pack("<HHI", tag, kind, count) + (struct.pack("<HH", value, 0) if kind == 3 and count == 1
                                                        else struct.pack("<I", value))
    return b"II*\x00" + struct.pack("<I", 8) + ifd + struct.pack("<I", 0) + struct.pack("<HHH", 8, 8, 8) + pixels


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
    put("image", "tif_rgb_4x3", b"\x04" + tiff_rgb(4, 3))
    declared_huge(cli)
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


def declared_huge(cli):
    """Small files whose headers declare sizes past the 4 Mpx the image fuzzer allows (refused
    before decoding), or within it but more than the file can hold (refused as truncated)."""
    for w, h in ((100000, 100000), (2048, 2048)):
        name = "%dx%d" % (w, h)
        ihdr = png(1, 1)[:33]
        body = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)
        ihdr = ihdr[:16] + body + struct.pack(">I", zlib.crc32(b"IHDR" + body) & 0xFFFFFFFF)
        put("image", "png_declares_" + name, b"\x01" + ihdr + png(1, 1)[33:])
        tiny = exr(1, 1)
        box = struct.pack("<iiii", 0, 0, 0, 0)
        put("image", "exr_declares_" + name, b"\x00" + tiny.replace(box, struct.pack("<iiii", 0, 0, w - 1, h - 1), 2))
        put("image", "hdr_declares_" + name,
            b"\x03" + hdr(2, 2).replace(b"-Y 2 +X 2", ("-Y %d +X %d" % (h, w)).encode()))
        put("image", "tif_declares_" + name, b"\x04" + tiff_rgb(w, h, pixels=bytes(12)))
    if cli:
        src = os.path.join(CORPUS, "tmp.exr")
        out = os.path.join(CORPUS, "tmp.jpg")
        with open(src, "wb") as f:
            f.write(exr(8, 6))
        subprocess.run([cli, "convert", src, out], check=True, stdout=subprocess.DEVNULL)
        with open(out, "rb") as f:
            jpeg = f.read()
        os.remove(src)
        os.remove(out)
        sof = jpeg.index(b"\xff\xc0")  # baseline frame header: length, precision, height, width
        for w, h in ((65000, 65000), (2048, 2048)):
            put("image", "jpg_declares_%dx%d" % (w, h),
                b"\x02" + jpeg[:sof + 5] + struct.pack(">HH", h, w) + jpeg[sof + 9:])


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


NEXT_FILE = b"\n--next-file--\n"
TETRA_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TETRA_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def gltf_textured(buffer_uri, image_uri, byte_length):
    """A glTF tetrahedron (positions, UVs, indices in buffer 0) whose material's base colour
    texture is `image_uri`."""
    n = len(TETRA_V)
    return {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
            "materials": [{"name": "painted", "pbrMetallicRoughness": {
                "baseColorFactor": [0.9, 0.8, 0.7, 1], "baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
            "textures": [{"source": 0}], "images": [{"uri": image_uri}],
            "buffers": [dict({"byteLength": byte_length}, **({"uri": buffer_uri} if buffer_uri else {}))],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n},
                            {"buffer": 0, "byteOffset": 12 * n, "byteLength": 8 * n},
                            {"buffer": 0, "byteOffset": 20 * n, "byteLength": 6 * len(TETRA_F)}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 1, 1]},
                          {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC2"},
                          {"bufferView": 2, "componentType": 5123, "count": 3 * len(TETRA_F), "type": "SCALAR"}]}


def mesh_files():
    """A mesh with its side files (mesh_files_fuzzer.cpp): an OBJ with its material library and
    textures, a glTF and a GLB with an external buffer and texture."""
    obj = "mtllib mesh.mtl\n" + "".join("v %g %g %g\n" % v for v in TETRA_V) + "vt 0 0\nvt 1 0\nvt 0 1\n"
    for k, (a, b, c) in enumerate(TETRA_F):
        obj += "usemtl %s\n" % ("painted", "photo", "plain", "painted")[k]
        obj += "f %d/1 %d/2 %d/3\n" % (a + 1, b + 1, c + 1)
    mtl = ("newmtl painted\nKd 0.8 0.8 0.8\nmap_Kd texture.png\n"
           "newmtl photo\nKd 0.5 0.5 0.5\nmap_Kd -bm 1 -o 0 0 texture.jpg\n"
           "newmtl plain\nKd 0.2 0.3 0.8\nNi 1.5\n")
    texture = png(4, 4)
    put("mesh_files", "obj_mtl_png", b"\x00" + NEXT_FILE.join([obj.encode(), mtl.encode(), texture]))
    put("mesh_files", "obj_mtl_missing_texture", b"\x00" + NEXT_FILE.join([obj.encode(), mtl.encode()]))
    put("mesh_files", "obj_missing_mtl", b"\x00" + obj.encode())
    put("mesh_files", "obj_mtl_windows_paths", b"\x00" + NEXT_FILE.join(
        [obj.encode(), mtl.replace("map_Kd texture.png", "map_Kd .\\texture.png").encode(), texture]))
    buf = (b"".join(struct.pack("<fff", *v) for v in TETRA_V)
           + b"".join(struct.pack("<ff", (x + y) / 2, z) for x, y, z in TETRA_V)
           + b"".join(struct.pack("<HHH", *f) for f in TETRA_F))
    buf += b"\0" * ((4 - len(buf) % 4) % 4)
    gltf = json.dumps(gltf_textured("mesh.bin", "texture.png", len(buf))).encode()
    put("mesh_files", "gltf_bin_png", b"\x01" + NEXT_FILE.join([gltf, buf, texture]))
    put("mesh_files", "gltf_missing_bin", b"\x01" + gltf)
    spaced = json.dumps(gltf_textured("mesh.bin", "./texture%2Epng", len(buf))).encode()
    put("mesh_files", "gltf_percent_encoded_texture", b"\x01" + NEXT_FILE.join([spaced, buf, texture]))
    js = json.dumps(gltf_textured("mesh.bin", "texture.png", len(buf))).encode()
    js += b" " * ((4 - len(js) % 4) % 4)
    glb = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js)) + struct.pack("<II", len(js), 0x4E4F534A) + js
    put("mesh_files", "glb_external_bin_png", b"\x02" + NEXT_FILE.join([glb, buf, texture]))


def merge(cli):
    """Shards of a 12 x 8 frame (two tiles, one of them partial) from `diffphoton render
    --pass-range`: after the flags byte (bit 0: reseal the checksums), shards one after another."""
    work = os.path.join(tempfile.gettempdir(), "dp-merge-seeds")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    def run(*args):
        subprocess.run([cli, *args], check=True, cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    run("make-test-image", "photo.exr", "--size", "12", "8", "--value", "0.5", "0.5", "0.5")
    run("make-test-image", "probe.exr", "--size", "64", "32", "--probe-sun", "--value", "0.1", "0.1", "0.12")
    project = {"schema_version": 1, "photo": {"path": "photo.exr"}, "probe": {"path": "probe.exr"},
               "camera": {"model": "lookat", "eye": [0, 1.5, 4], "target": [0, 0.4, 0], "vfov_deg": 40},
               "real": [{"name": "floor", "shape": {"type": "plane", "size": [10, 10]}, "albedo": [0.5, 0.5, 0.5]}],
               "objects": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.5},
                            "transform": {"translation": [0, 0.5, 0]},
                            "material": {"type": "glass", "ior": 1.5}}],
               "render": {"photons_per_pass": 2000, "passes": 4}}
    with open(os.path.join(work, "scene.json"), "w") as f:
        json.dump(project, f)
    shard = {}
    for name, extra in (("0-2", ["--pass-range", "0:2"]), ("2-3", ["--pass-range", "2:3"]),
                        ("3-4", ["--pass-range", "3:4"]), ("seed7", ["--pass-range", "2:3", "--seed", "7"])):
        run("render", "scene.json", "-o", name + ".dpp", *extra)
        with open(os.path.join(work, name + ".dpp"), "rb") as f:
            shard[name] = f.read()
    shutil.rmtree(work)
    put("merge", "one_shard", b"\x01" + shard["0-2"])
    put("merge", "two_shards", b"\x00" + shard["0-2"] + shard["2-3"])
    put("merge", "two_shards_resealed", b"\x01" + shard["0-2"] + shard["2-3"])
    put("merge", "three_shards_reversed", b"\x01" + shard["3-4"] + shard["2-3"] + shard["0-2"])
    put("merge", "overlap", b"\x01" + shard["0-2"] + shard["0-2"])
    put("merge", "gap", b"\x01" + shard["0-2"] + shard["3-4"])
    put("merge", "other_seed", b"\x01" + shard["0-2"] + shard["seed7"])
    put("merge", "truncated", b"\x00" + shard["0-2"][:5000] + shard["2-3"])


def cli_lines():
    """Command lines, their arguments NUL-separated (cli_fuzzer.cpp): every command, with the
    options whose values are checked."""
    lines = [
        "render scene.json -o out.exr --passes 4 --layers --photons 20000 --seed 7 --threads 2",
        "render scene.json -o out.png --time 30 --exposure -1.5 --view Filmic --bits 16 --adaptive off",
        "render scene.json -o out.exr --method standard-correlated --samples-per-pass 4 --focus-after 8 --half",
        "render scene.json --pass-range 0:8 -o part.dpp --threads 1 --probe-max-width 1024",
        "render scene.json --pixel 12,7 --pass 3",
        "render scene.json -o out.jpg --denoise --quality 90 --force",
        "merge part-0-8.dpp part-8-16.dpp -o merged.exr --layers --allow-gaps --project scene.json",
        "info scene.json --json",
        "reference scene.json -o truth.exr --spp 16 --real-only --seed 3 --exposure 0.5",
        "convert photo.exr photo.tif --bits 32 --colorspace linear --layer dL",
        "compare a.exr b.exr --layer dL --changed photo.exr --only objects",
        "make-test-image probe.exr --size 64 32 --probe-sun --sun-dir 0 1 0 --sun-radius-deg 2 --sky-zenith 0.1 0.2 0.3",
        "bench scenes -o rows.json --methods differential,standard --max-seconds-differential 5 --denoise",
        "export blender scene.json -o scene.py",
        "calibrate chessboard scene.json a.jpg b.jpg --board 9x6 --square 0.025 --json",
        "calibrate rectangle scene.json --size 4000x3000 --corners 1,2 3,4 5,6 7,8 --width 0.297 --height 0.21",
        "calibrate points scene.json --photo p.jpg --point 0,0,0,10,20 --point 1,0,0,30,20 --focal-mm 35 --sensor-width 36",
        "calibrate vanishing scene.json --size 800x600 --x 1,2,3,4 --z 5,6,7,8 --origin 400,500 --camera-height 1.6",
        "calibrate exif scene.json photo.jpg --sensor-width 23.5",
        "calibrate fspy scene.json room.fspy --extract-photo room.jpg",
        "calibrate proxy scene.json wall --points 10 400 600 420 --height 2.5 --thickness 0.1 --name wall",
        "calibrate albedo scene.json --proxy floor --resolution 256 --subsamples 2 --clip 0.99 -o out.json",
        "calibrate probe scene.json --grey-card 10 20 30 40 --white-balance --reflectance 0.18",
        "--version",
        "render --help",
        "rendr scene.json",
    ]
    for i, line in enumerate(lines):
        words = line.split(" ")
        put("cli", "%02d_%s" % (i, "_".join(w.strip("-") for w in words[:2] if w)), b"\0".join(w.encode() for w in words))


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
    principled = json.loads(json.dumps(base))
    principled["objects"][0]["material"] = {"type": "principled", "base_colour": [0.95, 0.64, 0.54],
                                            "metallic": 1, "roughness": 0.3}
    principled["objects"][2]["material"] = {"type": "principled", "base_colour": {"texture": "texture.exr"},
                                            "metallic": 0, "roughness": 0.2, "ior": 1.45, "specular": 0.5,
                                            "transmission": 1, "emission": [0.1, 0.2, 0.3]}
    for target in ("project", "scene"):
        put(target, "principled", json.dumps(principled, indent=1))
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
    mesh_files()
    projects()
    fspy()
    cli_lines()
    if args.cli:
        merge(args.cli)
