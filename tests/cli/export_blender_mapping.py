"""The Mapping-node rotation docs/cycles.md gives for a scene rebuilt in Blender's axes (runs
inside Blender; used by export_blender.sh).

    blender -b --factory-startup --python-exit-code 1 --python export_blender_mapping.py -- \\
        PROJECT OUT_DIR

Renders the project as dp_cycles.py builds it (the probe's frame, no Mapping node), then the
same scene moved into Blender's axes (ours' x -> C x, C: (x, y, z) -> (x, -z, y)) with the
probe through a Vector Mapping node of rotation Z = -(yaw + 90 deg), and then with Z = +(yaw +
90 deg), a wrong sign (the objects hidden from the camera, their shadows kept). Prints the IoU of each one's shadow (composite below 0.9 of the plate)
against the first as `documented_iou X wrong_sign_iou Y`. The probe must be turned about the
vertical only.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench", "cycles"))
import check_conversion  # noqa: E402
import dp_cycles  # noqa: E402
from mathutils import Matrix  # noqa: E402

C = Matrix(((1, 0, 0), (0, 0, -1), (0, 1, 0)))  # ours' Y-up to Blender's Z-up, as its importers


def shadow(path, plate):
    w, h, rgb = check_conversion.read_exr(path)
    return [x < 0.9 * plate for x in check_conversion.luminance(rgb)]


def iou(a, b):
    union = sum(1 for x, y in zip(a, b) if x or y)
    return sum(1 for x, y in zip(a, b) if x and y) / union if union else 1.0


def main():
    project, out = sys.argv[sys.argv.index("--") + 1:][:2]
    cs = dp_cycles.CyclesScene(project, mode="catcher", threads=2)
    rot = cs.project["probe"].get("rotation_deg", [0, 0, 0])
    assert rot[0] == 0 and rot[2] == 0, "the probe must be turned about the vertical only"
    yaw = float(rot[1])
    # The documented general formula reduces to the yaw-only one.
    general = (dp_cycles.ENV_FROM_PROBE @ dp_cycles.euler_xyz_deg(rot).transposed() @ C.transposed()).to_euler("XYZ")
    expected = Matrix.Rotation(math.radians(-(yaw + 90)), 3, "Z").to_euler("XYZ")
    assert all(abs(math.sin(p - q)) < 1e-5 for p, q in zip(general, expected)), (general, expected)
    # The objects leave the camera's view and keep casting their shadows: what is below the
    # plate is then shadow only.
    for o in cs.scene.objects:
        if o.name.startswith("object "):
            o.visible_camera = False
    spp, seed = 64, 1
    exported = os.path.join(out, "frame-probe.exr")
    cs.render(spp, seed, exported)
    # Into Blender's axes: every object (the camera too) by C times the inverse of the frame.
    to_blender_axes = (C @ dp_cycles.blender_from_ours(cs.project["probe"]).transposed()).to_4x4()
    for o in cs.scene.objects:
        o.matrix_world = to_blender_axes @ o.matrix_world
    nodes, links = cs.scene.world.node_tree.nodes, cs.scene.world.node_tree.links
    coords = nodes.new("ShaderNodeTexCoord")
    mapping = nodes.new("ShaderNodeMapping")
    mapping.vector_type = "VECTOR"
    links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], nodes["Environment Texture"].inputs["Vector"])
    results = {}
    for name, z in (("documented", -(yaw + 90)), ("wrong_sign", yaw + 90)):
        mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(z))
        results[name] = os.path.join(out, f"axes-{name}.exr")
        cs.render(spp, seed, results[name])
    plate = 0.5  # the test's grey plate
    ref = shadow(exported, plate)
    print(f"documented_iou {iou(ref, shadow(results['documented'], plate)):.4f} "
          f"wrong_sign_iou {iou(ref, shadow(results['wrong_sign'], plate)):.4f} shadow_pixels {sum(ref)}",
          flush=True)


main()
