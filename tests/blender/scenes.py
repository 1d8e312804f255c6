# Builds one small test scene in Blender from scratch, exports it to glTF with the exporter's default
# settings and renders the same scene with Cycles, so that svbrdf-render's image of the glTF can be
# compared with Cycles' (tests/blender/README.md).
#
#   blender -b --factory-startup --python-exit-code 1 --python tests/blender/scenes.py -- \
#       --scene NAME --out DIR --res W H --spp N [--seed S] [--variant lambert|lambert-only]
#
# Writes DIR/NAME.gltf (with NAME.bin and the textures beside it) and DIR/NAME.cycles.png. With
# --variant V, only DIR/NAME.cycles-V.png: Cycles' render of the scene with the dielectrics' diffuse
# made Lambertian (diffuse_variant), to measure what Cycles' Principled BSDF adds to the difference.
import argparse
import math
import os
import sys

import bpy
import numpy as np
from mathutils import Vector

SCENES = {}


def scene(fn):
    SCENES[fn.__name__] = fn
    return fn


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="scenes.py")
    p.add_argument("--scene", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--res", nargs=2, type=int, default=[160, 120], metavar=("W", "H"))
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--seed", type=int, default=1, help="Cycles' seed (a second one measures its noise)")
    p.add_argument("--variant", choices=["lambert", "lambert-only"])
    return p.parse_args(argv)


def clear_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras, bpy.data.images):
        for block in list(coll):
            coll.remove(block)


def principled(name, base=(0.5, 0.5, 0.5), metallic=0.0, roughness=0.5, emission=None, strength=1.0):
    """A Principled BSDF material; specular stays at its default 0.5 (F0 = 0.04, glTF's dielectric),
    for which the exporter writes no KHR_materials_specular."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*base, 1.0)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Specular"].default_value = 0.5
    if emission is not None:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return mat


def add_mesh(obj_name, op, material, location=(0, 0, 0), rotation=(0, 0, 0), smooth=False, **kw):
    op(location=location, rotation=rotation, **kw)
    obj = bpy.context.active_object
    obj.name = obj_name
    obj.data.materials.append(material)
    if smooth:
        for poly in obj.data.polygons:
            poly.use_smooth = True
    return obj


def plane(name, material, size, location=(0, 0, 0), rotation=(0, 0, 0)):
    return add_mesh(name, bpy.ops.mesh.primitive_plane_add, material, location, rotation, size=size)


def aim(obj, location, target):
    obj.location = location
    obj.rotation_euler = (Vector(target) - Vector(location)).to_track_quat("-Z", "Y").to_euler()


def camera(location, target, lens=35.0):
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.data.lens = lens
    bpy.context.scene.collection.objects.link(cam)
    aim(cam, location, target)
    bpy.context.scene.camera = cam


def lamp(kind, name, energy, location, target=(0, 0, 0), **settings):
    """A lamp as glTF can carry it: punctual (no radius) or a sun of zero angular size."""
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    if kind == "SUN":
        data.angle = 0.0
    else:
        data.shadow_soft_size = 0.0
    for key, value in settings.items():
        setattr(data, key, value)
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    aim(obj, location, target)
    return obj


@scene
def sun_materials():
    floor = principled("floor_grey", base=(0.5, 0.5, 0.5), roughness=0.6)
    plane("Floor", floor, 10)
    add_mesh("DiffuseSphere", bpy.ops.mesh.primitive_uv_sphere_add,
             principled("diffuse_red", base=(0.7, 0.15, 0.08), roughness=0.5),
             location=(-1.3, 0.3, 0.7), radius=0.7, segments=48, ring_count=24, smooth=True)
    add_mesh("MetalSphere", bpy.ops.mesh.primitive_uv_sphere_add,
             principled("metal_gold", base=(0.95, 0.7, 0.35), metallic=1.0, roughness=0.3),
             location=(0.5, 0.8, 0.7), radius=0.7, segments=48, ring_count=24, smooth=True)
    add_mesh("Box", bpy.ops.mesh.primitive_cube_add, principled("diffuse_light_grey", base=(0.75, 0.75, 0.75)),
             location=(1.9, -0.6, 0.45), rotation=(0, 0, 0.5), size=0.9)
    lamp("SUN", "Sun", 3.0, location=(3, -2, 5), target=(0, 0, 0))
    camera((0.5, -6.5, 3.2), (0.2, 0.3, 0.4))


@scene
def point_spot():
    plane("Floor", principled("floor_grey", base=(0.5, 0.5, 0.5), roughness=0.6), 12)
    plane("Wall", principled("wall_blue_grey", base=(0.45, 0.5, 0.6), roughness=0.7), 12,
          location=(0, 3, 0), rotation=(math.pi / 2, 0, 0))
    add_mesh("Box", bpy.ops.mesh.primitive_cube_add, principled("diffuse_green", base=(0.2, 0.55, 0.25)),
             location=(-1.2, 0.8, 0.4), rotation=(0, 0, 0.3), size=0.8)
    lamp("POINT", "Point", 150.0, location=(-1.8, 0.0, 2.0))
    # A hard-edged cone (little blend) so that the edge is visible on the floor.
    lamp("SPOT", "Spot", 400.0, location=(1.6, 0.6, 3.0), target=(1.6, 0.6, 0.0),
         spot_size=math.radians(40.0), spot_blend=0.1)
    camera((0.0, -6.0, 3.5), (0.0, 0.8, 0.3))


@scene
def emissive_panel():
    wall = principled("wall_white", base=(0.6, 0.6, 0.6), roughness=0.8)
    plane("Floor", wall, 6)
    plane("BackWall", wall, 6, location=(0, 2, 0), rotation=(math.pi / 2, 0, 0))
    plane("SideWall", principled("wall_red", base=(0.6, 0.2, 0.15), roughness=0.8), 6,
          location=(-2, 0, 0), rotation=(0, math.pi / 2, 0))
    add_mesh("Box", bpy.ops.mesh.primitive_cube_add, principled("box_grey", base=(0.5, 0.5, 0.5)),
             location=(0.3, 0.5, 0.35), rotation=(0, 0, 0.4), size=0.7)
    # The only light: a 1 m panel facing down (a plane's normal is +Z; flipped by the rotation).
    plane("Panel", principled("panel", base=(0.0, 0.0, 0.0), emission=(1.0, 0.9, 0.8), strength=8.0), 1.0,
          location=(-0.6, 0.6, 2.0), rotation=(math.pi, 0, 0))
    camera((1.2, -4.5, 1.4), (-0.3, 0.8, 0.7))


def bump_maps(n=256, bumps=6, depth=0.6):
    """A painted tile pattern and a tangent-space normal map of round bumps, as RGBA float rows from
    the bottom (Blender's pixel order)."""
    t = (np.arange(n) + 0.5) / n
    u, v = np.meshgrid(t, t)  # rows are v
    cu, cv = (u * bumps) % 1.0 - 0.5, (v * bumps) % 1.0 - 0.5
    r2 = cu * cu + cv * cv
    inside = r2 < 0.16
    # Height h = depth * (0.16 - r²) inside each bump: dh/du = -2 depth cu · bumps (per unit of uv).
    dhdu = np.where(inside, -2.0 * depth * cu * bumps, 0.0)
    dhdv = np.where(inside, -2.0 * depth * cv * bumps, 0.0)
    normal = np.stack([-dhdu, -dhdv, np.ones_like(u)], axis=-1)
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    normal_rgba = np.concatenate([0.5 * normal + 0.5, np.ones((n, n, 1))], axis=-1)
    checker = ((np.floor(u * bumps) + np.floor(v * bumps)) % 2)[..., None]
    color = checker * np.array([0.85, 0.75, 0.45]) + (1 - checker) * np.array([0.35, 0.55, 0.75])
    color_rgba = np.concatenate([color, np.ones((n, n, 1))], axis=-1)
    return color_rgba, normal_rgba


def image(name, rgba, colorspace):
    img = bpy.data.images.new(name, rgba.shape[1], rgba.shape[0], alpha=False)
    img.colorspace_settings.name = colorspace
    img.pixels.foreach_set(rgba.astype(np.float32).ravel())
    img.pack()
    return img


@scene
def normal_mapped():
    color_rgba, normal_rgba = bump_maps()
    mat = principled("bumpy_tiles", roughness=0.5)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    base = nodes.new("ShaderNodeTexImage")
    base.image = image("bumpy_tiles_base_color", color_rgba, "sRGB")
    links.new(base.outputs["Color"], bsdf.inputs["Base Color"])
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = image("bumpy_tiles_normal", normal_rgba, "Non-Color")
    normal_map = nodes.new("ShaderNodeNormalMap")
    normal_map.space = "TANGENT"
    links.new(tex.outputs["Color"], normal_map.inputs["Color"])
    links.new(normal_map.outputs["Normal"], bsdf.inputs["Normal"])
    plane("Tiles", mat, 4)
    lamp("SUN", "Sun", 4.0, location=(-4, 1, 1.5), target=(0, 0, 0))
    camera((0.0, -4.0, 3.0), (0.0, 0.1, 0.0))


def diffuse_variant(variant):
    """Each dielectric Principled BSDF's Disney diffuse becomes a Lambertian Diffuse BSDF (roughness
    0). lambert: added to the same Principled with a black base color (its specular layer alone), as
    Cycles 3.4 layers them (the diffuse not dimmed by the specular's Fresnel). lambert-only: the
    Diffuse BSDF alone, no specular layer (svbrdf-render's counterpart: KHR_materials_specular with
    specularFactor 0)."""
    for mat in bpy.data.materials:
        if not mat.use_nodes or "Principled BSDF" not in mat.node_tree.nodes:
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        bsdf, output = nodes["Principled BSDF"], nodes["Material Output"]
        emits = bsdf.inputs["Emission Strength"].default_value * max(bsdf.inputs["Emission"].default_value[:3])
        if bsdf.inputs["Metallic"].default_value >= 1.0 or emits > 0.0:
            continue  # metals have no diffuse; the emitter's base color is black
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Roughness"].default_value = 0.0
        base_in, normal_in = bsdf.inputs["Base Color"], bsdf.inputs["Normal"]
        if base_in.is_linked:
            links.new(base_in.links[0].from_socket, diffuse.inputs["Color"])
            links.remove(base_in.links[0])
        else:
            diffuse.inputs["Color"].default_value = base_in.default_value
        base_in.default_value = (0.0, 0.0, 0.0, 1.0)
        if normal_in.is_linked:
            links.new(normal_in.links[0].from_socket, diffuse.inputs["Normal"])
        surface = diffuse.outputs["BSDF"]
        if variant == "lambert":
            add = nodes.new("ShaderNodeAddShader")
            links.new(surface, add.inputs[0])
            links.new(bsdf.outputs["BSDF"], add.inputs[1])
            surface = add.outputs["Shader"]
        links.new(surface, output.inputs["Surface"])


def setup_cycles(res, spp, seed):
    s = bpy.context.scene
    s.render.engine = "CYCLES"
    s.cycles.device = "CPU"
    s.cycles.samples = spp
    s.cycles.use_denoising = False
    s.cycles.use_adaptive_sampling = False
    s.cycles.seed = seed
    # Light paths stay at Cycles' defaults: max_bounces 12 with diffuse 4, glossy 4, transmission 12,
    # transparent 8; indirect samples clamped at 10; "filter glossy" 1.0; light threshold 0.01.
    # svbrdf-render follows paths up to 16 scattering events and clamps nothing.
    # A one-pixel box, as svbrdf-render samples its pixels (Cycles defaults to a 1.5 px Blackman-Harris).
    s.cycles.pixel_filter_type = "BOX"
    s.cycles.filter_width = 1.0
    s.render.threads_mode = "FIXED"
    s.render.threads = 2
    s.render.resolution_x, s.render.resolution_y = res
    s.render.resolution_percentage = 100
    s.render.film_transparent = False
    s.render.dither_intensity = 0.0
    s.display_settings.display_device = "sRGB"
    s.view_settings.view_transform = "Standard"
    s.view_settings.look = "None"
    s.view_settings.exposure = 0.0
    s.view_settings.gamma = 1.0
    s.render.image_settings.file_format = "PNG"
    s.render.image_settings.color_mode = "RGB"
    s.render.image_settings.color_depth = "8"
    # glTF carries no world: a black background in Cycles, and run-scene gives svbrdf-render a black
    # environment too (--env 0,0,0).
    world = bpy.data.worlds.new("Black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    s.world = world


def main():
    args = parse_args()
    if args.scene not in SCENES:
        sys.exit(f"scenes.py: unknown scene {args.scene!r}; known: {', '.join(sorted(SCENES))}")
    os.makedirs(args.out, exist_ok=True)
    clear_scene()
    setup_cycles(args.res, args.spp, args.seed)
    SCENES[args.scene]()
    if args.variant is None:
        # The exporter's defaults but for the separate-files format and including the camera and the
        # lamps, which Blender 3.4 leaves out unless asked. Lights go out in its default "Standard"
        # lighting mode: sun W/m² → lux, point and spot W → W/(4π) sr⁻¹ → candela, at 683 lm/W.
        bpy.ops.export_scene.gltf(filepath=os.path.join(args.out, args.scene + ".gltf"),
                                  export_format="GLTF_SEPARATE", export_cameras=True, export_lights=True)
        png = os.path.join(args.out, args.scene + ".cycles.png")
    else:
        diffuse_variant(args.variant)
        png = os.path.join(args.out, f"{args.scene}.cycles-{args.variant}.png")
    bpy.context.scene.render.filepath = png
    bpy.ops.render.render(write_still=True)


main()
