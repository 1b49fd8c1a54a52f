"""glTF 2.0 meshes drawn with their file's materials, for mitsuba_crosscheck.py.

Split from mitsuba_crosscheck.py (which imports it as `gltf`); it reads that module's shared
helpers as `xc`, the running module when the check is run as a script.
"""
import json
import math
import os

import numpy as np

import mitsuba as mi

import mitsuba_crosscheck as xc

# ---------------------------------------------------------------------------------------------
# glTF 2.0 meshes drawn with their file's materials (`"material_source": "file"`)
#
# diffphoton reads a glTF through Assimp (core/geometry/mesh_loader.cpp, mesh_materials.cpp) and
# maps each material onto its principled model (core/assets/file_materials.cpp). The script
# reads the same file with numpy (JSON, .bin buffers, PNG side files through mi.Bitmap), writes
# each primitive as a PLY for Mitsuba and builds the material from the same texels:
#
# - UVs: ours keeps glTF's (texel row 0, the image's top, at v = 0; mesh.h), as Mitsuba's
#   bitmap does with a PLY's UVs (its PLY loader does not flip v; its OBJ loader does).
# - Lookups (render_scene.cpp texture_at): bilinear at (u W - 1/2, v H - 1/2) of fract(uv),
#   clamped at the image's edges (Image::bilinear): Mitsuba's bitmap with filter_type
#   bilinear and wrap_mode clamp is the same for UVs in [0, 1] (others are refused).
# - Base colour: sRGB-decoded codes (image_io.cpp srgb_to_linear) times baseColorFactor
#   clamped to [0, 1]; ours clamps the interpolated value to [0, 0.98], here each texel.
# - metallicRoughnessTexture: linear codes; roughness = roughnessFactor x G, metallic =
#   metallicFactor x B (principled_scatter.cpp principled_at); ours raises the interpolated
#   roughness to 0.03, here each texel. (Mitsuba's principled raises alpha to 0.001, a
#   roughness of 0.0316: its metal is rougher between 0.03 and 0.0316.)
# - normalTexture: linear codes, m = 2c - 1, ours bends the interpolated normal to
#   normalize(T m.x s + B m.y s + N max(m.z, 0)), T along dp/du (per triangle, from the UVs),
#   B = N x T towards the image's top, s the scale. Mitsuba's `normalmap` uses
#   normalize(2c - 1) in its shading frame (s = dp/du projected, t = n x s): the same frame
#   where the UVs are not mirrored (checked per triangle, else refused). The texels are
#   handed over as (m.x s, m.y s, max(m.z, 0)) unnormalised: bilinear interpolation commutes
#   with that, so both normalise the same interpolated vector. Mitsuba's shadow-terminator
#   term and its flip of normals facing away from the viewer are switched off (ours has
#   neither).

GLTF_COMPONENTS = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32,
                   5126: np.float32}
GLTF_WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


def srgb_to_linear(c):
    """core/image/image_io.cpp srgb_to_linear."""
    c = np.asarray(c, np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def quat_matrix(q):
    x, y, z, w = (float(c) for c in q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def file_frame(shape):
    """Shape::file_frame (core/scene/project.cpp): the file's axes to +Y up, times unit_scale."""
    r = {"y": np.eye(3),
         "z": np.array([[1, 0, 0], [0, 0, 1], [0, -1, 0]], dtype=np.float64),
         "-y": np.array([[1, 0, 0], [0, -1, 0], [0, 0, -1]], dtype=np.float64),
         "-z": np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]], dtype=np.float64)}.get(shape.get("up_axis", "y"))
    if r is None:
        raise xc.Unsupported(f"shape.up_axis: {shape.get('up_axis')}")
    m = np.eye(4)
    m[:3, :3] = r * float(shape.get("unit_scale", 1.0))
    return m


class Gltf:
    """The parts of a .gltf file the script maps: meshes under the default scene's nodes, their
    accessors, and metallic-roughness materials with image files."""

    def __init__(self, path, where):
        self.path, self.where = path, where
        self.folder = os.path.dirname(os.path.abspath(path))
        if not path.lower().endswith(".gltf"):
            raise xc.Unsupported(f"{where}: file materials are mapped for .gltf files only ({path})")
        with open(path) as f:
            self.j = json.load(f)
        if not str(self.j.get("asset", {}).get("version", "")).startswith("2"):
            raise xc.Unsupported(f"{where}: not a glTF 2.0 file")
        for ext in self.j.get("extensionsRequired", []):
            raise xc.Unsupported(f"{where}: required extension {ext}")
        self.buffers = []
        for b in self.j.get("buffers", []):
            uri = b.get("uri", "")
            if uri.startswith("data:"):
                import base64
                self.buffers.append(base64.b64decode(uri.split(",", 1)[1]))
            elif uri:
                with open(self.file(uri), "rb") as f:
                    self.buffers.append(f.read())
            else:
                raise xc.Unsupported(f"{where}: a buffer without a uri (.glb)")
        self._images = {}

    def file(self, uri):
        from urllib.parse import unquote
        return os.path.normpath(os.path.join(self.folder, unquote(uri)))

    def accessor(self, k):
        a = self.j["accessors"][k]
        if "sparse" in a or "bufferView" not in a:
            raise xc.Unsupported(f"{self.where}: sparse or empty accessor {k}")
        view = self.j["bufferViews"][a["bufferView"]]
        dtype = np.dtype(GLTF_COMPONENTS[a["componentType"]]).newbyteorder("<")
        n, count = GLTF_WIDTH[a["type"]], int(a["count"])
        stride = view.get("byteStride") or n * dtype.itemsize
        offset = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        rows = np.ndarray((count, n), dtype, buffer=self.buffers[view["buffer"]], offset=offset,
                          strides=(stride, dtype.itemsize))
        out = rows.astype(np.float64)
        if a.get("normalized") and dtype.kind in "iu":
            out /= float(np.iinfo(dtype).max)
        return out

    def node_matrices(self):
        """(node, world matrix) of every node of the default scene that has a mesh."""
        j = self.j
        nodes = j.get("nodes", [])
        if "scenes" in j:
            roots = j["scenes"][j.get("scene", 0)].get("nodes", [])
        else:
            children = {c for n in nodes for c in n.get("children", [])}
            roots = [k for k in range(len(nodes)) if k not in children]
        out, stack = [], [(k, np.eye(4)) for k in roots]
        while stack:
            k, parent = stack.pop()
            n = nodes[k]
            if "matrix" in n:
                local = np.array(n["matrix"], dtype=np.float64).reshape(4, 4).T  # column-major
            else:
                local = xc.mat4(quat_matrix(n.get("rotation", [0, 0, 0, 1])), n.get("translation", [0, 0, 0]),
                             n.get("scale", [1, 1, 1]))
            world = parent @ local
            if "mesh" in n:
                out.append((n, world))
            stack.extend((c, world) for c in n.get("children", []))
        return out

    def primitives(self):
        """Per triangle primitive: positions, normals, uvs (world of the file), triangles,
        material index (None without one)."""
        out = []
        for node, world in self.node_matrices():
            if "skin" in node or node.get("weights"):
                raise xc.Unsupported(f"{self.where}: skinned or morphed meshes")
            normal_matrix = np.linalg.inv(world[:3, :3]).T
            for p in self.j["meshes"][node["mesh"]]["primitives"]:
                if p.get("mode", 4) != 4:
                    raise xc.Unsupported(f"{self.where}: primitive mode {p.get('mode')} (triangles only)")
                if p.get("targets"):
                    raise xc.Unsupported(f"{self.where}: morph targets")
                attr = p["attributes"]
                pos = self.accessor(attr["POSITION"])
                if "NORMAL" not in attr:
                    # ours fills missing normals itself (mesh_loader.cpp fill_missing_normals)
                    raise xc.Unsupported(f"{self.where}: a primitive without normals")
                nrm = self.accessor(attr["NORMAL"])
                uv = self.accessor(attr["TEXCOORD_0"]) if "TEXCOORD_0" in attr else None
                idx = (self.accessor(p["indices"]).astype(np.int64).reshape(-1, 3) if "indices" in p
                       else np.arange(len(pos)).reshape(-1, 3))
                pos = pos @ world[:3, :3].T + world[:3, 3]
                nrm = nrm @ normal_matrix.T
                nrm /= np.maximum(np.linalg.norm(nrm, axis=1, keepdims=True), 1e-30)
                out.append((pos, nrm, uv, idx, p.get("material")))
        return out

    def image_codes(self, tex_info, where):
        """The texels of a textureInfo as codes in [0, 1] (H, W, 3), row 0 the image's top."""
        if tex_info.get("texCoord", 0) != 0:
            raise xc.Unsupported(f"{where}: texCoord {tex_info['texCoord']} (ours reads TEXCOORD_0)")
        if "KHR_texture_transform" in tex_info.get("extensions", {}):
            raise xc.Unsupported(f"{where}: KHR_texture_transform")
        source = self.j["textures"][tex_info["index"]].get("source")
        image = self.j["images"][source]
        uri = image.get("uri", "")
        if not uri or uri.startswith("data:"):
            raise xc.Unsupported(f"{where}: embedded images (only image files are read here)")
        path = self.file(uri)
        if path not in self._images:
            a = np.array(mi.Bitmap(path))
            if a.dtype == np.uint8:
                a = a.astype(np.float64) / 255.0
            elif a.dtype == np.uint16:
                a = a.astype(np.float64) / 65535.0
            else:
                raise xc.Unsupported(f"{where}: {path}: only 8- and 16-bit images")
            if a.ndim == 2:
                a = a[..., None]
            if a.shape[2] < 3:  # grey (+ alpha)
                a = np.repeat(a[..., :1], 3, axis=2)
            self._images[path] = a[..., :3]
        return self._images[path]


def bitmap_texture(a):
    """Linear float texels (H, W) or (H, W, 3) as a Mitsuba bitmap texture filtered as ours."""
    a = np.ascontiguousarray(a, dtype=np.float32)
    fmt = mi.Bitmap.PixelFormat.Y if a.ndim == 2 else mi.Bitmap.PixelFormat.RGB
    if a.ndim == 2:
        a = a[..., None]
    return {"type": "bitmap", "bitmap": mi.Bitmap(a, pixel_format=fmt), "raw": True,
            "filter_type": "bilinear", "wrap_mode": "clamp"}


def gltf_material_bsdf(g, k, where):
    """Material k of glTF `g` as ours maps it (file_materials.cpp principled_from_file), in the
    rows of the principled material (xc.principled_bsdf), with its textures. Returns the BSDF and,
    where the metallic factor comes from a texture, the metallic texels (for the regions)."""
    m = g.j["materials"][k]
    where = f"{where} material '{m.get('name', k)}'"
    pbr = m.get("pbrMetallicRoughness", {})
    ext = m.get("extensions", {})
    if float(ext.get("KHR_materials_transmission", {}).get("transmissionFactor", 0)) > 0:
        raise xc.Unsupported(f"{where}: transmission (not mapped with textures)")
    for e in ("KHR_materials_pbrSpecularGlossiness", "KHR_materials_clearcoat", "KHR_materials_sheen",
              "KHR_materials_volume"):
        if e in ext:
            raise xc.Unsupported(f"{where}: {e}")
    ior = float(ext.get("KHR_materials_ior", {}).get("ior", 1.5))
    ior = min(max(ior, 1.01), 5.0)
    factor = np.clip(np.array(pbr.get("baseColorFactor", [1, 1, 1, 1])[:3], dtype=np.float64), 0, 1)
    rough_f = min(max(float(pbr.get("roughnessFactor", 1.0)), 0.0), 1.0)
    metal_f = min(max(float(pbr.get("metallicFactor", 1.0)), 0.0), 1.0)

    if "baseColorTexture" in pbr:
        base = np.clip(srgb_to_linear(g.image_codes(pbr["baseColorTexture"], where + " baseColorTexture")) * factor,
                       0.0, 0.98)
        base_max = float(base.max())

        def base_tex(scale=1.0):
            return bitmap_texture(base * scale)
    else:
        base_c = np.clip(factor, 0.0, 0.98)
        base_max = float(base_c.max())

        def base_tex(scale=1.0):
            return xc.rgb(base_c * scale)
    if "metallicRoughnessTexture" in pbr:
        mr = np.clip(g.image_codes(pbr["metallicRoughnessTexture"], where + " metallicRoughnessTexture"), 0, 1)
        rough = np.maximum(rough_f * mr[..., 1], xc.SPECULAR_ROUGHNESS)
        metal = metal_f * mr[..., 2]
    else:
        rough = np.full((1, 1), max(rough_f, xc.SPECULAR_ROUGHNESS))
        metal = np.full((1, 1), metal_f)

    conductor = dielectric = None
    if metal.max() > 0:
        r = bitmap_texture(rough) if rough.size > 1 and np.ptp(rough) > 0 else float(rough.flat[0])
        conductor = {"type": "twosided", "material": {
            "type": "principled", "base_color": base_tex(), "metallic": 1.0, "roughness": r, "eta": ior,
            "spec_tint": 0.0}}
    if metal.min() < 1:
        # roughplastic's alpha is one number: the roughness wherever the texels are not all
        # metal must be one value. (Between a metal texel and a dielectric one ours
        # interpolates the dielectric's roughness too; Mitsuba keeps this one.)
        w = np.broadcast_to(1 - metal, rough.shape)
        vals = rough[w > 1e-6]
        if np.ptp(vals) > 0.01:
            raise xc.Unsupported(f"{where}: the roughness of its non-metallic texels varies "
                              f"({vals.min():.3f} to {vals.max():.3f}); roughplastic's alpha is one number")
        rd = float(np.average(vals, weights=w[w > 1e-6]))
        alpha = rd * rd
        scale = 1.0 if xc.PLASTIC_RAW else xc.roughplastic_energy_scale(alpha, ior)
        dielectric = {"type": "twosided", "material": {
            "type": "roughplastic", "distribution": "ggx", "alpha": alpha, "int_ior": ior, "ext_ior": 1.0,
            "nonlinear": False, "diffuse_reflectance": base_tex(scale)}}
        print(f"  {where}: dielectric part roughness {rd:.4f} (alpha {alpha:.5f}), roughplastic energy scale "
              f"{scale:.4f}, largest diffuse reflectance {scale * base_max:.3f}", flush=True)
    if conductor is None:
        bsdf = dielectric
    elif dielectric is None:
        bsdf = conductor
    elif metal.size > 1 and np.ptp(metal) > 0:
        bsdf = {"type": "blendbsdf", "weight": bitmap_texture(metal), "bsdf_0": dielectric, "bsdf_1": conductor}
    else:
        w = float(metal.flat[0])
        bsdf = {"type": "blendbsdf", "weight": {"type": "rgb", "value": [w, w, w]}, "bsdf_0": dielectric,
                "bsdf_1": conductor}

    if "normalTexture" in m:
        codes = g.image_codes(m["normalTexture"], where + " normalTexture")
        s = min(max(float(m["normalTexture"].get("scale", 1.0)), 0.0), 10.0)
        v = 2 * codes - 1
        v = np.dstack([v[..., 0] * s, v[..., 1] * s, np.maximum(v[..., 2], 0.0)])
        bsdf = {"type": "normalmap", "normalmap": bitmap_texture(0.5 * v + 0.5), "bsdf": bsdf,
                "use_shadowing_function": False, "flip_invalid_normals": False}
    return bsdf, (metal if metal.size > 1 and np.ptp(metal) > 0 else None)


def write_ply(path, pos, nrm, uv, idx):
    n, f = len(pos), len(idx)
    props = ["x", "y", "z", "nx", "ny", "nz"] + (["u", "v"] if uv is not None else [])
    header = ("ply\nformat binary_little_endian 1.0\n" f"element vertex {n}\n" +
              "".join(f"property float {p}\n" for p in props) +
              f"element face {f}\nproperty list uchar int vertex_indices\nend_header\n")
    cols = [pos, nrm] + ([uv] if uv is not None else [])
    verts = np.ascontiguousarray(np.hstack(cols), dtype="<f4")
    faces = np.zeros(f, dtype=[("n", "u1"), ("i", "<i4", 3)])
    faces["n"] = 3
    faces["i"] = idx
    with open(path, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(verts.tobytes())
        out.write(faces.tobytes())


def mirrored_triangles(pos, nrm, uv, idx):
    """Triangles whose UVs are mirrored against ours' frame: N x T pointing away from the image's
    top (ours flips B there, Mitsuba's normalmap does not); triangles without UV area aside."""
    p0, p1, p2 = pos[idx[:, 0]], pos[idx[:, 1]], pos[idx[:, 2]]
    t0, t1, t2 = uv[idx[:, 0]], uv[idx[:, 1]], uv[idx[:, 2]]
    e1, e2, d1, d2 = p1 - p0, p2 - p0, t1 - t0, t2 - t0
    det = d1[:, 0] * d2[:, 1] - d2[:, 0] * d1[:, 1]
    ok = np.abs(det) > 1e-20
    det = np.where(ok, det, 1.0)[:, None]
    dpdu = (d2[:, 1:2] * e1 - d1[:, 1:2] * e2) / det
    dpdv = (d1[:, 0:1] * e2 - d2[:, 0:1] * e1) / det
    n = nrm[idx[:, 0]] + nrm[idx[:, 1]] + nrm[idx[:, 2]]
    return int(np.sum(ok & (np.einsum("ij,ij->i", np.cross(n, dpdu), -dpdv) < 0)))


def gltf_shapes(obj, base_dir, where, project_material_bsdf, file_materials=True):
    """The object's glTF primitives as Mitsuba PLY shapes written to base_dir, each with its
    material (or `project_material_bsdf()` where the file gives none, or where
    `file_materials` is false): (shape dict, metallic texels or None) per primitive."""
    path = xc.resolve(base_dir, obj["shape"]["path"])
    g = Gltf(path, where + ".shape.path")
    to_world = xc.object_matrix(obj.get("transform")) @ file_frame(obj["shape"])
    stem = os.path.splitext(os.path.basename(path))[0]
    out = []
    for k, (pos, nrm, uv, idx, mat) in enumerate(g.primitives()):
        metal = None
        if mat is None or not file_materials:
            bsdf = project_material_bsdf()  # ours: the project's material where the file gives none
        else:
            bsdf, metal = gltf_material_bsdf(g, mat, where)
            textured = any(t in g.j["materials"][mat].get("pbrMetallicRoughness", {})
                           for t in ("baseColorTexture", "metallicRoughnessTexture")) or \
                "normalTexture" in g.j["materials"][mat]
            if textured:
                if uv is None:
                    raise xc.Unsupported(f"{where}: a textured primitive without TEXCOORD_0")
                if uv.min() < -1e-6 or uv.max() > 1 + 1e-6:
                    # ours wraps with fract() and clamps at texel edges; Mitsuba's modes wrap or clamp
                    raise xc.Unsupported(f"{where}: UVs outside [0, 1] ({uv.min():.3f} to {uv.max():.3f})")
            if "normalTexture" in g.j["materials"][mat]:
                bad = mirrored_triangles(pos, nrm, uv, idx)
                if bad:
                    raise xc.Unsupported(f"{where}: {bad} triangles with mirrored UVs (ours turns the normal "
                                      "map's +Y to the image's top, Mitsuba's normalmap does not)")
        ply = os.path.join(base_dir, f"{stem}_{k}.ply")
        write_ply(ply, pos, nrm, uv, idx)
        out.append(({"type": "ply", "filename": ply, "to_world": mi.ScalarTransform4f(to_world), "bsdf": bsdf},
                    metal))
    return out


def is_gltf_object(o):
    return o["shape"]["type"] == "mesh" and o["shape"]["path"].lower().endswith(".gltf")



def texel_bilinear(texels, u, v):
    """core/assets/render_scene.cpp texture_at of one channel: fract(uv), then Image::bilinear."""
    h, w = texels.shape
    x = min(max((u - math.floor(u)) * w - 0.5, 0.0), w - 1.0)
    y = min(max((v - math.floor(v)) * h - 0.5, 0.0), h - 1.0)
    x0, y0 = int(math.floor(x)), int(math.floor(y))
    x1, y1 = min(x0 + 1, w - 1), min(y0 + 1, h - 1)
    fx, fy = x - x0, y - y0
    top = texels[y0, x0] * (1 - fx) + texels[y0, x1] * fx
    bottom = texels[y1, x0] * (1 - fx) + texels[y1, x1] * fx
    return float(top * (1 - fy) + bottom * fy)


def gltf_object_hits(project, base_dir, w, h):
    """Pixels whose centre ray meets a glTF object (its PLYs, traced by Mitsuba), and there the
    metallic factor of its file material's texture (NaN where it has none)."""
    shapes, metals = {}, {}
    for i, o in enumerate(project.get("objects", [])):
        if not o.get("visible", True) or not is_gltf_object(o):
            continue
        parts = gltf_shapes(o, base_dir, f"objects[{i}]", lambda: {"type": "diffuse"},
                            o.get("material_source", "project") == "file")
        for k, (sd, metal) in enumerate(parts):
            key = f"object_{i}_{k}"
            shapes[key] = dict(sd, bsdf={"type": "diffuse"})
            metals[key] = metal
    if not shapes:
        return None, None
    scene = mi.load_dict(dict({"type": "scene"}, **shapes))
    r, centre, fx, fy, cx, cy = xc.camera_pose(project["camera"], w, h)
    mask = np.zeros((h, w), bool)
    metallic = np.full((h, w), np.nan)
    for y in range(h):
        for x in range(w):
            d = r.T @ np.array([(x - cx) / fx, (y - cy) / fy, 1.0])
            d /= np.linalg.norm(d)
            si = scene.ray_intersect(mi.Ray3f(mi.Point3f(*centre), mi.Vector3f(*d)))
            if not si.is_valid():
                continue
            mask[y, x] = True
            metal = metals.get(si.shape.id())
            if metal is not None:
                metallic[y, x] = texel_bilinear(metal, float(si.uv[0]), float(si.uv[1]))
    return mask, metallic
