# Relative mean squared error of linear EXRs, read with Blender's image loader (Debian's Python has
# no OpenEXR module; Blender's has NumPy):
#
#   blender -b --factory-startup --python-exit-code 1 --python bench/cycles/relmse.py -- \
#       NAME=IMAGE.exr:REFERENCE.exr ...
#
# prints "relmse NAME VALUE" for each pair, where VALUE = 1/(3N) Σ_pixels Σ_{c∈RGB}
# (X_c − R_c)² / (R_c² + 0.01) over the N pixels, X the image's and R the reference's linear
# radiance (the 0.01 keeps black pixels from dividing by zero; alpha is ignored).
import sys

import bpy
import numpy as np


def load(path):
    img = bpy.data.images.load(path, check_existing=False)
    w, h = img.size
    px = np.empty(w * h * 4, dtype=np.float32)
    img.pixels.foreach_get(px)
    bpy.data.images.remove(img)
    return (w, h), px.reshape(h, w, 4)[..., :3].astype(np.float64)


for arg in sys.argv[sys.argv.index("--") + 1:]:
    name, pair = arg.split("=", 1)
    x_path, r_path = pair.split(":", 1)
    (xs, x), (rs, r) = load(x_path), load(r_path)
    if xs != rs:
        sys.exit(f"relmse.py: {x_path} is {xs}, {r_path} is {rs}")
    print(f"relmse {name} {np.mean((x - r) ** 2 / (r * r + 0.01)):.6g}", flush=True)
