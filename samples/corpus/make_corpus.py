"""Build and render the ssrcl validation corpus (issue 11): Cycles scenes for measuring SSR accuracy.

    blender -b --factory-startup --python-exit-code 1 --python samples/corpus/make_corpus.py \
        -- <outdir> [scene names...]

No names = every scene. For each scene: build it from scratch, render it with Cycles (CPU) and
write <outdir>/<name>.exr (multilayer, view layer "ViewLayer") and <outdir>/<name>.camera.json;
<outdir>/corpus.json (the manifest of every scene, rendered or not) is rewritten on each run.

Fairness rules (see README.md and /work/shared/docs/cycles-references.md):
- Reflectors: Principled BSDF, single-scatter GGX, metallic 1, base colour white (F0 = 1: no
  Fresnel, no tint), every other lobe 0; one socket drives both the BSDF roughness and the
  "roughness" value AOV. Main reflector pass_index 1; glossy props that are reflectors
  themselves (mirror_panels, metal_props) pass_index 2.
- Everything else is view-independent: Lambertian (Diffuse BSDF) or pure emission, AOV 1.0,
  pass_index 0. Lamps are invisible to glossy rays, the world is black, or (exterior_plaza) a
  sky that is invisible to glossy rays.

Environment overrides (previews / noise estimates only; the committed files use none):
SSRCL_CORPUS_SAMPLES (samples for every scene), SSRCL_CORPUS_SEED (Cycles seed, default 0),
SSRCL_CORPUS_PNG=1 (also write <name>.png of Combined), SSRCL_CORPUS_COVERAGE=1 (print the
fraction of pixels per IndexOB value, read back from the EXR; slow pure-Python decode).
"""
import json
import math
import os
import sys
import time

import bpy
from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "blender"))
import export_camera  # noqa: E402,F401  (used through scene_common.render_and_write)
from make_glossy_scene import (configure_glossy_render, make_diffuse_material,  # noqa: E402
                               make_emission_material)
from scene_common import (add_aov_output, build_world, render_and_write,  # noqa: E402
                          reset_scene)
from script_args import outdir_and_names, script_args  # noqa: E402

LAYER = "ViewLayer"
DIFFUSE_AOV = 1.0  # AOV roughness of every non-reflector ("no GGX lobe")
REFLECTOR_INDEX = 1  # pass_index of the main reflector
PROP_REFLECTOR_INDEX = 2  # pass_index of glossy props that are reflectors themselves


# ----------------------------------------------------------------------------------------------
# Materials
# ----------------------------------------------------------------------------------------------

class Shader:
    """Small node-building helper for one material's node tree."""

    def __init__(self, mat):
        self.mat = mat
        self.nodes = mat.node_tree.nodes
        self.links = mat.node_tree.links
        self._position = None

    def link(self, src, dst):
        self.links.new(src, dst)

    def value(self, v):
        node = self.nodes.new("ShaderNodeValue")
        node.outputs[0].default_value = v
        return node.outputs[0]

    def position(self):
        """World-space shading position (textures in scene units, independent of object size)."""
        if self._position is None:
            self._position = self.nodes.new("ShaderNodeNewGeometry").outputs["Position"]
        return self._position

    def math(self, op, a, b=0.0):
        node = self.nodes.new("ShaderNodeMath")
        node.operation = op
        for i, v in enumerate((a, b)):
            if isinstance(v, (int, float)):
                node.inputs[i].default_value = float(v)
            else:
                self.link(v, node.inputs[i])
        return node.outputs[0]

    def noise(self, scale, detail=2.0, roughness=0.5, distortion=0.0):
        node = self.nodes.new("ShaderNodeTexNoise")
        node.noise_dimensions = '3D'
        node.inputs["Scale"].default_value = scale
        node.inputs["Detail"].default_value = detail
        node.inputs["Roughness"].default_value = roughness
        node.inputs["Distortion"].default_value = distortion
        self.link(self.position(), node.inputs["Vector"])
        return node.outputs["Fac"]

    def map_range(self, sock, from_min, from_max, to_min, to_max):
        node = self.nodes.new("ShaderNodeMapRange")
        node.clamp = True
        self.link(sock, node.inputs["Value"])
        node.inputs["From Min"].default_value = from_min
        node.inputs["From Max"].default_value = from_max
        node.inputs["To Min"].default_value = to_min
        node.inputs["To Max"].default_value = to_max
        return node.outputs["Result"]

    def checker(self, scale, color1=(1, 1, 1), color2=(0, 0, 0)):
        """Checker on world position; squares of 1/scale scene units. Returns (color, fac)."""
        node = self.nodes.new("ShaderNodeTexChecker")
        node.inputs["Scale"].default_value = scale
        node.inputs["Color1"].default_value = (*color1, 1.0)
        node.inputs["Color2"].default_value = (*color2, 1.0)
        self.link(self.position(), node.inputs["Vector"])
        return node.outputs["Color"], node.outputs["Fac"]

    def brick(self, scale, color1, color2, mortar, axis="x"):
        """Brick rows along world Z (the texture is 2D): on a wall that runs along world
        `axis` ("x": the wall faces +-Y, "y": it faces +-X)."""
        sep = self.nodes.new("ShaderNodeSeparateXYZ")
        self.link(self.position(), sep.inputs[0])
        comb = self.nodes.new("ShaderNodeCombineXYZ")
        self.link(sep.outputs[axis.upper()], comb.inputs["X"])
        self.link(sep.outputs["Z"], comb.inputs["Y"])
        node = self.nodes.new("ShaderNodeTexBrick")
        node.inputs["Scale"].default_value = scale
        node.inputs["Color1"].default_value = (*color1, 1.0)
        node.inputs["Color2"].default_value = (*color2, 1.0)
        node.inputs["Mortar"].default_value = (*mortar, 1.0)
        node.inputs["Mortar Size"].default_value = 0.03
        self.link(comb.outputs[0], node.inputs["Vector"])
        return node.outputs["Color"]


def new_material(name):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    return mat, Shader(mat)


def metal(name, roughness, bump=None):
    """F0 = 1 single-scatter GGX reflector. `roughness` is a number or a function
    Shader -> socket; the same socket feeds the BSDF and the AOV. `bump` is an optional function
    Shader -> normal socket (e.g. a Bump node) for the BSDF's Normal."""
    mat, sh = new_material(name)
    bsdf = sh.nodes["Principled BSDF"]
    bsdf.distribution = 'GGX'  # single scatter, not 'MULTI_GGX'
    bsdf.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bsdf.inputs["Metallic"].default_value = 1.0
    for key in ("Specular", "Specular Tint", "Anisotropic", "Sheen", "Sheen Tint", "Clearcoat",
                "Subsurface", "Transmission"):
        bsdf.inputs[key].default_value = 0.0
    sock = roughness(sh) if callable(roughness) else sh.value(float(roughness))
    sh.link(sock, bsdf.inputs["Roughness"])
    add_aov_output(mat, sock)
    if bump is not None:
        sh.link(bump(sh), bsdf.inputs["Normal"])
    return mat


def diffuse(name, color):
    """Plain Lambertian (make_glossy_scene's Diffuse BSDF, AOV 1.0)."""
    return make_diffuse_material(name, color)


def emission(name, color, strength):
    return make_emission_material(name, color, strength)


def diffuse_tex(name, color_fn):
    """Lambertian whose colour comes from color_fn(Shader) -> colour socket (brick, checker)."""
    mat, sh = new_material(name)
    sh.nodes.remove(sh.nodes["Principled BSDF"])
    bsdf = sh.nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Roughness"].default_value = 0.0  # Lambert, not Oren-Nayar
    sh.link(color_fn(sh), bsdf.inputs["Color"])
    sh.link(bsdf.outputs["BSDF"], sh.nodes["Material Output"].inputs["Surface"])
    add_aov_output(mat, sh.value(DIFFUSE_AOV))
    return mat


def brick_mat(name, c1, c2, mortar=(0.55, 0.55, 0.5), scale=2.0, axis="x"):
    return diffuse_tex(name, lambda sh: sh.brick(scale, c1, c2, mortar, axis))


def checker_mat(name, c1, c2, scale=2.0):
    return diffuse_tex(name, lambda sh: sh.checker(scale, c1, c2)[0])


# ----------------------------------------------------------------------------------------------
# Objects, lights, camera
# ----------------------------------------------------------------------------------------------

def _finish(obj, mat, name, pass_index):
    obj.data.materials.append(mat)
    if name:
        obj.name = name
    obj.pass_index = pass_index
    return obj


def box(loc, dims, mat, rot=(0.0, 0.0, 0.0), name=None, pass_index=0):
    """Box centred at loc with full edge lengths dims; rot in degrees (XYZ Euler)."""
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=loc,
                                    rotation=tuple(math.radians(a) for a in rot))
    obj = bpy.context.active_object
    obj.scale = dims
    return _finish(obj, mat, name, pass_index)


def plane(loc, size_xy, mat, rot=(0.0, 0.0, 0.0), name=None, pass_index=0):
    """Plane centred at loc, size_xy = (x, y) extents before rotation (degrees)."""
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=loc,
                                     rotation=tuple(math.radians(a) for a in rot))
    obj = bpy.context.active_object
    obj.scale = (size_xy[0], size_xy[1], 1.0)
    return _finish(obj, mat, name, pass_index)


def floor(size, mat, z=0.0, name="Floor"):
    return plane((0.0, 0.0, z), (size, size), mat, name=name, pass_index=REFLECTOR_INDEX)


def sphere(loc, radius, mat, name=None, pass_index=0):
    bpy.ops.mesh.primitive_uv_sphere_add(radius=radius, location=loc, segments=48, ring_count=24)
    bpy.ops.object.shade_smooth()
    return _finish(bpy.context.active_object, mat, name, pass_index)


def cylinder(loc, radius, height, mat, rot=(0.0, 0.0, 0.0), name=None, pass_index=0,
             vertices=32):
    bpy.ops.mesh.primitive_cylinder_add(radius=radius, depth=height, location=loc,
                                        vertices=vertices,
                                        rotation=tuple(math.radians(a) for a in rot))
    bpy.ops.object.shade_smooth()
    return _finish(bpy.context.active_object, mat, name, pass_index)


def torus(loc, major, minor, mat, rot=(0.0, 0.0, 0.0), name=None, pass_index=0):
    bpy.ops.mesh.primitive_torus_add(location=loc, major_radius=major, minor_radius=minor,
                                     major_segments=64, minor_segments=24,
                                     rotation=tuple(math.radians(a) for a in rot))
    bpy.ops.object.shade_smooth()
    return _finish(bpy.context.active_object, mat, name, pass_index)


def _add_light(scene, data, loc, rot):
    obj = bpy.data.objects.new(data.name, data)
    obj.location = loc
    obj.rotation_euler = tuple(math.radians(a) for a in rot)
    obj.visible_glossy = False  # no highlight that is in no G-buffer
    scene.collection.objects.link(obj)
    return obj


def sun(scene, energy, elevation, azimuth, angle=2.0):
    """Sun coming from `elevation` degrees above the horizon, `azimuth` degrees (0 = from -Y,
    i.e. from behind a camera looking down +Y; positive = from the right)."""
    data = bpy.data.lights.new("Sun", type='SUN')
    data.energy = energy
    data.angle = math.radians(angle)
    # A sun shines down its local -Z: tilt it back by (90 - elevation) about X, then turn.
    return _add_light(scene, data, (0.0, 0.0, 10.0), (90.0 - elevation, 0.0, azimuth))


def area_light(scene, loc, size, energy, rot=(0.0, 0.0, 0.0)):
    data = bpy.data.lights.new("Area", type='AREA')
    data.energy = energy
    data.size = size
    return _add_light(scene, data, loc, rot)


def camera(scene, loc, target, lens, clip_start=0.1, clip_end=1000.0):
    data = bpy.data.cameras.new("Camera")
    data.lens = lens
    data.sensor_fit = 'AUTO'  # 36 mm across the (wider) image width
    data.clip_start = clip_start
    data.clip_end = clip_end
    obj = bpy.data.objects.new("Camera", data)
    obj.location = loc
    obj.rotation_euler = (Vector(target) - Vector(loc)).to_track_quat('-Z', 'Y').to_euler()
    scene.collection.objects.link(obj)
    scene.camera = obj
    bpy.context.view_layer.update()
    return obj


def black_world(scene):
    world = bpy.data.worlds.new("Black")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    bg.inputs["Strength"].default_value = 0.0
    scene.world = world


def set_units(scene, units):
    us = scene.unit_settings
    us.system = 'METRIC'
    us.scale_length = {"m": 1.0, "cm": 0.01, "mm": 0.001}[units]
    us.length_unit = {"m": 'METERS', "cm": 'CENTIMETERS', "mm": 'MILLIMETERS'}[units]


# Some saturated Lambertian colours.
RED, GREEN, BLUE = (0.8, 0.08, 0.05), (0.08, 0.65, 0.12), (0.06, 0.15, 0.8)
YELLOW, ORANGE, MAGENTA = (0.85, 0.7, 0.05), (0.9, 0.35, 0.04), (0.75, 0.06, 0.6)
CYAN, WHITE, GREY = (0.05, 0.6, 0.7), (0.8, 0.8, 0.8), (0.4, 0.4, 0.4)


# ----------------------------------------------------------------------------------------------
# Scenes (one idea each). Each builder gets an emptied scene and adds world, camera, objects.
# ----------------------------------------------------------------------------------------------

def build_interior_room(scene):
    black_world(scene)
    plane((0.0, 0.0, 0.0), (6.0, 8.0), metal("RoomFloor", 0.1), name="Floor",
          pass_index=REFLECTOR_INDEX)
    brick = brick_mat("Brick", (0.55, 0.18, 0.1), (0.35, 0.12, 0.08), axis="y")
    box((-3.05, 0.0, 1.5), (0.1, 8.0, 3.0), brick, name="LeftWall")
    box((0.0, 4.05, 1.5), (6.2, 0.1, 3.0), checker_mat("Tiles", (0.85, 0.8, 0.65),
                                                       (0.15, 0.25, 0.6), 2.5), name="BackWall")
    box((3.05, 0.0, 1.5), (0.1, 8.0, 3.0), diffuse("Green", (0.25, 0.5, 0.3)), name="RightWall")
    box((0.0, -4.05, 1.5), (6.2, 0.1, 3.0), diffuse("Grey", GREY), name="FrontWall")
    box((0.0, 0.0, 3.05), (6.2, 8.2, 0.1), diffuse("Ceiling", WHITE), name="Ceiling")
    box((-1.5, 1.5, 0.4), (0.8, 0.8, 0.8), diffuse("Blue", BLUE), rot=(0, 0, 20))
    sphere((0.7, 2.3, 0.5), 0.5, diffuse("Yellow", YELLOW))
    cylinder((1.9, 0.6, 0.8), 0.3, 1.6, diffuse("Red", RED))
    box((-2.2, -0.6, 0.45), (1.0, 0.5, 0.9), diffuse("Orange", ORANGE))  # cabinet by left wall
    plane((-0.4, 3.99, 1.7), (1.4, 0.8), emission("WallLamp", (1.0, 0.9, 0.7), 5.0),
          rot=(90, 0, 0))
    area_light(scene, (0.0, 0.5, 2.95), 2.0, 700.0)
    camera(scene, (1.3, -3.2, 1.5), (-0.8, 2.5, 0.5), 24.0)


def build_exterior_plaza(scene):
    build_world(scene)  # gradient sky, seen by the camera and lighting the scene ...
    scene.world.cycles_visibility.glossy = False  # ... but black to glossy rays
    floor(400.0, metal("PlazaGround", lambda sh: sh.map_range(
        sh.noise(0.12, detail=4.0), 0.3, 0.7, 0.08, 0.45)))
    windows = checker_mat("Windows", (0.75, 0.7, 0.6), (0.15, 0.18, 0.25), 0.8)
    blocks = [((-14, 22, 6), (10, 8, 12), diffuse("Terracotta", (0.7, 0.3, 0.2))),
              ((-2, 34, 9), (12, 8, 18), windows),
              ((12, 26, 4), (8, 10, 8), diffuse("Sand", (0.75, 0.65, 0.45))),
              ((26, 40, 10), (10, 10, 20), windows),
              ((-30, 45, 8), (12, 12, 16), diffuse("Teal", (0.15, 0.45, 0.45)))]
    for loc, dims, mat in blocks:
        box(loc, dims, mat)
    box((-3.0, 6.0, 0.25), (3.0, 0.6, 0.5), diffuse("Bench", (0.5, 0.3, 0.15)))
    sphere((3.5, 9.0, 1.2), 1.2, diffuse("Sculpture", RED))
    for x in (-6.0, 6.0):
        cylinder((x, 14.0, 2.5), 0.35, 5.0, diffuse("Column", WHITE))
    box((0.0, 18.0, 0.6), (2.0, 2.0, 1.2), diffuse("Planter", GREEN), rot=(0, 0, 30))
    sun(scene, 3.5, 40.0, -40.0)
    camera(scene, (0.0, -6.0, 1.7), (0.0, 20.0, 0.8), 28.0)


def build_mirror_glossy_tiles(scene):
    black_world(scene)

    def rough(sh):  # checker fac is exactly 0 or 1: roughness 0.02 or 0.35, 1 m tiles
        _, fac = sh.checker(1.0)
        return sh.math('ADD', sh.math('MULTIPLY', fac, 0.33), 0.02)
    floor(60.0, metal("TileFloor", rough))
    box((0.0, 7.0, 2.0), (14.0, 0.3, 4.0), brick_mat("Brick", (0.6, 0.55, 0.45),
                                                      (0.45, 0.4, 0.35)), name="BackWall")
    plane((0.0, 6.8, 2.6), (8.0, 0.6), emission("Strip", (0.8, 0.9, 1.0), 6.0), rot=(90, 0, 0))
    sphere((-2.2, 1.5, 0.6), 0.6, diffuse("Red", RED))
    box((0.3, 3.0, 0.7), (1.4, 1.4, 1.4), diffuse("Blue", BLUE), rot=(0, 0, 35))
    cylinder((2.5, 1.0, 1.0), 0.35, 2.0, diffuse("Yellow", YELLOW))
    sphere((-0.6, -0.3, 0.3), 0.3, diffuse("Magenta", MAGENTA))
    area_light(scene, (1.0, -1.0, 4.0), 3.0, 900.0)
    camera(scene, (0.0, -5.5, 1.5), (0.0, 3.0, 0.4), 35.0)


def build_puddles(scene):
    black_world(scene)

    def rough(sh):
        base = sh.map_range(sh.noise(2.0, detail=6.0), 0.35, 0.65, 0.5, 0.7)  # rough asphalt
        puddle = sh.math('GREATER_THAN', sh.noise(0.25, detail=2.0), 0.55)  # 0 or 1
        return sh.math('ADD', sh.math('MULTIPLY', base, sh.math('SUBTRACT', 1.0, puddle)),
                       sh.math('MULTIPLY', puddle, 0.05))
    floor(200.0, metal("WetGround", rough))
    brick = brick_mat("Brick", (0.5, 0.22, 0.12), (0.4, 0.3, 0.2), scale=1.5, axis="y")
    box((-6.0, 8.0, 3.0), (1.0, 20.0, 6.0), brick)
    box((2.0, 16.0, 4.0), (14.0, 1.0, 8.0), checker_mat("Facade", (0.7, 0.68, 0.6),
                                                       (0.25, 0.3, 0.35), 1.0))
    box((6.5, 9.0, 2.5), (1.0, 12.0, 5.0), diffuse("Plaster", (0.7, 0.6, 0.45)))
    for loc, size, col in (((-2.5, 5.0, 0.5), 1.0, ORANGE), ((-3.8, 6.2, 0.4), 0.8, GREEN),
                           ((2.5, 9.0, 0.6), 1.2, BLUE)):
        box(loc, (size, size, size), diffuse("Crate", col), rot=(0, 0, 15))
    cylinder((1.5, 4.0, 2.0), 0.08, 4.0, diffuse("Pole", GREY))
    sphere((1.5, 4.0, 4.1), 0.25, emission("LampHead", (1.0, 0.85, 0.6), 20.0))
    sphere((-1.0, 11.0, 0.8), 0.8, diffuse("Ball", RED))
    sun(scene, 2.5, 25.0, 30.0)
    camera(scene, (0.0, -7.0, 1.7), (0.0, 8.0, 0.2), 30.0)


def build_night_street(scene):
    black_world(scene)
    floor(300.0, metal("WetStreet", lambda sh: sh.map_range(
        sh.noise(0.8, detail=5.0), 0.35, 0.65, 0.3, 0.45)))
    dark_l = brick_mat("DarkBrick", (0.07, 0.05, 0.045), (0.05, 0.045, 0.04),
                       mortar=(0.1, 0.1, 0.1), axis="y")
    dark_r = diffuse("DarkWall", (0.06, 0.06, 0.07))
    box((-5.5, 25.0, 6.0), (1.0, 70.0, 12.0), dark_l, name="LeftFacade")
    box((5.5, 25.0, 6.0), (1.0, 70.0, 12.0), dark_r, name="RightFacade")
    box((0.0, 60.0, 6.0), (12.0, 1.0, 12.0), dark_r, name="EndWall")
    neon = [  # (location, dims, colour, strength)
        ((-4.95, 6.0, 3.2), (0.08, 2.0, 0.35), (1.0, 0.1, 0.6), 40.0),
        ((-4.95, 14.0, 2.6), (0.08, 0.25, 1.6), (0.1, 0.8, 1.0), 30.0),
        ((4.95, 9.0, 3.6), (0.08, 2.5, 0.3), (1.0, 0.8, 0.1), 25.0),
        ((4.95, 20.0, 2.8), (0.08, 1.2, 0.5), (0.2, 1.0, 0.3), 35.0),
        ((-4.95, 26.0, 4.0), (0.08, 3.0, 0.25), (0.6, 0.2, 1.0), 50.0),
        ((0.0, 59.45, 5.0), (4.0, 0.08, 0.4), (1.0, 0.25, 0.1), 20.0),
    ]
    for i, (loc, dims, col, strength) in enumerate(neon):
        box(loc, dims, emission("Neon%d" % i, col, strength), name="Neon%d" % i)
    for y in (4.0, 18.0, 32.0):  # dim shop windows
        plane((4.99, y, 1.4), (2.5, 1.6), emission("Window", (1.0, 0.75, 0.45), 1.5),
              rot=(90, 0, 90))
    box((-3.5, 11.0, 0.5), (1.0, 1.0, 1.0), diffuse("Bin", (0.3, 0.3, 0.3)))
    box((2.8, 16.0, 0.75), (1.6, 4.0, 1.5), diffuse("Van", (0.55, 0.55, 0.6)))
    sun(scene, 0.05, 35.0, 120.0)  # faint moonlight, only shapes
    camera(scene, (0.6, -4.0, 1.6), (0.0, 20.0, 0.6), 28.0)


def build_bump_floor(scene):
    black_world(scene)

    def bump(sh):
        node = sh.nodes.new("ShaderNodeBump")
        node.inputs["Strength"].default_value = 0.5
        node.inputs["Distance"].default_value = 0.02
        sh.link(sh.noise(4.0, detail=6.0, roughness=0.55), node.inputs["Height"])
        return node.outputs["Normal"]
    floor(60.0, metal("BumpedMetal", 0.2, bump=bump))
    box((0.0, 7.0, 2.0), (14.0, 0.3, 4.0), checker_mat("Wall", (0.8, 0.8, 0.75),
                                                       (0.2, 0.2, 0.25), 1.5), name="BackWall")
    for x, col in ((-2.5, (1.0, 0.4, 0.2)), (2.5, (0.3, 0.6, 1.0))):
        plane((x, 6.8, 1.6), (0.5, 2.4), emission("Panel", col, 8.0), rot=(90, 0, 0))
    sphere((-1.4, 2.0, 0.55), 0.55, diffuse("Green", GREEN))
    box((1.3, 3.0, 0.6), (1.2, 1.2, 1.2), diffuse("Orange", ORANGE), rot=(0, 0, -25))
    cylinder((0.0, 4.5, 1.2), 0.3, 2.4, diffuse("White", WHITE))
    torus((0.3, 0.6, 0.12), 0.4, 0.12, diffuse("Cyan", CYAN))
    area_light(scene, (-1.0, 0.0, 4.5), 2.5, 800.0)
    camera(scene, (0.0, -4.5, 1.5), (0.0, 2.5, 0.3), 35.0)


def build_thin_objects(scene):
    black_world(scene)
    floor(60.0, metal("Floor", 0.1))
    wood = diffuse("Wood", (0.55, 0.35, 0.18))
    white = diffuse("White", WHITE)
    # Table: top on four thin legs.
    box((-0.6, 1.6, 0.74), (1.2, 0.7, 0.04), wood, name="TableTop")
    for dx in (-0.55, 0.55):
        for dy in (-0.3, 0.3):
            cylinder((-0.6 + dx, 1.6 + dy, 0.36), 0.02, 0.72, white, name="Leg")
    # Fence of thin boards on two thin rails.
    for i in range(14):
        box((-2.6 + 0.38 * i, 4.0, 0.6), (0.08, 0.02, 1.2), diffuse("Board", (0.75, 0.7, 0.55)))
    for z in (0.3, 1.0):
        cylinder((0.0, 4.03, z), 0.015, 5.6, diffuse("Rail", (0.3, 0.3, 0.35)), rot=(0, 90, 0))
    # Poles of different thickness.
    for x, y, r, col in ((1.3, 1.0, 0.02, RED), (1.8, 2.2, 0.035, BLUE), (2.4, 0.6, 0.05, YELLOW),
                         (-2.2, 2.6, 0.03, GREEN)):
        cylinder((x, y, 1.25), r, 2.5, diffuse("Pole", col))
    # Stool: a disc on three splayed thin legs.
    cylinder((0.9, 2.9, 0.5), 0.2, 0.03, diffuse("Seat", MAGENTA))
    for a in (0, 120, 240):
        ax, ay = math.cos(math.radians(a)), math.sin(math.radians(a))
        cylinder((0.9 + 0.1 * ax, 2.9 + 0.1 * ay, 0.25), 0.012, 0.52, white,
                 rot=(-10 * ay, 10 * ax, 0))
    box((0.0, 7.0, 1.5), (10.0, 0.2, 3.0), diffuse("Backdrop", (0.35, 0.4, 0.45)))
    plane((0.0, 6.85, 1.1), (6.0, 1.4), emission("Glow", (1.0, 0.9, 0.75), 4.0),
          rot=(90, 0, 0))
    sun(scene, 3.0, 50.0, -30.0)
    camera(scene, (0.2, -1.8, 1.2), (0.0, 2.5, 0.45), 18.0)


def build_grazing_long(scene):
    black_world(scene)
    floor(800.0, metal("LongFloor", 0.05))
    cols = (RED, YELLOW, BLUE, GREEN, ORANGE, MAGENTA, CYAN, WHITE)
    for i, y in enumerate((8.0, 15.0, 24.0, 35.0, 50.0, 65.0, 80.0)):
        x = (-1.0) ** i * (1.0 + 0.15 * y)
        cylinder((x, y, 1.5 + 0.05 * y), 0.3 + 0.01 * y, 3.0 + 0.1 * y,
                 diffuse("Pillar%d" % i, cols[i]))
    box((0.6, 12.0, 0.25), (0.5, 0.5, 0.5), diffuse("Cube", cols[7]), rot=(0, 0, 30))
    box((-3.0, 30.0, 1.0), (2.0, 2.0, 2.0), diffuse("Block", cols[6]), rot=(0, 0, 20))
    sphere((2.0, 42.0, 1.5), 1.5, diffuse("Ball", cols[4]))
    plane((0.0, 120.0, 4.0), (60.0, 6.0), emission("FarStrip", (1.0, 0.85, 0.6), 5.0),
          rot=(90, 0, 0))
    box((0.0, 125.0, 10.0), (120.0, 2.0, 20.0), checker_mat("FarWall", (0.6, 0.6, 0.55),
                                                            (0.2, 0.25, 0.3), 0.1))
    sun(scene, 3.0, 30.0, -50.0)
    camera(scene, (0.0, 0.0, 0.15), (0.0, 100.0, -0.5), 50.0, clip_start=0.01, clip_end=2000.0)


def build_tabletop_cm(scene):
    """Modelled in centimetres: table 200 x 120 cm, objects 5-40 cm."""
    set_units(scene, "cm")
    black_world(scene)
    box((0.0, 20.0, 73.0), (200.0, 120.0, 4.0), metal("TableTop", 0.4), name="TableTop",
        pass_index=REFLECTOR_INDEX)
    box((0.0, 20.0, 35.5), (20.0, 20.0, 71.0), diffuse("TableFoot", GREY))
    box((0.0, 120.0, 125.0), (500.0, 4.0, 250.0), checker_mat("Wall", (0.8, 0.75, 0.6),
                                                              (0.3, 0.35, 0.5), 0.04))
    plane((0.0, 0.0, 0.0), (1000.0, 1000.0), diffuse("RoomFloor", (0.35, 0.3, 0.25)))
    z0 = 75.0
    cylinder((-25.0, 30.0, z0 + 5.0), 4.5, 10.0, diffuse("Mug", RED))
    box((18.0, 35.0, z0 + 1.5), (22.0, 15.0, 3.0), diffuse("Book", BLUE), rot=(0, 0, 12))
    box((20.0, 36.0, z0 + 4.5), (20.0, 14.0, 3.0), diffuse("Book2", GREEN), rot=(0, 0, -5))
    for x, y, r, col in ((-5.0, 15.0, 4.0, ORANGE), (3.0, 12.0, 3.5, YELLOW),
                         (-12.0, 8.0, 3.0, GREEN)):
        sphere((x, y, z0 + r), r, diffuse("Fruit", col))
    cylinder((-45.0, 55.0, z0 + 15.0), 6.0, 30.0, diffuse("Vase", CYAN))
    cylinder((45.0, 60.0, z0 + 14.0), 9.0, 12.0, emission("LampShade", (1.0, 0.85, 0.6), 6.0))
    cylinder((45.0, 60.0, z0 + 4.0), 1.0, 8.0, diffuse("LampStem", GREY))
    sun(scene, 3.0, 55.0, -35.0)
    camera(scene, (10.0, -75.0, 120.0), (0.0, 30.0, 78.0), 35.0, clip_start=1.0,
           clip_end=10000.0)


def build_product_mm(scene):
    """Modelled in millimetres: a jewellery/product shot, objects 5-50 mm, 100 mm lens."""
    set_units(scene, "mm")
    black_world(scene)
    floor(600.0, metal("Plate", 0.12), name="Plate")
    gold = diffuse("Gold", (0.85, 0.6, 0.2))
    torus((-12.0, 10.0, 2.0), 10.0, 2.0, gold, name="Ring")
    torus((14.0, 22.0, 11.0), 9.0, 1.5, diffuse("Silver", (0.7, 0.7, 0.75)), rot=(80, 0, 20),
          name="StandingRing")
    for i, (x, y, r, col) in enumerate(((4.0, -4.0, 3.0, RED), (9.0, -1.0, 2.5, BLUE),
                                        (13.5, 1.5, 2.0, GREEN), (-28.0, 2.0, 4.5, WHITE))):
        sphere((x, y, r), r, diffuse("Bead%d" % i, col))
    box((-30.0, 32.0, 6.0), (30.0, 20.0, 12.0), diffuse("Box", (0.1, 0.1, 0.12)), rot=(0, 0, 15))
    cylinder((32.0, 40.0, 25.0), 9.0, 50.0, diffuse("Bottle", MAGENTA))
    box((0.0, 110.0, 60.0), (400.0, 5.0, 120.0), checker_mat("Card", (0.8, 0.8, 0.8),
                                                             (0.3, 0.3, 0.35), 0.04))
    plane((0.0, 107.0, 25.0), (200.0, 20.0), emission("Softbox", (1.0, 0.95, 0.9), 4.0),
          rot=(90, 0, 0))
    sun(scene, 3.0, 50.0, 35.0)
    camera(scene, (0.0, -220.0, 90.0), (0.0, 12.0, 6.0), 100.0, clip_start=5.0,
           clip_end=10000.0)


def build_wide_corridor(scene):
    black_world(scene)
    plane((0.0, 20.0, 0.0), (4.0, 50.0), metal("CorridorFloor", 0.3), name="Floor",
          pass_index=REFLECTOR_INDEX)
    box((-2.05, 20.0, 1.5), (0.1, 50.0, 3.0), brick_mat("Brick", (0.6, 0.3, 0.2),
                                                        (0.45, 0.25, 0.2), scale=2.5,
                                                        axis="y"))
    box((2.05, 20.0, 1.5), (0.1, 50.0, 3.0), diffuse("Plaster", (0.75, 0.72, 0.65)))
    box((0.0, 20.0, 3.05), (4.2, 50.0, 0.1), diffuse("Ceiling", (0.6, 0.6, 0.6)))
    box((0.0, 45.05, 1.5), (4.2, 0.1, 3.0), diffuse("EndWall", BLUE))
    box((0.0, -5.05, 1.5), (4.2, 0.1, 3.0), diffuse("BackWall", GREY))
    for y in range(2, 44, 4):
        plane((0.0, float(y), 2.99), (1.0, 0.3), emission("CeilingLight", (1.0, 0.95, 0.85), 12.0),
              rot=(180, 0, 0))
    for i, y in enumerate((3.0, 9.0, 15.0, 23.0)):
        col = (RED, GREEN, YELLOW, CYAN)[i]
        box((1.98, y, 1.05), (0.06, 1.0, 2.1), diffuse("Door%d" % i, col))
    box((-1.7, 6.0, 0.5), (0.5, 0.8, 1.0), diffuse("Cabinet", ORANGE))
    cylinder((0.6, 12.0, 0.45), 0.25, 0.9, diffuse("Barrel", MAGENTA))
    for y in (2.0, 10.0, 18.0, 26.0):  # fill light for the walls (invisible to glossy rays)
        area_light(scene, (0.0, y, 2.95), 1.0, 150.0)
    camera(scene, (0.3, 0.0, 1.5), (0.0, 10.0, 0.0), 16.0)


def build_mirror_panels(scene):
    black_world(scene)
    floor(60.0, metal("RoughFloor", 0.3))
    mirror = metal("Mirror", 0.0)
    for x, y, rx, rz in ((-2.2, 2.5, 12.0, 30.0), (0.4, 4.0, -8.0, -10.0), (2.6, 2.0, 15.0, -40.0)):
        box((x, y, 1.05), (1.3, 0.04, 1.8), mirror, rot=(rx, 0, rz), name="MirrorPanel",
            pass_index=PROP_REFLECTOR_INDEX)
    box((0.0, 8.0, 2.0), (16.0, 0.3, 4.0), brick_mat("Brick", (0.6, 0.55, 0.45),
                                                      (0.5, 0.4, 0.3)), name="BackWall")
    plane((0.0, 7.8, 3.0), (10.0, 0.5), emission("Strip", (1.0, 0.85, 0.6), 6.0), rot=(90, 0, 0))
    sphere((-0.8, 1.0, 0.45), 0.45, diffuse("Red", RED))
    box((1.4, 0.2, 0.4), (0.8, 0.8, 0.8), diffuse("Green", GREEN), rot=(0, 0, 25))
    cylinder((-3.2, 5.0, 1.0), 0.4, 2.0, diffuse("Yellow", YELLOW))
    sphere((3.4, 5.5, 0.7), 0.7, diffuse("Blue", BLUE))
    box((0.0, -6.0, 1.5), (16.0, 0.3, 3.0), checker_mat("FrontWall", (0.8, 0.8, 0.8),
                                                        (0.7, 0.2, 0.1), 1.0))
    area_light(scene, (0.0, -1.0, 5.0), 3.0, 1000.0)
    sun(scene, 1.5, 45.0, 20.0)
    camera(scene, (0.0, -5.0, 1.7), (0.0, 2.5, 0.7), 30.0)


def build_metal_props(scene):
    black_world(scene)
    floor(60.0, metal("Floor", 0.2))
    prop = metal("PropMetal", 0.1)
    sphere((-0.9, 1.5, 0.6), 0.6, prop, name="MetalSphere", pass_index=PROP_REFLECTOR_INDEX)
    cylinder((1.2, 2.5, 0.7), 0.35, 1.4, prop, name="MetalCan", pass_index=PROP_REFLECTOR_INDEX)
    torus((0.4, 0.3, 0.12), 0.35, 0.12, prop, name="MetalTorus", pass_index=PROP_REFLECTOR_INDEX)
    box((-2.2, 3.0, 0.5), (1.0, 1.0, 1.0), diffuse("Red", RED), rot=(0, 0, 20))
    sphere((0.2, 3.8, 0.4), 0.4, diffuse("Yellow", YELLOW))
    box((2.4, 0.8, 0.35), (0.7, 0.7, 0.7), diffuse("Blue", BLUE), rot=(0, 0, -30))
    box((0.0, 6.0, 2.0), (14.0, 0.3, 4.0), checker_mat("Wall", (0.8, 0.8, 0.75),
                                                       (0.2, 0.45, 0.3), 1.5), name="BackWall")
    plane((0.0, 5.8, 2.8), (6.0, 0.6), emission("Strip", (0.9, 0.9, 1.0), 6.0), rot=(90, 0, 0))
    box((-5.0, 2.0, 2.0), (0.3, 10.0, 4.0), brick_mat("Brick", (0.55, 0.2, 0.12),
                                                       (0.4, 0.15, 0.1), axis="y"),
        name="LeftWall")
    area_light(scene, (1.0, -1.0, 4.5), 3.0, 900.0)
    camera(scene, (0.5, -4.2, 1.6), (0.0, 2.0, 0.4), 40.0)


BASE_SAMPLES = 256
SCENES = [
    dict(name="interior_room", split="tune", units="m", samples=384, build=build_interior_room,
         description="Room with a metal floor (r 0.1), brick/checker/plain walls beside and "
                     "behind the camera partly off screen, an area light and a wall lamp, props."),
    dict(name="exterior_plaza", split="tune", units="m", samples=BASE_SAMPLES,
         build=build_exterior_plaza,
         description="Large metal ground with a noise roughness map (0.08-0.45), buildings and "
                     "props, sun and a sky that is black to glossy rays."),
    dict(name="mirror_glossy_tiles", split="tune", units="m", samples=512,
         build=build_mirror_glossy_tiles,
         description="1 m floor tiles alternating mirror (r 0.02) and glossy (r 0.35) from a "
                     "checker: sharp roughness discontinuities."),
    dict(name="puddles", split="holdout", units="m", samples=BASE_SAMPLES, build=build_puddles,
         description="Rough ground (r 0.5-0.7) with smooth puddles (r 0.05) from a thresholded "
                     "noise, courtyard walls, crates, a street lamp, low sun."),
    dict(name="night_street", split="tune", units="m", samples=768, build=build_night_street,
         description="Night street: wet ground (r 0.3-0.45), small bright neon signs "
                     "(strength 20-50) on dark walls; the speckle/firefly case."),
    dict(name="bump_floor", split="tune", units="m", samples=384,
         build=build_bump_floor,
         description="Metal floor (r 0.2) with a noise bump map in the normal, props and two "
                     "emissive panels: the Normal pass carries the bump."),
    dict(name="thin_objects", split="holdout", units="m", samples=512,
         build=build_thin_objects,
         description="Thin poles, fence boards and rails, table and stool legs on a glossy floor "
                     "(r 0.1), 18 mm lens: thickness and contact points."),
    dict(name="grazing_long", split="holdout", units="m", samples=512,
         build=build_grazing_long,
         description="Camera 0.15 m over a long near-mirror floor (r 0.05), pillars up to 80 m, "
                     "far emissive strip; 50 mm lens: long grazing rays."),
    dict(name="tabletop_cm", split="tune", units="cm", samples=BASE_SAMPLES,
         build=build_tabletop_cm,
         description="Tabletop modelled in centimetres (metal top r 0.4, objects 5-40 cm), "
                     "clip 1-10000 cm."),
    dict(name="product_mm", split="holdout", units="mm", samples=384,
         build=build_product_mm,
         description="Jewellery/product shot modelled in millimetres (rings, beads 5-50 mm) on a "
                     "metal plate (r 0.12), 100 mm lens, softbox card."),
    dict(name="wide_corridor", split="tune", units="m", samples=BASE_SAMPLES,
         build=build_wide_corridor,
         description="Corridor with a 16 mm lens: metal floor (r 0.3), brick and plaster walls, "
                     "coloured doors, emissive ceiling lights; strong perspective."),
    dict(name="mirror_panels", split="tune", units="m", samples=BASE_SAMPLES,
         build=build_mirror_panels,
         description="Tilted mirror panels (r 0, pass_index 2) over a rough floor (r 0.3, "
                     "pass_index 1), diffuse objects around: reflections of and on mirrors."),
    dict(name="metal_props", split="holdout", units="m", samples=BASE_SAMPLES,
         build=build_metal_props,
         description="Glossy metal sphere, can and torus (r 0.1, pass_index 2) on a glossy floor "
                     "(r 0.2): hits on glossy surfaces."),
]
SCENE_BY_NAME = {s["name"]: s for s in SCENES}


# ----------------------------------------------------------------------------------------------
# Render settings, manifest, main
# ----------------------------------------------------------------------------------------------

def configure_corpus_render(scene, samples):
    # configure_glossy_render: configure_render (CPU, 480x270, seed 0, denoise off, multilayer
    # half ZIP EXR, Combined/Z/Normal/Gloss passes + roughness AOV) plus adaptive sampling off,
    # clamps off, Filter Glossy 0, caustics off.
    configure_glossy_render(scene)
    scene.cycles.samples = samples
    layer = scene.view_layers[LAYER]
    layer.use_pass_object_index = True


def write_manifest(outdir, scenes=None):
    entries = [{k: s[k] for k in ("name", "split", "units", "description", "samples")}
               for s in (scenes or SCENES)]
    with open(os.path.join(outdir, "corpus.json"), "w") as f:
        json.dump({"scenes": entries}, f, indent=2)
        f.write("\n")


def coverage(exr_path):
    import minexr
    exr = minexr.ExrFile(exr_path)
    index = exr.channel(LAYER + ".IndexOB.X")
    counts = {}
    for v in index:
        counts[int(round(v))] = counts.get(int(round(v)), 0) + 1
    return {k: counts[k] / len(index) for k in sorted(counts)}


def render_scene(spec, outdir):
    bpy.ops.wm.read_factory_settings(use_empty=False)
    scene = bpy.context.scene
    reset_scene()
    spec["build"](scene)
    samples = int(os.environ.get("SSRCL_CORPUS_SAMPLES", spec["samples"]))
    configure_corpus_render(scene, samples)
    scene.cycles.seed = int(os.environ.get("SSRCL_CORPUS_SEED", 0))
    start = time.perf_counter()
    exr_path, _ = render_and_write(scene, outdir, spec["name"])
    seconds = time.perf_counter() - start
    print("CORPUS %s: %d samples, %.1f s, %d bytes" % (spec["name"], samples, seconds,
                                                       os.path.getsize(exr_path)))
    if os.environ.get("SSRCL_CORPUS_PNG"):
        settings = scene.render.image_settings
        settings.file_format = 'PNG'
        settings.color_depth = '8'
        bpy.data.images["Render Result"].save_render(os.path.join(outdir, spec["name"] + ".png"))
    if os.environ.get("SSRCL_CORPUS_COVERAGE"):
        print("CORPUS %s coverage by IndexOB: %s" % (
            spec["name"], ", ".join("%d: %.3f" % kv for kv in coverage(exr_path).items())))


def main():
    outdir, names = outdir_and_names(
        script_args(), SCENE_BY_NAME,
        "usage: blender -b --factory-startup --python make_corpus.py -- <outdir> [scene names...]")
    write_manifest(outdir)
    for name in names:
        render_scene(SCENE_BY_NAME[name], outdir)


if __name__ == "__main__":
    main()
