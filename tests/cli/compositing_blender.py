"""Recomposites a layered render in Blender's compositor as docs/compositing.md says to:
plate x catcher, then the premultiplied objects over it. Run by compositing_blender.sh:
blender -b --factory-startup --python compositing_blender.py -- RENDER.exr PLATE.exr OUT.exr WIDTH HEIGHT"""
import sys

import bpy

render_path, plate_path, out_path, width, height = sys.argv[sys.argv.index("--") + 1:]
scene = bpy.context.scene
scene.render.engine = "BLENDER_WORKBENCH"  # the 3D scene is not used; the cheapest engine
scene.use_nodes = True
tree = scene.node_tree
for node in list(tree.nodes):
    tree.nodes.remove(node)

render = bpy.data.images.load(render_path)
plate = bpy.data.images.load(plate_path)
# A multilayer image has no size before the compositor reads it: the caller gives it.
scene.render.resolution_x, scene.render.resolution_y = int(width), int(height)
scene.render.resolution_percentage = 100

layers = tree.nodes.new("CompositorNodeImage")
layers.image = render
back = tree.nodes.new("CompositorNodeImage")
back.image = plate
sockets = [o.name for o in layers.outputs]
print("passes", sockets)
for wanted in ("objects", "catcher"):
    if wanted not in sockets:
        raise SystemExit(f"Blender lists no '{wanted}' pass in {render_path}: {sockets}")

multiply = tree.nodes.new("CompositorNodeMixRGB")
multiply.blend_type = "MULTIPLY"
multiply.inputs[0].default_value = 1.0
tree.links.new(back.outputs["Image"], multiply.inputs[1])
tree.links.new(layers.outputs["catcher"], multiply.inputs[2])

over = tree.nodes.new("CompositorNodeAlphaOver")
over.use_premultiply = False  # `objects` is premultiplied already
tree.links.new(multiply.outputs[0], over.inputs[1])
tree.links.new(layers.outputs["objects"], over.inputs[2])

composite = tree.nodes.new("CompositorNodeComposite")
composite.use_alpha = False
tree.links.new(over.outputs[0], composite.inputs["Image"])

settings = scene.render.image_settings
settings.file_format = "OPEN_EXR"
settings.color_depth = "32"
settings.color_mode = "RGB"
scene.render.filepath = out_path
bpy.ops.render.render(write_still=True)
print("wrote", out_path)
