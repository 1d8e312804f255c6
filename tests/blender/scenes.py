# Builds one small test scene in Blender from scratch, exports it to glTF with the exporter's default
# settings and renders the same scene with Cycles, so that svbrdf-render's image of the glTF can be
# compared with Cycles' (tests/blender/README.md).
#
#   blender -b --factory-startup --python-exit-code 1 --python tests/blender/scenes.py -- \
#       --scene NAME --out DIR --res W H --spp N [--seed S] [--variant lambert|lambert-only|principled-coat]
#
# Writes DIR/NAME.gltf (with NAME.bin and the textures beside it) and DIR/NAME.cycles.png, in which
# Cycles renders each clearcoat as KHR_materials_clearcoat defines it (gltf_clearcoat). With
# --variant V, only DIR/NAME.cycles-V.png: Cycles' render of the scene with the dielectrics' diffuse
# made Lambertian (diffuse_variant), to measure what Cycles' Principled BSDF adds to the difference,
# or with Blender's own Principled clearcoat (principled-coat), to measure how far it is from glTF's.
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
    p.add_argument("--variant", choices=["lambert", "lambert-only", "principled-coat"])
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


def checker(n=128, cells=8, light=(1.0, 1.0, 1.0), dark=(0.12, 0.12, 0.12)):
    """A checkerboard of `cells`² squares as RGBA float rows from the bottom."""
    t = (np.arange(n) + 0.5) / n
    u, v = np.meshgrid(t, t)
    checker = ((np.floor(u * cells) + np.floor(v * cells)) % 2)[..., None]
    rgb = checker * np.array(light) + (1 - checker) * np.array(dark)
    return np.concatenate([rgb, np.ones((n, n, 1))], axis=-1)


def clearcoat(mat, weight, roughness):
    """Gives a Principled BSDF material a clearcoat (exported as KHR_materials_clearcoat)."""
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Clearcoat"].default_value = weight
    bsdf.inputs["Clearcoat Roughness"].default_value = roughness
    return mat


@scene
def clearcoat_paint():
    # Car paint in a studio of soft boxes: a dark red dielectric and a blue metal, each under a
    # smooth coat. Wide panels on the ceiling and on the wall behind the camera cover much of what
    # the spheres reflect, so that the coat's sharp image of them (which the rough bases blur into
    # a glow) fills much of the frame; wide, so that few pixels straddle a panel's edge. A dim floor.
    plane("Floor", principled("floor_dark", base=(0.02, 0.02, 0.02), roughness=0.7), 14)
    add_mesh("PaintSphere", bpy.ops.mesh.primitive_uv_sphere_add,
             clearcoat(principled("paint_red", base=(0.15, 0.01, 0.01), roughness=0.7), 1.0, 0.05),
             location=(-0.85, 0.0, 0.75), radius=0.75, segments=64, ring_count=32, smooth=True)
    add_mesh("MetalSphere", bpy.ops.mesh.primitive_uv_sphere_add,
             clearcoat(principled("paint_blue_metal", base=(0.06, 0.1, 0.3), metallic=1.0, roughness=0.6),
                       1.0, 0.1),
             location=(0.85, 0.0, 0.75), radius=0.75, segments=64, ring_count=32, smooth=True)
    # 8 m long panels, 1.4 m wide with 1.4 m between them: on the ceiling facing down, and behind the
    # camera facing it.
    box = principled("softbox", base=(0.0, 0.0, 0.0), emission=(1.0, 1.0, 1.0), strength=6.0)
    for i, y in enumerate((-4.2, -1.4, 1.4)):
        obj = plane(f"CeilingPanel{i}", box, 1.0, location=(0.0, y, 3.0), rotation=(math.pi, 0, 0))
        obj.scale = (8.0, 1.4, 1.0)
    obj = plane("WallPanel", box, 1.0, location=(0.0, -5.5, 1.4), rotation=(-math.pi / 2, 0, 0))
    obj.scale = (8.0, 1.4, 1.0)
    camera((0.0, -3.4, 1.25), (0.0, 0.0, 0.75), lens=40.0)


def gltf_material_output(mat, thickness):
    """The exporter's "glTF Material Output" node group, carrying KHR_materials_volume's
    thicknessFactor: Blender 3.4's exporter writes the volume extension only where a material has
    it with Thickness > 0. Unlinked, it changes nothing Cycles renders."""
    group = bpy.data.node_groups.get("glTF Material Output")
    if group is None:
        group = bpy.data.node_groups.new("glTF Material Output", "ShaderNodeTree")
        group.inputs.new("NodeSocketFloat", "Thickness")
    node = mat.node_tree.nodes.new("ShaderNodeGroup")
    node.node_tree = group
    node.inputs["Thickness"].default_value = thickness


def glass(name, absorption):
    """Clear glass (transmission 1, IOR 1.5, roughness 0) filled with a Volume Absorption of
    coefficient `absorption` (1/m per channel), written as density ρ = 50 and color C = 1 − σ/ρ so
    that Cycles' σ = ρ·(1 − C) and glTF's σ = −ln(C)/(1/ρ) agree within 1.2 % (README)."""
    mat = principled(name, base=(1.0, 1.0, 1.0), roughness=0.0)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Transmission"].default_value = 1.0
    bsdf.inputs["IOR"].default_value = 1.5
    density = 50.0
    volume = nodes.new("ShaderNodeVolumeAbsorption")
    volume.inputs["Color"].default_value = (*[1.0 - s / density for s in absorption], 1.0)
    volume.inputs["Density"].default_value = density
    links.new(volume.outputs["Volume"], nodes["Material Output"].inputs["Volume"])
    gltf_material_output(mat, 1.0)
    return mat


@scene
def glass_volume():
    # A glass ball and a glass block in front of a lit checker wall: refraction shows in the bent
    # squares, absorption in the tint that deepens with the path length through each.
    wall = principled("checker_wall", base=(0.0, 0.0, 0.0), roughness=1.0)
    nodes, links = wall.node_tree.nodes, wall.node_tree.links
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = image("checker_wall_emission", checker(), "sRGB")
    links.new(tex.outputs["Color"], nodes["Principled BSDF"].inputs["Emission"])
    nodes["Principled BSDF"].inputs["Emission Strength"].default_value = 1.0
    plane("Wall", wall, 6.0, location=(0, 2.0, 0.8), rotation=(math.pi / 2, 0, 0))
    add_mesh("GlassBall", bpy.ops.mesh.primitive_uv_sphere_add, glass("glass_teal", (1.2, 0.35, 0.12)),
             location=(-0.8, 0.0, 0.8), radius=0.65, segments=64, ring_count=32, smooth=True)
    add_mesh("GlassBlock", bpy.ops.mesh.primitive_cube_add, glass("glass_amber", (0.1, 0.45, 1.2)),
             location=(0.85, 0.1, 0.8), rotation=(0.3, 0.2, 0.5), size=0.9)
    camera((0.0, -4.0, 1.1), (0.0, 0.5, 0.8), lens=40.0)


def gltf_clearcoat(mat):
    """Cycles' counterpart of KHR_materials_clearcoat for a Principled BSDF with a clearcoat: the
    same Principled without its coat, mixed with a GGX Glossy BSDF of the coat's roughness (α = r²
    in both) by clearcoat·Fc, Fc = 0.04 + 0.96·(1 − |N·V|)^5 — the extension's fresnel_coat, where
    Cycles 3.4's own Principled clearcoat is another model (README)."""
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf, output = nodes["Principled BSDF"], nodes["Material Output"]
    weight = bsdf.inputs["Clearcoat"].default_value
    roughness = bsdf.inputs["Clearcoat Roughness"].default_value
    bsdf.inputs["Clearcoat"].default_value = 0.0
    facing = nodes.new("ShaderNodeLayerWeight")  # Facing at blend 0.5: 1 − |N·V|
    facing.inputs["Blend"].default_value = 0.5
    power = nodes.new("ShaderNodeMath")
    power.operation = "POWER"
    power.inputs[1].default_value = 5.0
    schlick = nodes.new("ShaderNodeMath")
    schlick.operation = "MULTIPLY_ADD"
    schlick.inputs[1].default_value = 0.96
    schlick.inputs[2].default_value = 0.04
    blend = nodes.new("ShaderNodeMath")
    blend.operation = "MULTIPLY"
    blend.inputs[1].default_value = weight
    coat = nodes.new("ShaderNodeBsdfGlossy")
    coat.distribution = "GGX"
    coat.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    coat.inputs["Roughness"].default_value = roughness
    mix = nodes.new("ShaderNodeMixShader")
    links.new(facing.outputs["Facing"], power.inputs[0])
    links.new(power.outputs[0], schlick.inputs[0])
    links.new(schlick.outputs[0], blend.inputs[0])
    links.new(blend.outputs[0], mix.inputs["Fac"])
    links.new(bsdf.outputs["BSDF"], mix.inputs[1])
    links.new(coat.outputs["BSDF"], mix.inputs[2])
    links.new(mix.outputs["Shader"], output.inputs["Surface"])


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
        png = os.path.join(args.out, f"{args.scene}.cycles-{args.variant}.png")
    # Cycles renders each clearcoat as KHR_materials_clearcoat defines it, unless asked for Blender's
    # own Principled clearcoat (principled-coat), to measure how far that one is from it.
    if args.variant != "principled-coat":
        for mat in bpy.data.materials:
            if (mat.use_nodes and "Principled BSDF" in mat.node_tree.nodes and
                    mat.node_tree.nodes["Principled BSDF"].inputs["Clearcoat"].default_value > 0.0):
                gltf_clearcoat(mat)
    if args.variant in ("lambert", "lambert-only"):
        diffuse_variant(args.variant)
    bpy.context.scene.render.filepath = png
    bpy.ops.render.render(write_still=True)


main()
