#!/usr/bin/env python3
"""One glTF scene of many texture sets, for bench/render/large_scene.sh.

    bench/render/large_scene.py OUT.gltf SET.gltf...

Each SET.gltf is a texture set as bench/mip/random_texture_set (or `svbrdf-bake material`) writes it:
one material whose textures are image files beside it. The scene places each set's material on its
own 1 m quad, facing +Z, in a grid of ceil(sqrt(N)) columns with 10 cm between quads, and adds a
camera on the +Z axis that sees the whole grid (16:9) and a directional light from above the camera,
so that every material is seen and every one of its textures is looked up. The images are referred
to by their paths relative to OUT's folder, not copied; the quads' geometry is one embedded buffer.
"""
import base64
import json
import math
import os
import struct
import sys


def fail(where, what):
    print(f"large_scene.py: {where}: {what}", file=sys.stderr)
    sys.exit(2)


def texture_indices(node, offset):
    """Shifts every texture reference ({"index": i} under a *Texture key) of a material by offset."""
    if isinstance(node, dict):
        for key, value in node.items():
            if key.endswith("Texture") and isinstance(value, dict) and "index" in value:
                value["index"] += offset
            texture_indices(value, offset)
    elif isinstance(node, list):
        for value in node:
            texture_indices(value, offset)


def quad_buffer():
    """A 1 m quad in the XY plane, seen from +Z: positions, normals, tangents, uvs and indices.

    uv (0, 0) is the image's top-left, so v runs down the quad (-Y); the tangent is +X (+u) with
    w = +1, which makes the bitangent +Y, the normal map's up (as scenes/texture_set.cpp's quad).
    """
    h = 0.5
    positions = [(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)]
    normals = [(0, 0, 1)] * 4
    tangents = [(1, 0, 0, 1)] * 4
    uvs = [(0, 1), (1, 1), (1, 0), (0, 0)]
    indices = [0, 1, 2, 0, 2, 3]
    parts = [
        b"".join(struct.pack("<3f", *p) for p in positions),
        b"".join(struct.pack("<3f", *n) for n in normals),
        b"".join(struct.pack("<4f", *t) for t in tangents),
        b"".join(struct.pack("<2f", *u) for u in uvs),
        b"".join(struct.pack("<H", i) for i in indices) + b"\0\0",
    ]
    views, offset = [], 0
    for k, part in enumerate(parts):
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(part) - (2 if k == 4 else 0)}
        view["target"] = 34963 if k == 4 else 34962
        views.append(view)
        offset += len(part)
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-h, -h, 0], "max": [h, h, 0]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC4"},
        {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 4, "componentType": 5123, "count": 6, "type": "SCALAR"},
    ]
    data = b"".join(parts)
    buffer = {"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}
    return buffer, views, accessors


def main(argv):
    if len(argv) < 3:
        fail("usage", "large_scene.py OUT.gltf SET.gltf...")
    out, sets = argv[1], argv[2:]
    out_dir = os.path.dirname(os.path.abspath(out))
    doc = {"asset": {"version": "2.0", "generator": "bench/render/large_scene.py"}, "extensionsUsed": ["KHR_lights_punctual"],
           "images": [], "samplers": [], "textures": [], "materials": [], "meshes": [], "nodes": []}
    buffer, views, accessors = quad_buffer()
    doc["buffers"], doc["bufferViews"], doc["accessors"] = [buffer], views, accessors
    columns = math.ceil(math.sqrt(len(sets)))
    rows = math.ceil(len(sets) / columns)
    pitch = 1.1
    for k, path in enumerate(sets):
        try:
            with open(path) as f:
                s = json.load(f)
        except (OSError, ValueError) as e:
            fail(path, f"cannot read the texture set: {e}")
        if len(s.get("materials", [])) != 1:
            fail(path + ": materials", "a texture set has one material")
        set_dir = os.path.dirname(os.path.abspath(path))
        image0, sampler0, texture0 = len(doc["images"]), len(doc["samplers"]), len(doc["textures"])
        for i, image in enumerate(s.get("images", [])):
            if "uri" not in image or image["uri"].startswith("data:"):
                fail(f"{path}: images[{i}]", "expected an image file beside the glTF")
            doc["images"].append({"uri": os.path.relpath(os.path.join(set_dir, image["uri"]), out_dir)})
        doc["samplers"] += s.get("samplers", [])
        for texture in s.get("textures", []):
            t = dict(texture)
            t["source"] += image0
            if "sampler" in t:
                t["sampler"] += sampler0
            doc["textures"].append(t)
        material = s["materials"][0]
        texture_indices(material, texture0)
        doc["materials"].append(material)
        doc["meshes"].append({"name": material.get("name", f"set {k}"), "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "TANGENT": 2, "TEXCOORD_0": 3}, "indices": 4, "material": k}]})
        column, row = k % columns, k // columns
        x = (column - (columns - 1) / 2) * pitch
        y = ((rows - 1) / 2 - row) * pitch
        doc["nodes"].append({"name": material.get("name", f"set {k}"), "mesh": k, "translation": [x, y, 0]})
    # The camera on +Z (glTF cameras look down their -Z): the grid's height, plus a margin, fills yfov,
    # unless its width over the aspect is the larger.
    aspect, yfov = 16 / 9, 0.6
    half = max(rows * pitch / 2, columns * pitch / 2 / aspect) + 0.2
    distance = half / math.tan(yfov / 2)
    doc["cameras"] = [{"name": "grid", "type": "perspective",
                       "perspective": {"aspectRatio": aspect, "yfov": yfov, "znear": 0.1, "zfar": 10 * distance}}]
    doc["nodes"].append({"name": "camera", "camera": 0, "translation": [0, 0, distance]})
    # A sun from above and behind the camera (light travels along the node's -Z): 40° about X; 2000 lux,
    # 2.9 W/m² as the renderer reads photometric units (÷ 683 lm/W).
    a = math.radians(-40) / 2
    doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"name": "sun", "type": "directional", "intensity": 2000.0}]}}
    doc["nodes"].append({"name": "sun", "rotation": [math.sin(a), 0, 0, math.cos(a)],
                         "extensions": {"KHR_lights_punctual": {"light": 0}}})
    doc["scenes"] = [{"name": "large scene", "nodes": list(range(len(doc["nodes"])))}]
    doc["scene"] = 0
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)


if __name__ == "__main__":
    main(sys.argv)
