#!/usr/bin/env python3
"""Copies a glTF (with the files beside it) into OUT_DIR and adds the camera that svbrdf-render
frames a scene with when the file has none (Camera::framing, render/camera.cpp: 40° vertical field
of view, from +Z and a little above, 1.15 × the bounding sphere), so that Blender's importer and
svbrdf-render see the same camera.

    add_camera.py SCENE.gltf OUT_DIR ASPECT      (prints the new .gltf's path)
"""
import json
import math
import os
import shutil
import sys


def quat_rotate(q, v):
    x, y, z, w = q
    # v + 2w (q×v) + 2 q×(q×v)
    cx, cy, cz = y * v[2] - z * v[1], z * v[0] - x * v[2], x * v[1] - y * v[0]
    ccx, ccy, ccz = y * cz - z * cy, z * cx - x * cz, x * cy - y * cx
    return [v[0] + 2 * (w * cx + ccx), v[1] + 2 * (w * cy + ccy), v[2] + 2 * (w * cz + ccz)]


def node_bounds(doc, index, lo, hi):
    """World bounds of a node's mesh from the POSITION accessors' min/max (exact for the rotations by
    multiples of 90° that sample models use; translation, rotation and scale only, no matrices)."""
    node = doc["nodes"][index]
    if "matrix" in node or "children" in node:
        sys.exit("add_camera.py: nodes with matrices or children are not handled")
    if "mesh" in node:
        t, r, s = node.get("translation", [0, 0, 0]), node.get("rotation", [0, 0, 0, 1]), node.get("scale", [1, 1, 1])
        for prim in doc["meshes"][node["mesh"]]["primitives"]:
            acc = doc["accessors"][prim["attributes"]["POSITION"]]
            for i in range(8):
                corner = [(acc["max"] if i >> k & 1 else acc["min"])[k] * s[k] for k in range(3)]
                p = quat_rotate(r, corner)
                for k in range(3):
                    lo[k], hi[k] = min(lo[k], p[k] + t[k]), max(hi[k], p[k] + t[k])


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def main():
    src, out_dir, aspect = sys.argv[1], sys.argv[2], float(sys.argv[3])
    with open(src) as f:
        doc = json.load(f)
    os.makedirs(out_dir, exist_ok=True)
    for entry in doc.get("buffers", []) + doc.get("images", []):
        if "uri" in entry and not entry["uri"].startswith("data:"):
            shutil.copyfile(os.path.join(os.path.dirname(src), entry["uri"]), os.path.join(out_dir, entry["uri"]))
    scene = doc["scenes"][doc.get("scene", 0)]
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    for index in scene["nodes"]:
        node_bounds(doc, index, lo, hi)
    yfov = math.radians(40.0)
    center = [0.5 * (a + b) for a, b in zip(lo, hi)]
    radius = max(0.5 * math.sqrt(sum((b - a) ** 2 for a, b in zip(lo, hi))), 1e-3)
    dist = 1.15 * radius / math.sin(0.5 * yfov)
    d = normalize([0.0, 0.35, 1.0])
    eye = [c + k * dist for c, k in zip(center, d)]
    # Looking along -d with +Y up: the rotation taking -Z to -d, as a quaternion.
    f = [-c for c in d]
    r = normalize(cross(f, [0, 1, 0]))
    u = cross(r, f)
    m = [[r[0], u[0], d[0]], [r[1], u[1], d[1]], [r[2], u[2], d[2]]]  # columns r, u, d
    w = math.sqrt(max(0.0, 1 + m[0][0] + m[1][1] + m[2][2])) / 2
    q = [(m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w), (m[1][0] - m[0][1]) / (4 * w), w]
    doc.setdefault("cameras", []).append(
        {"name": "framing", "type": "perspective",
         "perspective": {"yfov": yfov, "aspectRatio": aspect, "znear": 0.01}})
    doc["nodes"].append({"name": "framing", "camera": len(doc["cameras"]) - 1, "translation": eye, "rotation": q})
    scene["nodes"].append(len(doc["nodes"]) - 1)
    out = os.path.join(out_dir, os.path.basename(src))
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
    print(out)


main()
