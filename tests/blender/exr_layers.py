# Blender's compositor reading svbrdf-render's layered EXR (tests/blender/README.md, `exr-layers`):
# an Image node on the EXR, each layer it offers routed to the Composite output, rendered and saved as a
# 32-bit EXR, whose pixel (X, Y) (from the top-left, as svbrdf-render counts) is printed as
#   LAYER <socket> <v0> <v1> <v2>
# for the sockets albedo, N, Depth (the Z channel) and mip_level, after a line SOCKETS listing all.
#
#   blender -b --factory-startup --python-exit-code 1 --python exr_layers.py -- EXR WIDTH HEIGHT X Y WORKDIR
import sys

import bpy

exr, width, height, x, y, work = sys.argv[sys.argv.index("--") + 1:][:6]
width, height, x, y = int(width), int(height), int(x), int(y)
image = bpy.data.images.load(exr)
scene = bpy.context.scene
# The cheapest engine: the scene itself is not what is looked at, only the compositor's input image.
scene.render.engine = "BLENDER_WORKBENCH"
scene.use_nodes = True
tree = scene.node_tree
for n in list(tree.nodes):
    tree.nodes.remove(n)
source = tree.nodes.new("CompositorNodeImage")
source.image = image
composite = tree.nodes.new("CompositorNodeComposite")
print("SOCKETS", " ".join(o.name for o in source.outputs))
# The frame is the EXR's size (given: a multilayer image reads its size as (0, 0) until drawn).
scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = width, height, 100
settings = scene.render.image_settings
settings.file_format = "OPEN_EXR"
settings.color_depth = "32"
for socket in ("albedo", "N", "Depth", "mip_level"):
    tree.links.new(source.outputs[socket], composite.inputs["Image"])
    bpy.ops.render.render()
    path = f"{work}/blender_{socket}.exr"
    bpy.data.images["Render Result"].save_render(path)
    result = bpy.data.images.load(path)
    pixels = list(result.pixels)  # loads the image: its size reads (0, 0) before
    w, h = result.size
    # Blender's pixel rows run from the bottom up.
    k = ((h - 1 - y) * w + x) * 4
    p = pixels[k:k + 3]
    print("LAYER", socket, *(f"{v:.9g}" for v in p))
