"""The lights of a .blend that an exported script saved, against the project's (used by
export_blender.sh; runs in Blender 3.4 or as Blender 5's Python module):

    blender -b --factory-startup --python-exit-code 1 --python export_blender_lights.py -- BLEND PROJECT
    python export_blender_lights.py -- BLEND PROJECT

Each project light must arrive as a Blender light of its kind, power and colour, at its
position, shining along its direction (Blender's local -Z, ours' local -Y turned by the Euler
XYZ rotation), an area light's face of its size with its local x along ours' local x, seen by
the camera as `visible` says. Directions are compared in ours' world through the scene's frame
(dp_cycles.blender_from_ours, as the objects are placed). Prints `lights_ok N` at the end.
"""
import json
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench", "cycles"))
import dp_cycles  # noqa: E402


def rotation(deg):
    """Ours' Euler XYZ rotation (X applied first), written out rather than taken from dp_cycles."""
    x, y, z = (math.radians(float(a)) for a in deg)
    rx = Matrix(((1, 0, 0), (0, math.cos(x), -math.sin(x)), (0, math.sin(x), math.cos(x))))
    ry = Matrix(((math.cos(y), 0, math.sin(y)), (0, 1, 0), (-math.sin(y), 0, math.cos(y))))
    rz = Matrix(((math.cos(z), -math.sin(z), 0), (math.sin(z), math.cos(z), 0), (0, 0, 1)))
    return rz @ ry @ rx


def near(what, got, want, tol=1e-4):
    got, want = list(got), list(want)
    assert all(abs(g - w) <= tol * max(1.0, abs(w)) for g, w in zip(got, want)), (what, got, want)


def main():
    blend, project_path = sys.argv[sys.argv.index("--") + 1:][:2]
    bpy.ops.wm.open_mainfile(filepath=blend)
    project = json.load(open(project_path))
    to_ours = dp_cycles.blender_from_ours(project["probe"]).transposed()
    objects = [o for o in bpy.data.objects if o.type == "LIGHT"]
    lights = project.get("lights", [])
    # Each light twice, sharing its data: lighting the main layer's objects (hidden from the
    # camera) and, in the second layer, lighting the plain proxies and seen (dp_cycles.setup_lamp_layer).
    assert len(objects) == 2 * len(lights), (len(objects), len(lights))
    for i, light in enumerate(lights):
        name = f"light {i} {light.get('name', '')}"
        lighting, o = bpy.data.objects[name], bpy.data.objects[name + " (seen)"]
        assert lighting.data == o.data and not lighting.visible_camera, name
        # matrix_basis: Blender 5 leaves matrix_world unevaluated in a file's inactive layer.
        near(name + " the two copies' place", [x for r in lighting.matrix_basis for x in r],
             [x for r in o.matrix_basis for x in r])
        d = o.data
        kind = light["type"]
        assert d.type == {"point": "POINT", "spot": "SPOT", "rect": "AREA", "disk": "AREA"}[kind], (name, d.type)
        # Blender 3.4's area lights shine pi / 4 of Blender 4's at the same energy.
        factor = 4 / math.pi if kind in ("rect", "disk") and bpy.app.version < (4, 0, 0) else 1
        near(name + " energy", [d.energy], [light.get("power_w", 100) * factor])
        near(name + " colour", d.color, light.get("colour", [1, 1, 1]))
        t = light.get("transform", {})
        r = rotation(t.get("rotation_deg", [0, 0, 0]))
        m = o.matrix_basis  # no parents: the object-to-world matrix
        near(name + " position", to_ours @ m.translation, t.get("translation", [0, 0, 0]))
        near(name + " direction", to_ours @ (m.to_3x3() @ Vector((0, 0, -1))).normalized(), r @ Vector((0, -1, 0)))
        if kind == "spot":
            near(name + " spot_size", [d.spot_size], [math.radians(light.get("spot_angle_deg", 45))])
            near(name + " spot_blend", [d.spot_blend], [light.get("spot_blend", 0.15)])
        if kind in ("point", "spot"):
            near(name + " radius", [d.shadow_soft_size], [0])
            assert o.visible_camera, name
            continue
        s = t.get("scale", [1, 1, 1])
        size = light.get("size", [0.5, 0.5])
        near(name + " face's x", to_ours @ (m.to_3x3() @ Vector((1, 0, 0))).normalized(), r @ Vector((1, 0, 0)))
        want_y = (size[1] if kind == "rect" else size[0]) * s[2]
        near(name + " size", [d.size, d.size_y], [size[0] * s[0], want_y])
        shape = "RECTANGLE" if kind == "rect" else ("DISK" if abs(size[0] * s[0] - want_y) < 1e-6 else "ELLIPSE")
        assert d.shape == shape, (name, d.shape, shape)
        assert o.visible_camera == light.get("visible", True), (name, o.visible_camera)
    # A proxy's gloss layer: a GGX Glossy of its roughness, Schlick's Fresnel from its specular.
    for i, r in enumerate(project.get("real", [])):
        mats = [m for m in bpy.data.materials if m.name.startswith(f"real {i}")]
        assert mats, f"no material of real[{i}]"
        glossy = [n for n in mats[0].node_tree.nodes if n.type == "BSDF_GLOSSY"]
        gloss = r.get("gloss", {})
        assert bool(glossy) == (gloss.get("specular", 0) > 0), (i, [n.type for n in mats[0].node_tree.nodes])
        if glossy:
            near(f"real[{i}] roughness", [glossy[0].inputs["Roughness"].default_value], [gloss.get("roughness", 0.1)])
            f0 = [n for n in mats[0].node_tree.nodes if n.type == "MAP_RANGE"][0].inputs["To Min"].default_value
            near(f"real[{i}] F0", [f0], [gloss["specular"]])
    print("lights_ok", len(lights), flush=True)


main()
