# Cycles' side of bench/cycles/run: one render with the Cycles settings of tests/blender/scenes.py
# (CPU, no denoising, no adaptive sampling, a 1-px box filter, Standard view, 2 threads), whose
# functions it reuses (the file is run without its main()).
#
#   blender -b --factory-startup --python-exit-code 1 --python bench/cycles/cycles_bench.py -- \
#       gltf  --file SCENE.gltf --world R G B --res W H --spp N --seed S --out FILE.png|FILE.exr
#   blender ... -- scene --name emissive_panel --res W H --spp N --seed S --out FILE.png|FILE.exr
#
# gltf: imports a glTF with Blender's importer (its first camera; a uniform world of radiance R,G,B,
# as svbrdf-render's --env R,G,B). scene: builds one of scenes.py's scenes. An .exr is written as
# 32-bit float linear RGB. Prints "cycles_bench: started", "cycles_bench: loaded" (the scene is in
# Blender) and "cycles_bench: rendered", flushed, for run's timestamps; Cycles prints its own
# status lines ("Synchronizing object", "Updating Images", "Sample 0/64", ...).
import argparse
import os
import sys

import bpy

print("cycles_bench: started", flush=True)

SCENES_PY = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "blender", "scenes.py")


def load_scenes_py():
    with open(SCENES_PY) as f:
        src = f.read()
    head, sep, tail = src.rpartition("\nmain()")
    if not sep or tail.strip():
        sys.exit("cycles_bench.py: tests/blender/scenes.py no longer ends with main()")
    ns = {"__name__": "scenes", "__file__": SCENES_PY}
    exec(compile(head, SCENES_PY, "exec"), ns)
    return ns


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="cycles_bench.py")
    p.add_argument("mode", choices=["gltf", "scene"])
    p.add_argument("--file")
    p.add_argument("--name")
    p.add_argument("--world", nargs=3, type=float, default=[0.0, 0.0, 0.0])
    p.add_argument("--res", nargs=2, type=int, required=True)
    p.add_argument("--spp", type=int, required=True)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--out", required=True)
    return p.parse_args(argv)


def main():
    args = parse_args()
    scenes = load_scenes_py()
    scenes["clear_scene"]()
    scenes["setup_cycles"](args.res, args.spp, args.seed)
    s = bpy.context.scene
    if args.mode == "gltf":
        # Blender 3.4's importer asks for np.bool (gltf2_blender_mesh.py, set_poly_smoothing), an
        # alias that NumPy 1.24 (Debian 12's) removed; the builtin is what it meant.
        import numpy
        if not hasattr(numpy, "bool"):
            numpy.bool = bool
        bpy.ops.import_scene.gltf(filepath=args.file)
        cams = [o for o in bpy.context.scene.objects if o.type == "CAMERA"]
        if not cams:
            sys.exit(f"cycles_bench.py: {args.file} has no camera")
        s.camera = cams[0]
        bg = s.world.node_tree.nodes["Background"]
        peak = max(args.world)
        bg.inputs["Color"].default_value = (*[c / peak if peak > 0 else 0.0 for c in args.world], 1.0)
        bg.inputs["Strength"].default_value = peak
    else:
        scenes["SCENES"][args.name]()
    if args.out.endswith(".exr"):
        st = s.render.image_settings
        st.file_format = "OPEN_EXR"
        st.color_mode = "RGB"
        st.color_depth = "32"
        st.exr_codec = "ZIP"
    print("cycles_bench: loaded", flush=True)
    s.render.filepath = os.path.abspath(args.out)
    s.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    print("cycles_bench: rendered", flush=True)


main()
