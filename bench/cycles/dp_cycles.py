"""A diffphoton project as a Blender Cycles scene: the one converter every Cycles script shares.

Runs inside Blender 3.4 (`blender -b --factory-startup -P SCRIPT -- ARGS`) or Blender 5 as a
Python module (PyPI bpy: `python SCRIPT ARGS`); imported by cycles_render.py (the `cycles`,
`cycles5` and `cycles5-artist` methods of `diffphoton bench`) and check_conversion.py. The
conventions it maps, and how each was checked, are in docs/cycles.md:

- world: the Blender scene is built in the probe's frame (probe +Y up becomes Blender's +Z up,
  the probe's centre direction becomes +X), so the Environment Texture needs no rotation;
- camera: OpenCV intrinsics and pose become a perspective camera with a vertical sensor fit,
  lens shift for the principal point and pixel aspect for fx != fy (no lens distortion);
- probe: the lat-long map as an Environment Texture with closest-texel lookups (ours is
  piecewise constant) and an importance map of one cell per texel;
- real proxies: diffuse surfaces (with a GGX Glossy added for a gloss layer) marked as shadow
  catchers; virtual objects: diffuse, sharp
  glossy (mirror) or sharp glass (Blender 3.4's SHARP distribution, GGX at roughness 0 in
  Blender 4 and later, which dropped SHARP and treats roughness 0 as a perfect reflection);
  principled: Principled BSDF (glTF's material; its inputs by the names of Blender 3.4 or 4+;
  its emission lights the real proxies, as ours does); meshes from OBJ, PLY, STL, FBX (in
  metres from its declared unit) or glTF 2.0 (Blender's glTF importer, its Y-up conversion
  undone), the file's own materials kept for "material_source": "file";
- lights: point and spot (radius 0) and area lights (rectangle, disk or ellipse) of the same
  power in watts, turned from ours' local -Y to Blender's local -Z (LIGHT_FROM_BLENDER);
- one composite per render: Combined + (1 - Combined.alpha) * photo * ShadowCatcher.
"""
import array
import json
import math
import os
import time

import bpy
from mathutils import Matrix, Vector

# Vertex normals on a sphere mesh are set to the exact radial direction; with 256 x 128 quads
# the silhouette is within 8e-5 radii of the true sphere (ours intersects an exact sphere).
SPHERE_SEGMENTS, SPHERE_RINGS = 256, 128
# ...except for a non-uniformly scaled sphere, which ours renders as its 96 x 48 UV mesh.
OURS_SPHERE_MESH = (96, 48)
MAX_ALBEDO = 0.98  # ours clamps every reflectance to [0, 0.98] (Surface::reflectance_at)


def script_args(script_file):
    """The script's own arguments: those after `--` (Blender: `blender -b -P SCRIPT -- ARGS`),
    else, when the script is Python's main program (Blender as a module: `python SCRIPT ARGS`),
    those after its name, else none."""
    import sys
    if "--" in sys.argv:
        return sys.argv[sys.argv.index("--") + 1:]
    if sys.argv and os.path.abspath(sys.argv[0]) == os.path.abspath(script_file):
        return sys.argv[1:]
    return []


def has_enum_item(struct, prop, item):
    return item in {e.identifier for e in struct.bl_rna.properties[prop].enum_items}


def set_linear(img):
    """Marks an image's values as linear: the colour space "Linear" in Blender 3.4, renamed
    "Linear Rec.709" in Blender 4."""
    names = img.colorspace_settings.bl_rna.properties["name"].enum_items.keys()
    img.colorspace_settings.name = "Linear" if "Linear" in names else "Linear Rec.709"


def use_nodes(idblock):
    """Node trees on a material or world: to be switched on in Blender 3.4; always there in
    Blender 5, where `use_nodes` is deprecated."""
    if bpy.app.version < (5, 0, 0) or idblock.node_tree is None:
        idblock.use_nodes = True


def make_sharp(bsdf):
    """A perfectly sharp Glossy, Glass or Refraction BSDF: the SHARP distribution in Blender
    3.4; Blender 4 dropped it, and GGX at roughness 0 is the same singular lobe there."""
    if has_enum_item(bsdf, "distribution", "SHARP"):
        bsdf.distribution = "SHARP"
    else:
        bsdf.distribution = "GGX"
        bsdf.inputs["Roughness"].default_value = 0.0


class ConversionError(Exception):
    """A project this converter cannot express in Cycles (or a malformed one): names the file
    and the field, as diffphoton's own errors do."""

    def __init__(self, file, field, message):
        super().__init__(f"{file}: field '{field}': {message}" if field else f"{file}: {message}")


# ---------------------------------------------------------------------------------------------
# Conventions (docs/project-format.md)


def euler_xyz_deg(r):
    """d_world = Rz * Ry * Rx * d_local (X applied first), as core/probe euler_xyz_deg."""
    return (Matrix.Rotation(math.radians(r[2]), 3, "Z") @ Matrix.Rotation(math.radians(r[1]), 3, "Y")
            @ Matrix.Rotation(math.radians(r[0]), 3, "X"))


def object_matrix(transform):
    """M = T * Rz * Ry * Rx * S (4 x 4, ours)."""
    transform = transform or {}
    s = transform.get("scale", [1, 1, 1])
    rs = euler_xyz_deg(transform.get("rotation_deg", [0, 0, 0])) @ Matrix.Diagonal(Vector(s))
    m = rs.to_4x4()
    m.translation = Vector(transform.get("translation", [0, 0, 0]))
    return m


# Blender's Environment Texture reads a direction v at u = 1/2 - atan2(v.y, v.x) / 2 pi and
# v_up = 1/2 + asin(v.z) / pi. Ours reads a probe-space direction d at u = 1/2 + atan2(d.x, -d.z)
# / 2 pi, row acos(d.y) / pi from the top: v = (-d.z, -d.x, d.y) reads the same texel (probe +Y
# up becomes Blender's +Z up, the probe's centre direction -Z becomes +X).
ENV_FROM_PROBE = Matrix(((0, 0, -1), (-1, 0, 0), (0, 1, 0)))


def blender_from_ours(probe):
    """The rotation from ours' world to the Blender scene's: the scene is built in the probe's
    frame, so that the Environment Texture needs no rotation and Cycles' importance map (one
    cell per texel) lines up with the probe's texels. A Mapping-node rotation instead splits a
    bright texel between two cells: a one-texel sun then arrives as rare, heavy samples (on the
    city probe turned 35 degrees the ground came out about 2% dark at 256 spp; docs/cycles.md)."""
    return ENV_FROM_PROBE @ euler_xyz_deg(probe.get("rotation_deg", [0, 0, 0])).transposed()


def blender_matrix(frame, m4):
    """A 4 x 4 object-to-world matrix of ours as a Blender object-to-world matrix."""
    return frame.to_4x4() @ m4


def latlong_direction(u, v):
    """Probe-space direction of lat-long coordinates (u, v) in [0, 1): ours."""
    theta, phi = math.pi * v, 2 * math.pi * (u - 0.5)
    return Vector((math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi)))


def camera_pose(cam, width, height, file):
    """World-to-camera R (rows: right, down, forward), camera centre, fx, fy, cx, cy (ours)."""
    model = cam.get("model", "lookat")
    if model == "lookat":
        eye = Vector(cam["eye"])
        fwd = (Vector(cam["target"]) - eye).normalized()
        right = fwd.cross(Vector(cam.get("up", [0, 1, 0]))).normalized()
        down = fwd.cross(right)
        f = 0.5 * height / math.tan(0.5 * math.radians(cam.get("vfov_deg", 45.0)))
        return Matrix((right, down, fwd)), eye, f, f, 0.5 * (width - 1), 0.5 * (height - 1)
    if model != "opencv":
        raise ConversionError(file, "camera.model", f"unknown model '{model}' (lookat or opencv)")
    if any(float(k) != 0 for k in cam.get("distortion", [])):
        raise ConversionError(file, "camera.distortion",
                              "Cycles' perspective camera has no lens distortion; undistort the photograph "
                              "and set the distortion to zero")
    r = Matrix(cam["rotation"])
    t = Vector(cam["translation"])
    return r, -(r.transposed() @ t), float(cam["fx"]), float(cam["fy"]), float(cam["cx"]), float(cam["cy"])


# Blender's light shines along its local -Z with its face in local XY; ours shines along local
# -Y with its face in local XZ. LIGHT_FROM_BLENDER takes Blender's light axes to ours: x -> x,
# y -> -z, z -> y (a rotation: Blender's size_y runs along ours' local -z, the same extent).
LIGHT_FROM_BLENDER = Matrix(((1, 0, 0), (0, 0, 1), (0, -1, 0)))


def light_energy_factor(kind):
    """Blender's energy for one watt of ours. Ours follows Blender 4 and later (an area light's
    radiance P / (pi A)); Blender 3.4's area light has radiance P / (4 A): pi / 4 of it, so it
    gets 4 / pi more energy (measured: a rect and a disk light's change on the floor came out
    0.786 of ours in 3.4, equal in 5.0; docs/cycles.md)."""
    return 4.0 / math.pi if kind in ("rect", "disk") and bpy.app.version < (4, 0, 0) else 1.0


def light_object(light, frame, index, file):
    """A project light (point, spot, rect or disk; docs/project-format.md) as a Blender light
    object. Its transform's translation and rotation place it; its scale x and z stretch an
    area light's face only, as in ours (core/assets/virtual_lights.cpp)."""
    kind = light.get("type", "point")
    if kind not in ("point", "spot", "rect", "disk"):
        raise ConversionError(file, f"lights[{index}].type", f"unknown light type '{kind}'")
    transform = light.get("transform") or {}
    scale = transform.get("scale", [1, 1, 1])
    name = f"light {index} {light.get('name', '')}"
    data = bpy.data.lights.new(name, "AREA" if kind in ("rect", "disk") else kind.upper())
    data.energy = float(light.get("power_w", 100.0)) * light_energy_factor(kind)
    data.color = light.get("colour", [1, 1, 1])  # in [0, 1], as Blender's
    if kind in ("point", "spot"):
        data.shadow_soft_size = 0.0  # ours: a point, hard shadows
        if hasattr(data, "use_soft_falloff"):  # Blender 4 and later
            data.use_soft_falloff = False
    if kind == "spot":
        data.spot_size = math.radians(min(180.0, max(1.0, float(light.get("spot_angle_deg", 45.0)))))
        data.spot_blend = float(light.get("spot_blend", 0.15))
    elif kind in ("rect", "disk"):
        size = light.get("size", [0.5, 0.5])
        sx = float(size[0]) * float(scale[0])
        sy = float(size[1] if kind == "rect" else size[0]) * float(scale[2])
        if kind == "rect":
            data.shape = "RECTANGLE"
        else:
            data.shape = "DISK" if abs(sx - sy) <= 1e-6 * max(sx, sy) else "ELLIPSE"
        data.size, data.size_y = sx, sy
    obj = bpy.data.objects.new(name, data)
    m = (euler_xyz_deg(transform.get("rotation_deg", [0, 0, 0])) @ LIGHT_FROM_BLENDER).to_4x4()
    m.translation = Vector(transform.get("translation", [0, 0, 0]))
    obj.matrix_world = blender_matrix(frame, m)
    # Ours: a hidden area light's face is not seen by the camera; it lights everything alike.
    obj.visible_camera = bool(light.get("visible", True)) or kind in ("point", "spot")
    return obj


# ---------------------------------------------------------------------------------------------
# Images: each one reaches Cycles as linear values (what ours holds after loading), so that
# interpolation happens on the same numbers.


def resolve(base_dir, p):
    return p if os.path.isabs(p) else os.path.normpath(os.path.join(base_dir, p))


def srgb_to_linear(v):
    return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4


SRGB_LUT = [srgb_to_linear(k / 255.0) for k in range(256)]


def is_linear_file(path):
    return os.path.splitext(path)[1].lower() in (".exr", ".hdr")


def pixels_of(img):
    """RGBA floats of an image, rows bottom-up (Blender's order); raw values for 8-bit images."""
    px = array.array("f", bytes(4 * 4 * img.size[0] * img.size[1]))
    img.pixels.foreach_get(px)
    return px


def open_image(path, file, field, name):
    """The image file as Blender reads it, named `name`; a ConversionError naming `field` where
    it is missing, unreadable or empty."""
    if not os.path.isfile(path):
        raise ConversionError(file, field, f"file not found: {path}")
    try:
        img = bpy.data.images.load(path, check_existing=False)
    except RuntimeError as e:
        raise ConversionError(file, field, f"cannot read {path}: {e}")
    if img.size[0] == 0 or img.size[1] == 0:
        raise ConversionError(file, field, f"cannot read {path} (unsupported or empty image)")
    img.name = name
    return img


def load_linear_image(path, file, field, name):
    """A Blender image of the file's linear values: EXR and HDR as stored, 8-bit PNG/JPEG/TIFF/
    BMP decoded from sRGB with the IEC 61966-2-1 curve (as ours), NaN/Inf replaced by 0."""
    img = open_image(path, file, field, name)
    w, h = img.size
    if is_linear_file(path):
        set_linear(img)
        px = pixels_of(img)
        if math.isfinite(sum(px)):
            return img
        clean = array.array("f", (x if math.isfinite(x) else 0.0 for x in px))
        bpy.data.images.remove(img)
        return float_image(name, w, h, clean)
    if img.is_float:
        raise ConversionError(file, field, f"{path}: only 8-bit LDR images (or EXR/HDR) are supported")
    px = pixels_of(img)
    bpy.data.images.remove(img)
    lut = SRGB_LUT
    lin = array.array("f", (lut[int(round(x * 255.0))] for x in px))
    lin[3::4] = array.array("f", [1.0]) * (w * h)
    return float_image(name, w, h, lin)


def float_image(name, w, h, rgba):
    """A packed float image holding `rgba` (rows bottom-up) as is: linear, no view transform."""
    img = bpy.data.images.new(name, w, h, alpha=True, float_buffer=True)
    set_linear(img)
    img.pixels.foreach_set(rgba)
    img.pack()
    return img


# ---------------------------------------------------------------------------------------------
# Scene parts


def setup_camera(scene, cam, width, height, frame, file):
    r, centre, fx, fy, cx, cy = camera_pose(cam, width, height, file)
    # Blender's camera looks along its local -Z with +Y up the image; ours is OpenCV's.
    to_world = Matrix((r[0], -r[1], -r[2])).transposed().to_4x4()
    to_world.translation = centre
    data = bpy.data.cameras.new("camera")
    data.type = "PERSP"
    data.sensor_fit = "VERTICAL"
    data.sensor_height = 24.0
    # The image height spans H / fy in the plane at unit distance: tan(vfov / 2) = H / (2 fy).
    data.lens = fy * data.sensor_height / height
    # Shifts are fractions of that height; ours has pixel centres at integers, so a centred
    # principal point is ((W - 1) / 2, (H - 1) / 2). Blender's y points up, ours down.
    data.shift_x = (0.5 * (width - 1) - cx) * fy / (fx * height)
    data.shift_y = (cy - 0.5 * (height - 1)) / height
    data.clip_start = 1e-4
    data.clip_end = 1e6
    obj = bpy.data.objects.new("camera", data)
    obj.matrix_world = blender_matrix(frame, to_world)
    scene.collection.objects.link(obj)
    scene.camera = obj
    render = scene.render
    render.resolution_x, render.resolution_y, render.resolution_percentage = width, height, 100
    # Pixels fx / fy times as tall as wide in the image plane give fx != fy.
    render.pixel_aspect_x, render.pixel_aspect_y = (1.0, fx / fy) if fx >= fy else (fy / fx, 1.0)


def setup_world(scene, probe, base_dir, file):
    if probe.get("format", "latlong") != "latlong":
        raise ConversionError(file, "probe.format", "only lat-long probes (unwrap a mirror ball first: "
                              "diffphoton calibrate probe)")
    img = load_linear_image(resolve(base_dir, probe["path"]), file, "probe.path", "probe")
    world = bpy.data.worlds.new("probe")
    use_nodes(world)
    nodes, links = world.node_tree.nodes, world.node_tree.links
    nodes.clear()
    # The scene is in the probe's frame (blender_from_ours): the texture reads the ray direction.
    env = nodes.new("ShaderNodeTexEnvironment")
    env.image = img
    env.interpolation = "Closest"  # ours is piecewise constant per texel
    env.projection = "EQUIRECTANGULAR"
    # Ours never samples negative probe pixels (Blender's probes hold a few near -1e-3).
    clamp = nodes.new("ShaderNodeVectorMath")
    clamp.operation = "MAXIMUM"
    clamp.inputs[1].default_value = (0.0, 0.0, 0.0)
    bg = nodes.new("ShaderNodeBackground")
    bg.inputs["Strength"].default_value = float(probe.get("intensity", 1.0))
    out = nodes.new("ShaderNodeOutputWorld")
    links.new(env.outputs["Color"], clamp.inputs[0])
    links.new(clamp.outputs["Vector"], bg.inputs["Color"])
    links.new(bg.outputs["Background"], out.inputs["Surface"])
    # An importance map of one cell per probe texel (cells land on texel centres), so that a
    # one-texel sun is found by light sampling.
    world.cycles.sampling_method = "MANUAL"
    world.cycles.sample_map_resolution = int(img.size[0])
    scene.world = world
    return world


def new_mesh_object(name, verts, faces, uvs=None, normals=None):
    """A mesh object from vertices and faces in ours' local coordinates. `uvs` are ours, one
    per face corner in face order; `normals` (one per vertex) make it smooth-shaded with
    exactly those normals."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(map(float, v)) for v in verts], [], [tuple(map(int, f)) for f in faces])
    if uvs is not None:
        mesh.uv_layers.new(name="UVMap").data.foreach_set("uv", [float(c) for uv in uvs for c in uv])
    mesh.validate()
    if normals is not None:
        set_vertex_normals(mesh, normals)
    return bpy.data.objects.new(name, mesh)


def set_vertex_normals(mesh, normals):
    mesh.polygons.foreach_set("use_smooth", [True] * len(mesh.polygons))
    if hasattr(mesh, "use_auto_smooth"):  # Blender 3.4: custom split normals need auto smooth;
        mesh.use_auto_smooth = True       # Blender 4.1 dropped it and always uses them
        mesh.auto_smooth_angle = math.pi
    mesh.normals_split_custom_set_from_vertices([tuple(map(float, n)) for n in normals])


def plane_geometry(size):
    hx, hz = 0.5 * size[0], 0.5 * size[1]
    # As core/geometry make_plane: counter-clockwise seen from +Y, UVs (0,0) (1,0) (1,1) (0,1).
    verts = [(-hx, 0, hz), (hx, 0, hz), (hx, 0, -hz), (-hx, 0, -hz)]
    return verts, [(0, 1, 2, 3)], [(0, 0), (1, 0), (1, 1), (0, 1)]


def box_geometry(size):
    h = Vector(size) * 0.5
    # As core/geometry make_box: per face (n, u, v) with cross(u, v) = n.
    faces_def = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
                 ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
                 ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
    verts, faces, uvs = [], [], []
    for n, u, v in faces_def:
        c, u, v = Vector(n) * h, Vector(u) * h, Vector(v) * h  # component-wise products
        base = len(verts)
        verts += [c - u - v, c + u - v, c + u + v, c - u + v]
        uvs += [(0, 0), (1, 0), (1, 1), (0, 1)]
        faces.append((base, base + 1, base + 2, base + 3))
    return verts, faces, uvs


def sphere_geometry(radius, segments, rings, triangles=False):
    """A UV sphere as core/geometry make_uv_sphere builds it: the same vertices, radial normals,
    corner UVs (u = phi / 2 pi with phi from +X towards +Z, v = 1 at the north pole) and, with
    `triangles`, the same triangles (otherwise quads)."""
    verts, normals, faces, uvs = [(0, radius, 0)], [(0, 1, 0)], [], []
    for r in range(1, rings):
        theta = math.pi * r / rings
        for j in range(segments):
            phi = 2 * math.pi * j / segments
            d = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            verts.append(tuple(radius * x for x in d))
            normals.append(d)
    verts.append((0, -radius, 0))
    normals.append((0, -1, 0))
    south = len(verts) - 1

    def ring(r, j):
        return 1 + (r - 1) * segments + j % segments

    def uv(r, j):
        return (j / segments, 1 - r / rings)

    # With phi growing from +X towards +Z these orders are counter-clockwise from outside.
    for j in range(segments):
        faces.append((0, ring(1, j + 1), ring(1, j)))
        uvs += [((j + 0.5) / segments, 1.0), uv(1, j + 1), uv(1, j)]
    for r in range(1, rings - 1):
        for j in range(segments):
            a, b, c, d = ring(r, j), ring(r, j + 1), ring(r + 1, j + 1), ring(r + 1, j)
            ua, ub, uc, ud = uv(r, j), uv(r, j + 1), uv(r + 1, j + 1), uv(r + 1, j)
            if triangles:
                faces += [(a, b, c), (a, c, d)]
                uvs += [ua, ub, uc, ua, uc, ud]
            else:
                faces.append((a, b, c, d))
                uvs += [ua, ub, uc, ud]
    for j in range(segments):
        faces.append((south, ring(rings - 1, j), ring(rings - 1, j + 1)))
        uvs += [((j + 0.5) / segments, 0.0), uv(rings - 1, j), uv(rings - 1, j + 1)]
    return verts, faces, normals, uvs


def is_exact_sphere(shape, transform):
    """Ours intersects an exact sphere when the scale is uniform (and then computes texture
    coordinates from the direction); otherwise it renders its 96 x 48 UV mesh."""
    if shape.get("type") != "sphere":
        return False
    scale = (transform or {}).get("scale", [1, 1, 1])
    return max(scale) - min(scale) <= 1e-6 * max(scale)


def import_mesh(path, name, file, field):
    """Objects of a mesh file, vertices in the file's own coordinates (no axis conversion)."""
    if not os.path.isfile(path):
        raise ConversionError(file, field, f"file not found: {path}")
    before = set(bpy.data.objects)
    ext = os.path.splitext(path)[1].lower()
    if ext == ".obj":
        # forward +Y, up +Z is the identity: the file's coordinates are kept as they are.
        bpy.ops.wm.obj_import(filepath=path, forward_axis="Y", up_axis="Z")
    elif ext == ".ply" and ply_importer() == "wm":
        # Blender 4's importer (forward +Y, up +Z: the identity); it reads the file's normals.
        bpy.ops.wm.ply_import(filepath=path, forward_axis="Y", up_axis="Z")
    elif ext == ".ply":
        bpy.ops.import_mesh.ply(filepath=path)  # Blender 3.4's Python add-on: no axes, no normals
    elif ext in (".gltf", ".glb"):
        import_gltf(path, file, field)
    elif ext == ".fbx":
        import_fbx(path, file, field)
    elif ext == ".stl":
        import_stl(path, file, field)
    else:
        raise ConversionError(file, field, f"{path}: Cycles meshes are read from OBJ, PLY, STL, FBX or glTF 2.0 only")
    new = [o for o in bpy.data.objects if o not in before]
    objs = [o for o in new if o.type == "MESH"]
    if not objs:
        raise ConversionError(file, field, f"{path}: the file holds no mesh")
    # glTF's importer turns the file's +Y up to Blender's +Z up (x, y, z) -> (x, -z, y); ours
    # reads the file's own coordinates (Y up, as ours' world), so that is undone.
    undo = GLTF_FILE_FROM_BLENDER.to_4x4() if ext in (".gltf", ".glb") else Matrix.Identity(4)
    for o in objs:
        world = o.matrix_world.copy()  # the node hierarchy's placement, parents included
        o.parent = None
        for coll in list(o.users_collection):
            coll.objects.unlink(o)
        o.data.transform(undo @ world)  # bake any importer placement into the vertices
        o.matrix_world = Matrix.Identity(4)
        o.name = name
        if ext == ".stl":  # ours shades an STL's facets flat, by the normals the file gives them
            for poly in o.data.polygons:
                poly.use_smooth = False
        elif not o.data.has_custom_normals:
            smooth_normals_like_ours(o.data)
    for o in new:  # the importer's empties, cameras and lights: not ours
        if o.type != "MESH":
            bpy.data.objects.remove(o, do_unlink=True)
    return objs


# Blender coordinates of glTF's importer back to the file's: (x, y, z) -> (x, z, -y), by rows.
GLTF_FILE_FROM_BLENDER = Matrix(((1, 0, 0), (0, 0, 1), (0, -1, 0)))


def import_gltf(path, file, field):
    """A glTF 2.0 file (.gltf with its side files, or .glb) by Blender's bundled importer (3.4
    and 5.0), which builds each glTF material as a Principled BSDF node tree with its textures
    (base colour sRGB; metallic-roughness and normal maps non-colour, a tangent-space Normal
    Map node), as ours reads the file's materials where material_source is "file"."""
    enable_addon("io_scene_gltf2", bpy.ops.import_scene.gltf)
    # Debian's Blender 3.4 importer uses numpy's aliases np.bool etc., which NumPy 1.24 removed
    # (AttributeError in set_poly_smoothing); the builtins they stood for take their place.
    import numpy as np
    for alias, builtin in (("bool", bool), ("int", int), ("float", float), ("object", object)):
        if alias not in np.__dict__:
            setattr(np, alias, builtin)
    try:
        bpy.ops.import_scene.gltf(filepath=path)
    except (RuntimeError, AttributeError) as e:
        raise ConversionError(file, field, f"{path}: Blender's glTF importer failed: {e}")


def enable_addon(module, operator):
    """Blender's bundled importer add-on `module` (a bare bpy module starts with none enabled)."""
    try:
        operator.get_rna_type()
    except (KeyError, AttributeError):
        import addon_utils
        addon_utils.enable(module, default_set=True)


def import_fbx(path, file, field):
    """An FBX file by Blender's bundled importer, in the file's own axes (the identity
    orientation, as for OBJ; the project's or the file's up axis is applied by file_frame) and
    in metres from the unit the file declares, as ours reads it."""
    enable_addon("io_scene_fbx", bpy.ops.import_scene.fbx)
    try:
        bpy.ops.import_scene.fbx(filepath=path, use_manual_orientation=True, axis_forward="Y", axis_up="Z",
                                 global_scale=1.0, use_custom_normals=True,
                                 use_image_search=False, use_anim=False)
    except (RuntimeError, AttributeError) as e:
        raise ConversionError(file, field, f"{path}: Blender's FBX importer failed: {e}")


def import_stl(path, file, field):
    """An STL file in its own axes: Blender 4.1 and later have a built-in importer, 3.4 a Python
    add-on."""
    try:
        bpy.ops.wm.stl_import.get_rna_type()
        bpy.ops.wm.stl_import(filepath=path, forward_axis="Y", up_axis="Z", global_scale=1.0)
        return
    except KeyError:
        pass
    except RuntimeError as e:
        raise ConversionError(file, field, f"{path}: Blender's STL importer failed: {e}")
    enable_addon("io_mesh_stl", bpy.ops.import_mesh.stl)
    try:
        bpy.ops.import_mesh.stl(filepath=path, axis_forward="Y", axis_up="Z", global_scale=1.0)
    except RuntimeError as e:
        raise ConversionError(file, field, f"{path}: Blender's STL importer failed: {e}")


def ply_importer():
    """"wm" where Blender has its built-in PLY importer (3.6 and later), else "import_mesh"."""
    try:
        bpy.ops.wm.ply_import.get_rna_type()
        return "wm"
    except KeyError:
        return "import_mesh"


def smooth_normals_like_ours(mesh):
    """Without normals in the file, ours shades smoothly with area-weighted face normals summed
    over the vertices at the same position (core/geometry mesh_loader fill_missing_normals)."""
    n_verts = len(mesh.vertices)
    co = array.array("f", bytes(4 * 3 * n_verts))
    mesh.vertices.foreach_get("co", co)
    mesh.calc_loop_triangles()
    tris = array.array("i", bytes(4 * 3 * len(mesh.loop_triangles)))
    mesh.loop_triangles.foreach_get("vertices", tris)
    acc = [0.0] * (3 * n_verts)
    for t in range(0, len(tris), 3):
        a, b, c = 3 * tris[t], 3 * tris[t + 1], 3 * tris[t + 2]
        e1 = (co[b] - co[a], co[b + 1] - co[a + 1], co[b + 2] - co[a + 2])
        e2 = (co[c] - co[a], co[c + 1] - co[a + 1], co[c + 2] - co[a + 2])
        g = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
        for v in (a, b, c):
            acc[v] += g[0]
            acc[v + 1] += g[1]
            acc[v + 2] += g[2]
    summed = {}
    for i in range(n_verts):
        key = (co[3 * i], co[3 * i + 1], co[3 * i + 2])
        s = summed.setdefault(key, [0.0, 0.0, 0.0])
        s[0] += acc[3 * i]
        s[1] += acc[3 * i + 1]
        s[2] += acc[3 * i + 2]
    normals = []
    for i in range(n_verts):
        s = Vector(summed[(co[3 * i], co[3 * i + 1], co[3 * i + 2])])
        normals.append(s.normalized() if s.length > 1e-30 else Vector((0, 1, 0)))
    set_vertex_normals(mesh, normals)


# The rotation taking a mesh file's up axis to ours' +Y (core/scene Shape::file_frame), by rows.
UP_AXIS_ROTATIONS = {
    "y": ((1, 0, 0), (0, 1, 0), (0, 0, 1)),
    "z": ((1, 0, 0), (0, 0, 1), (0, -1, 0)),
    "-y": ((1, 0, 0), (0, -1, 0), (0, 0, -1)),
    "-z": ((1, 0, 0), (0, 0, -1), (0, 1, 0)),
}


def file_frame(shape, file, field):
    """A mesh file's coordinates to the shape's local frame: its up axis turned to +Y, then
    `unit_scale` (the identity for the other shapes)."""
    if shape.get("type") != "mesh":
        return Matrix.Identity(4)
    axis = shape.get("up_axis", "y")
    if axis not in UP_AXIS_ROTATIONS:
        raise ConversionError(file, field + ".up_axis", f"unknown up axis '{axis}' (y, z, -y, -z)")
    scale = float(shape.get("unit_scale", 1.0))
    return (Matrix(UP_AXIS_ROTATIONS[axis]) * scale).to_4x4()


def shape_objects(shape, transform, frame, base_dir, file, field, name):
    """Blender objects for one shape placed by `transform` (ours' conventions)."""
    kind = shape.get("type")
    m = object_matrix(transform)
    if kind == "plane":
        verts, faces, uvs = plane_geometry(shape["size"])
        objs = [new_mesh_object(name, verts, faces, uvs)]
    elif kind == "box":
        verts, faces, uvs = box_geometry(shape["size"])
        objs = [new_mesh_object(name, verts, faces, uvs)]
    elif kind == "sphere":
        exact = is_exact_sphere(shape, transform)
        seg, rings = (SPHERE_SEGMENTS, SPHERE_RINGS) if exact else OURS_SPHERE_MESH
        verts, faces, normals, uvs = sphere_geometry(float(shape["radius"]), seg, rings, triangles=not exact)
        objs = [new_mesh_object(name, verts, faces, None if exact else uvs, normals)]
    elif kind == "mesh":
        objs = import_mesh(resolve(base_dir, shape["path"]), name, file, field + ".path")
    else:
        raise ConversionError(file, field + ".type", f"unknown shape '{kind}' (plane, box, sphere, mesh)")
    m = m @ file_frame(shape, file, field)
    for o in objs:
        o.matrix_world = blender_matrix(frame, m)
    return objs


# ---------------------------------------------------------------------------------------------
# Materials


def node_material(name):
    mat = bpy.data.materials.new(name)
    use_nodes(mat)
    mat.node_tree.nodes.clear()
    out = mat.node_tree.nodes.new("ShaderNodeOutputMaterial")
    out.target = "CYCLES"
    return mat, mat.node_tree.nodes, mat.node_tree.links, out


def load_data_image(path, file, field, name):
    """A Blender image of a data texture (metallic-roughness, normal map): its values as stored,
    never decoded from sRGB (glTF's rule, and ours)."""
    img = open_image(path, file, field, name)
    img.colorspace_settings.name = "Non-Color"
    return img


def texture_albedo(nodes, links, tex_path, sphere_frame, file, field, file_uvs=False):
    """A node giving a texture's albedo clamped to [0, 0.98], looked up as texture_node does."""
    tex = texture_node(nodes, links, load_linear_image(tex_path, file, field, os.path.basename(tex_path)),
                       sphere_frame, file_uvs)
    lo = nodes.new("ShaderNodeVectorMath")
    lo.operation = "MAXIMUM"
    lo.inputs[1].default_value = (0.0, 0.0, 0.0)
    hi = nodes.new("ShaderNodeVectorMath")
    hi.operation = "MINIMUM"
    hi.inputs[1].default_value = (MAX_ALBEDO,) * 3
    links.new(tex.outputs["Color"], lo.inputs[0])
    links.new(lo.outputs["Vector"], hi.inputs[0])
    return hi.outputs["Vector"]


def texture_node(nodes, links, image, sphere_frame, file_uvs=False):
    """An image texture node of `image` looked up as ours looks it up: by the mesh's UVs, or on
    an exact sphere (`sphere_frame`: the scene's blender_from_ours) by the direction from its
    centre. `file_uvs`: the UVs came from a mesh file, whose v ours flips on load, so Blender's
    own lookup of the imported UVs already agrees."""
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = image
    tex.interpolation = "Linear"  # ours: bilinear between texel centres, clamped at the edges
    tex.extension = "EXTEND"
    if sphere_frame is not None:
        # Ours computes an exact sphere's UV from the world direction n of the hit from the
        # centre (the transform's rotation plays no part): u = 1/2 + atan2(n.x, -n.z) / 2 pi,
        # v = acos(n.y) / pi with v = 0 on the top row; Blender's image v = 0 is the bottom row.
        geom = nodes.new("ShaderNodeNewGeometry")
        info = nodes.new("ShaderNodeObjectInfo")
        rel = nodes.new("ShaderNodeVectorMath")
        rel.operation = "SUBTRACT"
        links.new(geom.outputs["Position"], rel.inputs[0])
        links.new(info.outputs["Location"], rel.inputs[1])
        to_ours = nodes.new("ShaderNodeMapping")  # Blender's world frame back to ours
        to_ours.vector_type = "VECTOR"
        to_ours.inputs["Rotation"].default_value = sphere_frame.transposed().to_euler("XYZ")
        links.new(rel.outputs["Vector"], to_ours.inputs["Vector"])
        norm = nodes.new("ShaderNodeVectorMath")
        norm.operation = "NORMALIZE"
        links.new(to_ours.outputs["Vector"], norm.inputs[0])
        sep = nodes.new("ShaderNodeSeparateXYZ")
        links.new(norm.outputs["Vector"], sep.inputs["Vector"])
        neg_z = nodes.new("ShaderNodeMath")
        neg_z.operation = "MULTIPLY"
        neg_z.inputs[1].default_value = -1.0
        links.new(sep.outputs["Z"], neg_z.inputs[0])
        atan = nodes.new("ShaderNodeMath")
        atan.operation = "ARCTAN2"  # atan2(first, second)
        links.new(sep.outputs["X"], atan.inputs[0])
        links.new(neg_z.outputs["Value"], atan.inputs[1])
        u = nodes.new("ShaderNodeMath")
        u.operation = "MULTIPLY_ADD"
        links.new(atan.outputs["Value"], u.inputs[0])
        u.inputs[1].default_value = 1.0 / (2 * math.pi)
        u.inputs[2].default_value = 0.5
        acos = nodes.new("ShaderNodeMath")
        acos.operation = "ARCCOSINE"
        links.new(sep.outputs["Y"], acos.inputs[0])
        v = nodes.new("ShaderNodeMath")
        v.operation = "MULTIPLY_ADD"  # 1 - acos / pi
        links.new(acos.outputs["Value"], v.inputs[0])
        v.inputs[1].default_value = -1.0 / math.pi
        v.inputs[2].default_value = 1.0
        comb = nodes.new("ShaderNodeCombineXYZ")
        links.new(u.outputs["Value"], comb.inputs["X"])
        links.new(v.outputs["Value"], comb.inputs["Y"])
        links.new(comb.outputs["Vector"], tex.inputs["Vector"])
    elif file_uvs:
        uv = nodes.new("ShaderNodeUVMap")
        links.new(uv.outputs["UV"], tex.inputs["Vector"])
    else:
        # Ours reads texture row v * H from the top, Blender's from the bottom: v -> 1 - v.
        uv = nodes.new("ShaderNodeUVMap")
        flip = nodes.new("ShaderNodeMapping")
        flip.vector_type = "POINT"
        flip.inputs["Location"].default_value = (0.0, 1.0, 0.0)
        flip.inputs["Scale"].default_value = (1.0, -1.0, 1.0)
        links.new(uv.outputs["UV"], flip.inputs["Vector"])
        links.new(flip.outputs["Vector"], tex.inputs["Vector"])
    return tex


def diffuse_material(name, albedo, base_dir, sphere_frame, file, field, file_uvs=False):
    mat, nodes, links, out = node_material(name)
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Roughness"].default_value = 0.0  # Lambertian, two-sided as ours
    if isinstance(albedo, list):
        rgb = [min(max(float(a), 0.0), MAX_ALBEDO) for a in albedo]
        bsdf.inputs["Color"].default_value = (*rgb, 1.0)
    elif isinstance(albedo, dict) and "texture" in albedo:
        path = resolve(base_dir, albedo["texture"])
        links.new(texture_albedo(nodes, links, path, sphere_frame, file, field + ".texture", file_uvs),
                  bsdf.inputs["Color"])
    elif albedo == "estimate":
        raise ConversionError(file, field, "'estimate' is resolved by diffphoton at load time; write the "
                              "estimated [r, g, b] into the project for Cycles")
    else:
        raise ConversionError(file, field, "expected [r, g, b] or {\"texture\": path}")
    links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    return mat


def add_gloss(mat, gloss):
    """A real proxy's gloss layer (docs/real-gloss.md) added over its diffuse BSDF: a GGX Glossy
    of roughness `roughness` (Cycles' alpha is roughness squared, as ours) whose colour is
    Schlick's Fresnel from `specular`, F0 + (1 - F0) (1 - cos)^5, with the cosine against the
    shading normal (ours takes the microfacet normal: the same for a polished surface)."""
    f0 = min(max(float(gloss.get("specular", 0.0)), 0.0), 1.0)
    if f0 <= 0:
        return
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    out = next(n for n in nodes if n.type == "OUTPUT_MATERIAL")
    diffuse = out.inputs["Surface"].links[0].from_node
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = "GGX"
    glossy.inputs["Roughness"].default_value = max(float(gloss.get("roughness", 0.1)), 0.03)
    facing = nodes.new("ShaderNodeLayerWeight")  # Facing: 1 - |cos|
    power = nodes.new("ShaderNodeMath")
    power.operation = "POWER"
    power.inputs[1].default_value = 5.0
    links.new(facing.outputs["Facing"], power.inputs[0])
    fresnel = nodes.new("ShaderNodeMapRange")  # F0 + (1 - F0) w
    fresnel.inputs["To Min"].default_value = f0
    fresnel.inputs["To Max"].default_value = 1.0
    links.new(power.outputs["Value"], fresnel.inputs["Value"])
    links.new(fresnel.outputs["Result"], glossy.inputs["Color"])
    add = nodes.new("ShaderNodeAddShader")
    links.new(diffuse.outputs["BSDF"], add.inputs[0])
    links.new(glossy.outputs["BSDF"], add.inputs[1])
    links.new(add.outputs["Shader"], out.inputs["Surface"])


def first_input(bsdf, *names):
    """The first of `names` the node has: Blender 4 renamed the Principled BSDF's inputs."""
    for n in names:
        if n in bsdf.inputs:
            return bsdf.inputs[n]
    raise KeyError(names[0])


def principled_material(name, m, base_dir, sphere_frame, file, field, file_uvs=False):
    """Ours is glTF's metallic-roughness material, which Blender's Principled BSDF takes as its
    glTF importer does. Blender 4 and 5: Specular IOR Level 0.5 is the IOR's own F0, so our
    specular factor s is 0.5 s; Blender 3.4: Specular is F0 / 0.08. Emission is radiance."""
    mat, nodes, links, out = node_material(name)
    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    base = m.get("base_colour", [0.5, 0.5, 0.5])
    if isinstance(base, dict) and "texture" in base:
        path = resolve(base_dir, base["texture"])
        links.new(texture_albedo(nodes, links, path, sphere_frame, file, field + ".base_colour.texture", file_uvs),
                  bsdf.inputs["Base Color"])
    elif isinstance(base, list):
        bsdf.inputs["Base Color"].default_value = (*[min(max(float(c), 0.0), MAX_ALBEDO) for c in base], 1.0)
    else:
        raise ConversionError(file, field + ".base_colour", "expected [r, g, b] or {\"texture\": path}")
    ior = float(m.get("ior", 1.5))
    specular = float(m.get("specular", 1.0))
    bsdf.inputs["Metallic"].default_value = float(m.get("metallic", 0.0))
    bsdf.inputs["Roughness"].default_value = float(m.get("roughness", 0.5))
    if m.get("metallic_roughness_texture"):
        # glTF's rule, as ours: green times the roughness, blue times the metallic.
        path = resolve(base_dir, m["metallic_roughness_texture"])
        image = load_data_image(path, file, field + ".metallic_roughness_texture", os.path.basename(path))
        tex = texture_node(nodes, links, image, sphere_frame, file_uvs)
        sep = nodes.new("ShaderNodeSeparateColor")
        links.new(tex.outputs["Color"], sep.inputs["Color"])
        for channel, key, default in (("Green", "Roughness", 0.5), ("Blue", "Metallic", 0.0)):
            times = nodes.new("ShaderNodeMath")
            times.operation = "MULTIPLY"
            times.inputs[1].default_value = float(m.get(key.lower(), default))
            links.new(sep.outputs[channel], times.inputs[0])
            links.new(times.outputs["Value"], bsdf.inputs[key])
    if m.get("normal_texture"):
        # A tangent-space map by the UVs' tangents (OpenGL's +Y, glTF's and ours). Blender's
        # Strength blends towards the map where glTF scales its X and Y: the same at 0 and 1.
        if not file_uvs:
            # Built-in shapes get their lookup flipped or computed (texture_node); Blender's
            # tangents follow the UV map as stored, so +Y would not be the texture's top.
            raise ConversionError(file, field + ".normal_texture",
                                  "a normal map is converted on meshes from files only, not on built-in shapes")
        path = resolve(base_dir, m["normal_texture"])
        image = load_data_image(path, file, field + ".normal_texture", os.path.basename(path))
        tex = texture_node(nodes, links, image, sphere_frame, file_uvs)
        normal_map = nodes.new("ShaderNodeNormalMap")
        normal_map.space = "TANGENT"
        normal_map.inputs["Strength"].default_value = float(m.get("normal_scale", 1.0))
        links.new(tex.outputs["Color"], normal_map.inputs["Color"])
        links.new(normal_map.outputs["Normal"], bsdf.inputs["Normal"])
    bsdf.inputs["IOR"].default_value = ior
    if "Specular IOR Level" in bsdf.inputs:
        bsdf.inputs["Specular IOR Level"].default_value = 0.5 * specular
    else:
        bsdf.inputs["Specular"].default_value = specular * ((ior - 1) / (ior + 1)) ** 2 / 0.08
    first_input(bsdf, "Transmission Weight", "Transmission").default_value = float(m.get("transmission", 0.0))
    emission = [float(e) for e in m.get("emission", [0, 0, 0])]
    first_input(bsdf, "Emission Color", "Emission").default_value = (*emission, 1.0)
    if "Emission Strength" in bsdf.inputs:
        bsdf.inputs["Emission Strength"].default_value = 1.0
    links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    return mat


def object_material(name, m, base_dir, sphere_frame, file, field, file_uvs=False):
    kind = m.get("type", "diffuse")
    if kind == "diffuse":
        return diffuse_material(name, m.get("albedo", [0.5, 0.5, 0.5]), base_dir, sphere_frame, file,
                                field + ".albedo", file_uvs)
    if kind == "principled":
        return principled_material(name, m, base_dir, sphere_frame, file, field, file_uvs)
    mat, nodes, links, out = node_material(name)
    if kind == "mirror":
        # Ours: reflectance times a perfect reflection, no Fresnel, two-sided: a sharp Glossy.
        bsdf = nodes.new("ShaderNodeBsdfGlossy")
        make_sharp(bsdf)
        bsdf.inputs["Color"].default_value = (*[float(x) for x in m.get("reflectance", [0.95] * 3)], 1.0)
        links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
        return mat
    if kind != "glass":
        raise ConversionError(file, field + ".type", f"unknown material '{kind}' (diffuse, mirror, glass, principled)")
    ior = float(m.get("ior", 1.5))
    tint = [float(t) for t in m.get("tint", [1, 1, 1])]
    if all(t == 1.0 for t in tint):
        bsdf = nodes.new("ShaderNodeBsdfGlass")
        make_sharp(bsdf)
        bsdf.inputs["IOR"].default_value = ior
        bsdf.inputs["Color"].default_value = (1, 1, 1, 1)
        links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
        return mat
    # Ours multiplies by `tint` once per pass through (on entering) and never tints reflection;
    # the Glass BSDF's colour would tint both. The same Fresnel mix by hand, with sqrt(tint) on
    # each refraction (in and out: tint per pass through).
    fresnel = nodes.new("ShaderNodeFresnel")
    fresnel.inputs["IOR"].default_value = ior
    refr = nodes.new("ShaderNodeBsdfRefraction")
    make_sharp(refr)
    refr.inputs["IOR"].default_value = ior
    refr.inputs["Color"].default_value = (*[math.sqrt(t) for t in tint], 1.0)
    refl = nodes.new("ShaderNodeBsdfGlossy")
    make_sharp(refl)
    refl.inputs["Color"].default_value = (1, 1, 1, 1)
    mix = nodes.new("ShaderNodeMixShader")
    links.new(fresnel.outputs["Fac"], mix.inputs["Fac"])
    links.new(refr.outputs["BSDF"], mix.inputs[1])
    links.new(refl.outputs["BSDF"], mix.inputs[2])
    links.new(mix.outputs["Shader"], out.inputs["Surface"])
    return mat


# ---------------------------------------------------------------------------------------------
# The scene


class CyclesScene:
    """A project converted into a fresh Blender scene.

    mode "catcher": real proxies are shadow catchers, virtual objects are rendered, the film is
    transparent and each render is composited onto the photograph. mode "real-only": proxies
    as plain diffuse surfaces, no objects, the probe visible: what `diffphoton reference
    --real-only` renders.

    `artist`: Cycles as artists run it in Blender 5 (artist_settings) instead of the plain
    estimator that matches ours (setup_render)."""

    def __init__(self, project_path, mode="catcher", threads=0, project=None, artist=False):
        """`project`: the project's JSON already read (the script `diffphoton export blender`
        writes carries it); `project_path` then only names it in messages and anchors relative
        paths."""
        if artist:
            check_artist_support()
        self.file = project_path
        if project is not None:
            p = project
        else:
            with open(project_path) as f:
                try:
                    p = json.load(f)
                except json.JSONDecodeError as e:
                    raise ConversionError(project_path, "", f"invalid JSON: {e}")
        self.project = p
        base_dir = os.path.dirname(os.path.abspath(project_path))
        for key in ("photo", "probe", "camera"):
            if key not in p:
                raise ConversionError(project_path, key, "required")
        bpy.ops.wm.read_factory_settings(use_empty=True)
        self.photo = load_linear_image(resolve(base_dir, p["photo"]["path"]), project_path, "photo.path", "photo")
        self.photo_scale = 2.0 ** float(p["photo"].get("exposure", 0.0))
        self.width, self.height = self.photo.size
        scene = bpy.context.scene
        self.scene = scene
        scene.render.engine = "CYCLES"
        frame = blender_from_ours(p["probe"])
        setup_camera(scene, p["camera"], self.width, self.height, frame, project_path)
        setup_world(scene, p["probe"], base_dir, project_path)
        self.mode = mode
        self.proxies, self.lamp_layer = [], None
        for i, r in enumerate(p.get("real", [])):
            field = f"real[{i}]"
            sphere_frame = frame if is_exact_sphere(r["shape"], r.get("transform")) else None
            mat = diffuse_material(f"real {i}", r.get("albedo", [0.5, 0.5, 0.5]), base_dir, sphere_frame,
                                   project_path, field + ".albedo", r["shape"].get("type") == "mesh")
            add_gloss(mat, r.get("gloss", {}))
            for o in shape_objects(r["shape"], r.get("transform"), frame, base_dir, project_path, field + ".shape",
                                   f"real {i} {r.get('name', '')}"):
                o.data.materials.clear()  # a proxy is its albedo (and gloss), whatever its file says
                o.data.materials.append(mat)
                o.is_shadow_catcher = mode == "catcher"
                self.proxies.append(o)
                if artist:  # MNEE: caustics cast by the glass objects land on the proxies
                    o.cycles.is_caustics_receiver = True
                scene.collection.objects.link(o)
        if mode == "catcher":
            for i, ob in enumerate(p.get("objects", [])):
                if not ob.get("visible", True):
                    continue
                field = f"objects[{i}]"
                source = ob.get("material_source", "project")
                if source not in ("project", "file"):
                    raise ConversionError(project_path, field + ".material_source",
                                          f"unknown material source '{source}' (project, file)")
                if source == "file" and ob["shape"].get("type") != "mesh":
                    raise ConversionError(project_path, field + ".material_source",
                                          "\"file\" is for mesh objects only")
                sphere_frame = frame if is_exact_sphere(ob["shape"], ob.get("transform")) else None
                mat = object_material(f"object {i}", ob.get("material", {}), base_dir, sphere_frame, project_path,
                                      field + ".material", ob["shape"].get("type") == "mesh")
                for o in shape_objects(ob["shape"], ob.get("transform"), frame, base_dir, project_path,
                                       field + ".shape", f"object {i} {ob.get('name', '')}"):
                    if source == "file" and len(o.data.materials) > 0:
                        # The file's materials, as the importer built them; the project's material
                        # covers the slots the file left empty (ours: faces without a material).
                        for k, slot in enumerate(o.data.materials):
                            if slot is None:
                                o.data.materials[k] = mat
                    else:
                        o.data.materials.clear()  # "project": every face the project's material
                        o.data.materials.append(mat)
                    if artist and ob.get("material", {}).get("type") == "glass":
                        o.cycles.is_caustics_caster = True
                    scene.collection.objects.link(o)
            # The lights are virtual, as the objects: a render of the real proxies has none.
            lamps = [light_object(light, frame, i, project_path) for i, light in enumerate(p.get("lights", []))]
            if lamps:
                self.setup_lamp_layer(lamps)
        self.setup_render(int(p.get("render", {}).get("max_depth", 8)), threads)
        self.artist = artist
        if artist:
            self.artist_settings()
        if mode == "catcher":
            self.setup_composite()

    def setup_lamp_layer(self, lamps):
        """A shadow catcher keeps only what the objects take from the light on it: a lamp lights
        it with and without them alike, so the lamps' light on the real proxies never reaches
        the composite. A second view layer renders it: the proxies as plain diffuse copies
        (each layer sees its own set), the lamps in a light group whose pass is that light
        alone, added to the backplate (setup_composite). An area light's face, where the
        camera sees it, comes from that pass too: the main layer's lamps (copies of the same
        lights) are hidden from the camera, or the face would be counted twice."""
        scene = self.scene
        main = scene.view_layers[0]
        layer = scene.view_layers.new("lamps on the real proxies")
        layer.lightgroups.add(name="lamps")

        def collection(name, excluded_from):
            c = bpy.data.collections.new(name)
            scene.collection.children.link(c)
            excluded_from.layer_collection.children[c.name].exclude = True
            return c

        catchers = collection("real proxies (shadow catchers)", layer)
        plain = collection("real proxies (lit by the lamps)", main)
        lighting = collection("lamps (lighting the objects)", layer)
        seen = collection("lamps (on the real proxies, and seen)", main)
        for o in self.proxies:
            scene.collection.objects.unlink(o)
            catchers.objects.link(o)
            copy = o.copy()  # the same mesh and material
            copy.name = o.name + " (lit)"
            copy.is_shadow_catcher = False
            plain.objects.link(copy)
        for lamp in lamps:
            copy = lamp.copy()  # the same light
            copy.name = lamp.name + " (seen)"
            copy.lightgroup = "lamps"
            seen.objects.link(copy)
            lamp.visible_camera = False
            lighting.objects.link(lamp)
        self.lamp_layer = layer

    def setup_render(self, max_depth, threads):
        scene, c = self.scene, self.scene.cycles
        c.device = "CPU"
        c.use_adaptive_sampling = False  # plain samples per pixel, as ours
        c.use_denoising = False
        c.time_limit = 0.0
        c.pixel_filter_type = "BOX"
        c.filter_width = 1.0  # uniform jitter inside the pixel, as ours
        # Ours traces max_depth segments with next-event estimation at the last vertex: light
        # at up to max_depth vertices, Cycles' max_bounces + 1 (0 is direct light only).
        bounces = max(0, max_depth - 1)
        c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = bounces
        c.transparent_max_bounces = bounces
        c.volume_bounces = 0
        c.caustics_reflective = c.caustics_refractive = True
        c.blur_glossy = 0.0  # no filter glossy: sharp caustics, as ours
        c.sample_clamp_direct = c.sample_clamp_indirect = 0.0  # no clamping (default indirect 10)
        c.light_sampling_threshold = 0.0
        c.use_auto_tile = False
        if hasattr(c, "use_light_tree"):  # Blender 3.5 and later: off, as Blender 3.4 samples
            c.use_light_tree = False
        if hasattr(c, "use_guiding"):
            c.use_guiding = False
        scene.render.use_persistent_data = False  # each render syncs and builds its BVH anew
        scene.render.threads_mode = "FIXED" if threads > 0 else "AUTO"
        if threads > 0:
            scene.render.threads = threads
        scene.render.film_transparent = self.mode == "catcher"
        scene.render.use_compositing = self.mode == "catcher"
        scene.render.use_sequencer = False
        scene.render.dither_intensity = 0.0
        scene.view_settings.view_transform = "Standard"
        scene.view_settings.look = "None"
        scene.view_settings.exposure = 0.0
        scene.view_settings.gamma = 1.0
        settings = scene.render.image_settings
        settings.file_format = "OPEN_EXR"
        settings.color_mode = "RGB"
        settings.color_depth = "32"
        settings.exr_codec = "ZIP"
        scene.view_layers[0].cycles.use_pass_shadow_catcher = self.mode == "catcher"

    def artist_settings(self):
        """Cycles as artists run it in Blender 5, on top of setup_render's scene: Open Image
        Denoise on the render with albedo and normal guides (accurate prefilter, CPU), adaptive
        sampling to a noise threshold of 0.01, path guiding (surfaces and volumes; CPU only), the
        light tree, and MNEE shadow caustics (the constructor marks glass objects as casters and
        the proxies as receivers; the world is the only light and is marked here). Everything
        else stays as setup_render sets it (no clamping, no filter glossy, the bounces of ours)."""
        c, world = self.scene.cycles, self.scene.world
        c.use_denoising = True
        c.denoiser = "OPENIMAGEDENOISE"
        c.denoising_input_passes = "RGB_ALBEDO_NORMAL"
        c.denoising_prefilter = "ACCURATE"
        c.denoising_use_gpu = False
        c.use_adaptive_sampling = True
        c.adaptive_threshold = 0.01
        c.adaptive_min_samples = 0  # automatic
        c.use_guiding = True
        c.use_surface_guiding = c.use_volume_guiding = True
        c.use_light_tree = True
        world.cycles.is_caustics_light = True
        for o in self.scene.objects:
            if o.type == "LIGHT":
                o.data.cycles.is_caustics_light = True

    def setup_composite(self):
        """Compositor: Combined + (1 - Combined.alpha) * photo * ShadowCatcher (Cycles' own
        recipe: multiply the backplate by the Shadow Catcher pass, then alpha-over Combined),
        with lamps + (1 - Combined.alpha) * their light on the proxies (setup_lamp_layer)."""
        if hasattr(self.scene, "compositing_node_group"):
            self.setup_composite_group()
            return
        scene = self.scene
        scene.use_nodes = True
        tree = scene.node_tree
        tree.nodes.clear()
        layers = tree.nodes.new("CompositorNodeRLayers")
        photo = tree.nodes.new("CompositorNodeImage")
        photo.image = self.photo
        exposure = tree.nodes.new("CompositorNodeMixRGB")  # the photo's exposure: 2^stops
        exposure.blend_type = "MULTIPLY"
        exposure.use_alpha = False
        exposure.inputs["Fac"].default_value = 1.0
        exposure.inputs[2].default_value = (self.photo_scale,) * 3 + (1.0,)
        mul = tree.nodes.new("CompositorNodeMixRGB")
        mul.blend_type = "MULTIPLY"
        mul.use_alpha = False
        mul.inputs["Fac"].default_value = 1.0
        over = tree.nodes.new("CompositorNodeAlphaOver")
        over.use_premultiply = False  # Combined is premultiplied: bg * (1 - alpha) + fg
        over.premul = 0.0
        over.inputs["Fac"].default_value = 1.0
        comp = tree.nodes.new("CompositorNodeComposite")
        comp.use_alpha = False
        tree.links.new(photo.outputs["Image"], exposure.inputs[1])
        tree.links.new(exposure.outputs["Image"], mul.inputs[1])
        tree.links.new(layers.outputs["Shadow Catcher"], mul.inputs[2])
        backplate = mul.outputs["Image"]
        if self.lamp_layer is not None:  # + the lamps' light on the real proxies
            lamps = tree.nodes.new("CompositorNodeRLayers")
            lamps.layer = self.lamp_layer.name
            add = tree.nodes.new("CompositorNodeMixRGB")
            add.blend_type = "ADD"
            add.use_alpha = False
            add.inputs["Fac"].default_value = 1.0
            tree.links.new(backplate, add.inputs[1])
            tree.links.new(lamps.outputs["Combined_lamps"], add.inputs[2])
            backplate = add.outputs["Image"]
        tree.links.new(backplate, over.inputs[1])
        tree.links.new(layers.outputs["Image"], over.inputs[2])
        tree.links.new(over.outputs["Image"], comp.inputs["Image"])

    def setup_composite_group(self):
        """The same composite in Blender 5, whose compositor is a node group
        (scene.compositing_node_group) ending in a Group Output, with the shader nodes' Mix for
        colour arithmetic and Alpha Over's options as inputs."""
        scene = self.scene
        tree = bpy.data.node_groups.new("composite", "CompositorNodeTree")
        tree.interface.new_socket("Image", in_out="OUTPUT", socket_type="NodeSocketColor")
        scene.compositing_node_group = tree
        layers = tree.nodes.new("CompositorNodeRLayers")
        layers.scene = scene
        photo = tree.nodes.new("CompositorNodeImage")
        photo.image = self.photo

        def multiply(a, b, blend="MULTIPLY"):
            mix = tree.nodes.new("ShaderNodeMix")
            mix.data_type = "RGBA"
            mix.blend_type = blend
            mix.clamp_result = False
            mix.clamp_factor = True
            mix.inputs["Factor"].default_value = 1.0
            sockets = {sk.identifier: sk for sk in (*mix.inputs, *mix.outputs)}
            for socket, value in ((sockets["A_Color"], a), (sockets["B_Color"], b)):
                if isinstance(value, tuple):
                    socket.default_value = value
                else:
                    tree.links.new(value, socket)
            return sockets["Result_Color"]

        exposed = multiply(photo.outputs["Image"], (self.photo_scale,) * 3 + (1.0,))  # 2^stops
        backplate = multiply(exposed, layers.outputs["Shadow Catcher"])
        if self.lamp_layer is not None:  # + the lamps' light on the real proxies
            lamps = tree.nodes.new("CompositorNodeRLayers")
            lamps.scene = scene
            lamps.layer = self.lamp_layer.name
            backplate = multiply(backplate, lamps.outputs["Combined_lamps"], "ADD")
        over = tree.nodes.new("CompositorNodeAlphaOver")
        over.inputs["Factor"].default_value = 1.0
        over.inputs["Straight Alpha"].default_value = False  # Combined is premultiplied
        out = tree.nodes.new("NodeGroupOutput")
        tree.links.new(backplate, over.inputs["Background"])
        tree.links.new(layers.outputs["Image"], over.inputs["Foreground"])
        tree.links.new(over.outputs["Image"], out.inputs["Image"])

    def render(self, spp, seed, exr_path):
        """Renders `spp` samples per pixel with `seed` and writes the result (the composite, or
        the plain render in real-only mode) as a linear RGB float EXR. Returns the wall time of
        the render call: scene sync, BVH build and image upload included, writing the file not."""
        c = self.scene.cycles
        c.samples = int(spp)
        c.seed = int(seed)
        t0 = time.perf_counter()
        bpy.ops.render.render(write_still=False)
        seconds = time.perf_counter() - t0
        bpy.data.images["Render Result"].save_render(exr_path, scene=self.scene)
        return seconds


def check_artist_support():
    """Artist mode needs Blender 5 (its light tree came in 3.5, its Cycles settings here are
    Blender 5's): raises ArtistUnsupported naming the Blender that runs."""
    if bpy.app.version < (5, 0, 0):
        raise ArtistUnsupported(f"--artist needs Blender 5 (Cycles as artists run it: Open Image Denoise "
                                f"with albedo and normal guides, adaptive sampling, path guiding, the light "
                                f"tree, MNEE); this is Blender {bpy.app.version_string}, whose Cycles has no "
                                f"light tree")


class ArtistUnsupported(Exception):
    """--artist under a Blender older than 5."""


def read_exr(path):
    """(width, height, RGB floats) of an EXR written by either renderer, rows top-down (ours'
    order)."""
    img = load_linear_image(path, path, "", os.path.basename(path))
    w, h = img.size
    px = pixels_of(img)
    bpy.data.images.remove(img)
    rgb = array.array("f")
    for y in range(h - 1, -1, -1):
        row = px[4 * w * y:4 * w * (y + 1)]
        del row[3::4]
        rgb.extend(row)
    return w, h, rgb
