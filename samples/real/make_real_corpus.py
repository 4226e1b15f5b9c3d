"""Build and render the real-asset corpus (issue 24): Cycles scenes made of public CC0 / BSD assets.

    python3 samples/real/sources.py <mirror dir>          # the assets, once (see sources.py)
    blender -b --factory-startup --python-exit-code 1 --python samples/real/make_real_corpus.py \
        -- <outdir> [scene names...]
    xvfb-run -a -s "-screen 0 1280x1024x24" blender -b --factory-startup --python-exit-code 1 \
        --python samples/real/make_real_corpus.py -- --eevee <outdir> [scene names...]
    blender -b --factory-startup --python-exit-code 1 --python samples/real/make_real_corpus.py \
        -- --move <outdir> <scene> [--frames N]

No names = every scene. Each scene is built from scratch and rendered like samples/corpus
(make_corpus.configure_corpus_render: Cycles CPU, 480x270, seed 0, no adaptive sampling, no
denoising, no clamps, Filter Glossy 0, caustics off; multilayer ZIP EXR, then every channel half
but Depth: compact_exr) into
<outdir>/<name>.exr + <name>.camera.json; <outdir>/corpus.json lists every scene (the schema of
samples/corpus/corpus.json, plus "environment" on the scenes lit by an HDRI). HDRI scenes also
write <outdir>/<hdri>.exr, the HDRI as the half-float EXR the render used, the file to give
`ssrcl --environment` (bench/score_corpus reads it from corpus.json).

What differs from samples/corpus, on purpose: the assets keep their own materials, so floors are
dielectric (Principled, Specular 0.5) or textured metal, props and walls are glossy too (hits on
view-dependent surfaces), normal maps and texture-driven roughness are in the G-buffer.
What stays: lamps are invisible to glossy rays (no highlight that is in no G-buffer); interiors
have a black world; the HDRI scenes' world is visible to every ray (environment fill). Every
Principled BSDF is set to single-scatter GGX (what ssrcl's E assumes; Blender 3.4's default).

Passes: those of samples/corpus (Combined, Depth, Normal, roughness AOV, Glossy Direct / Indirect /
Color, IndexOB: floor 1, glossy props 2, rest 0) plus the colour AOV "base_color" and the value AOV
"metallic" (what `ssrcl trace` reads for its default glossy-pass form), each fed from the socket
that drives the material's Principled BSDF input (texture links included): the three AOVs wired
by samples/blender/ssrcl_addon/passes.py, as the add-on wires them.

--eevee renders the same scenes with legacy EEVEE SSR (samples/corpus/render_eevee.py's settings:
Specular Light, plus Specular Color (GlossCol), lamps specular 0; interiors' world black for glossy rays, the HDRI scenes keep
their world probe) into <outdir>/<name>.eevee.exr. --move renders a short camera move (frames
<outdir>/<scene>.NNNN.exr, SSRCL_REAL_MOVE_SAMPLES samples each, default 32; --frames, default 6).

Needs oiiotool (Debian openimageio-tools) for compact_exr.

Environment: SSRCL_CORPUS_SAMPLES / SSRCL_CORPUS_SEED / SSRCL_CORPUS_PNG / SSRCL_CORPUS_COVERAGE
as in make_corpus.py; SSRCL_REAL_ASSETS (default samples/real/assets).
Sources (repository, path, commit, licence of every file): sources.py.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import time

import bpy
import numpy
from mathutils import Matrix, Vector

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "corpus"))
sys.path.insert(0, os.path.join(HERE, "..", "blender"))
import make_corpus  # noqa: E402  (scene helpers, render settings; puts samples/blender on sys.path)
from script_args import outdir_and_names, script_args, take_option  # noqa: E402
import make_env_corpus  # noqa: E402  (environment_world)
import render_eevee  # noqa: E402  (configure_eevee)
from scene_common import render_and_write, reset_scene  # noqa: E402
from sources import asset_path  # noqa: E402
from ssrcl_addon import passes  # noqa: E402  (the add-on's own pass and AOV wiring)

numpy.bool = bool  # Blender 3.4's glTF importer uses numpy.bool, gone from Debian's numpy

FLOOR = make_corpus.REFLECTOR_INDEX
PROP = make_corpus.PROP_REFLECTOR_INDEX
LAYER = make_corpus.LAYER


# ----------------------------------------------------------------------------------------------
# Material AOVs
# ----------------------------------------------------------------------------------------------

def wire_material_aovs(scene):
    """The add-on's passes and AOVs (roughness, base_color and metallic from the sockets driving
    each Principled BSDF's inputs, texture links included); every Principled BSDF single-scatter
    GGX."""
    passes.enable_view_layer_passes(scene.view_layers[LAYER])
    passes.wire_material_aovs(bpy.data.materials)
    for mat in bpy.data.materials:
        for node in mat.node_tree.nodes if mat.use_nodes and mat.node_tree else ():
            if node.bl_idname == "ShaderNodeBsdfPrincipled":
                node.distribution = 'GGX'


# ----------------------------------------------------------------------------------------------
# Assets: glTF models, PBR texture sets, HDRIs
# ----------------------------------------------------------------------------------------------

def model(local, location, rot_z=0.0, pass_index=0, scale=1.0, keep=None):
    """Imports a glTF model (its own materials) and places its roots at `location`, turned `rot_z`
    degrees about Z. `keep`: names of the model's objects to keep (the rest is deleted)."""
    before = set(bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=asset_path(local))
    objs = [o for o in bpy.data.objects if o not in before]
    if keep is not None:
        for o in [o for o in objs if o.name.split(".")[0] not in keep]:
            bpy.data.objects.remove(o, do_unlink=True)
        objs = [o for o in bpy.data.objects if o not in before]
    place = (Matrix.Translation(Vector(location)) @ Matrix.Rotation(math.radians(rot_z), 4, 'Z')
             @ Matrix.Scale(scale, 4))
    for o in objs:
        if o.parent is None:
            o.matrix_world = place @ o.matrix_world
        o.pass_index = pass_index
    return objs


def _image(sh, local, vector, color=True):
    node = sh.nodes.new("ShaderNodeTexImage")
    node.image = bpy.data.images.load(asset_path(local), check_existing=True)
    if not color:
        node.image.colorspace_settings.name = 'Non-Color'
    sh.link(vector, node.inputs["Vector"])
    return node


def pbr(name, tex, repeat, rough="arm", rough_scale=1.0, normal="nor_gl", metallic=None,
        bump_distance=0.004):
    """Principled material from a Poly Haven texture set textures/<tex>_<map>_1k.*, tiled
    `repeat` = (u, v) times over the object's UVs. rough: "arm" (G of the ARM map), "rough"
    (the roughness map) or "rough_g" (G of the roughness map: RobotLocomotion's rosewood copy
    packs it glTF-style, R and B are 1), times rough_scale (a wet or lacquered version).
    normal: "nor_gl" (tangent-space normal map) or "disp" (height through a Bump node).
    metallic: None (0), or "arm" (B of the ARM map)."""
    mat, sh = make_corpus.new_material(name)
    bsdf = sh.nodes["Principled BSDF"]
    mapping = sh.nodes.new("ShaderNodeMapping")
    mapping.inputs["Scale"].default_value = (repeat[0], repeat[1], 1.0)
    sh.link(sh.nodes.new("ShaderNodeTexCoord").outputs["UV"], mapping.inputs["Vector"])
    uv = mapping.outputs["Vector"]
    ext = lambda m: "jpg" if m == "diff" or (m != "disp" and tex in JPG_SETS) else "png"  # noqa: E731
    path = lambda m: "textures/%s_%s_1k.%s" % (tex, m, ext(m))  # noqa: E731
    sh.link(_image(sh, path("diff"), uv).outputs["Color"], bsdf.inputs["Base Color"])
    split = sh.nodes.new("ShaderNodeSeparateColor")
    sh.link(_image(sh, path("arm" if rough == "arm" else "rough"), uv, color=False).outputs["Color"],
            split.inputs["Color"])
    r = split.outputs["Red" if rough == "rough" else "Green"]
    if rough_scale != 1.0:
        r = sh.math('MULTIPLY', r, rough_scale)
    sh.link(r, bsdf.inputs["Roughness"])
    if metallic == "arm":
        sh.link(split.outputs["Blue"], bsdf.inputs["Metallic"])
    if normal == "nor_gl":
        nmap = sh.nodes.new("ShaderNodeNormalMap")
        sh.link(_image(sh, path("nor_gl"), uv, color=False).outputs["Color"], nmap.inputs["Color"])
        sh.link(nmap.outputs["Normal"], bsdf.inputs["Normal"])
    else:
        bump = sh.nodes.new("ShaderNodeBump")
        bump.inputs["Distance"].default_value = bump_distance
        sh.link(_image(sh, path("disp"), uv, color=False).outputs["Color"], bump.inputs["Height"])
        sh.link(bump.outputs["Normal"], bsdf.inputs["Normal"])
    return mat


# Texture sets whose roughness / ARM / normal maps are JPEG (the others' are PNG).
JPG_SETS = {"wood_floor", "blue_metal_plate", "painted_plaster_wall"}


def hdri_exr(hdri, outdir):
    """The HDRI as a half-float EXR in outdir (what the world uses and ssrcl gets), 1024x512."""
    path = os.path.join(outdir, hdri + ".exr")
    img = bpy.data.images.load(asset_path("hdri/%s_1k.hdr" % hdri))
    peak = max(img.pixels[:])
    if peak > 60000.0:
        raise RuntimeError("%s: peak %.0f does not fit a half float" % (hdri, peak))
    settings = bpy.context.scene.render.image_settings
    settings.file_format, settings.color_mode = 'OPEN_EXR', 'RGB'
    settings.color_depth, settings.exr_codec = '16', 'ZIP'
    img.save_render(path, scene=bpy.context.scene)
    bpy.data.images.remove(img)
    return path


def hdri_world(scene, path, rotation_z=0.0):
    make_env_corpus.environment_path = path
    make_env_corpus.environment_world(scene, rotation_z)


# ----------------------------------------------------------------------------------------------
# Room pieces
# ----------------------------------------------------------------------------------------------

def floor_plane(name, mat, size, centre=(0.0, 0.0), z=0.0):
    return make_corpus.plane((centre[0], centre[1], z), size, mat, name=name, pass_index=FLOOR)


def walls(mat, x0, x1, y0, y1, height, skip=()):
    """Walls (planes) of a box room; `skip`: sides left open ("left", "right", "back", "front")."""
    cx, cy, w, d = (x0 + x1) / 2, (y0 + y1) / 2, x1 - x0, y1 - y0
    sides = {"left": ((x0, cy, height / 2), (d, height), (90, 0, 90)),
             "right": ((x1, cy, height / 2), (d, height), (90, 0, -90)),
             "back": ((cx, y1, height / 2), (w, height), (90, 0, 0)),
             "front": ((cx, y0, height / 2), (w, height), (90, 0, 180))}
    for side, (loc, size, rot) in sides.items():
        if side not in skip:
            make_corpus.plane(loc, size, mat, rot=rot, name="Wall_" + side)


def tea_set(location, rot_z=0.0):
    return model("models/tea_set_01_1k.gltf", location, rot_z, pass_index=PROP)


# ----------------------------------------------------------------------------------------------
# Scenes
# ----------------------------------------------------------------------------------------------

def build_living_room(scene, outdir):
    make_corpus.black_world(scene)
    floor_plane("RosewoodFloor", pbr("Rosewood", "rosewood_veneer1", (4, 4.7), rough="rough_g"),
                (6.0, 7.0), (0.0, 0.5))
    plaster = pbr("Plaster", "painted_plaster_wall", (3, 1.4))
    walls(plaster, -3.0, 3.0, -3.0, 4.0, 2.8)
    make_corpus.plane((0.0, 0.5, 2.8), (6.0, 7.0), make_corpus.diffuse("Ceiling", (0.8, 0.8, 0.78)),
                      rot=(180, 0, 0))
    model("models/sofa_03_1k.gltf", (0.2, 3.4, 0.0), 180.0)
    model("models/wooden_bookshelf_worn_1k.gltf", (-2.65, 1.6, 0.0), -90.0)
    model("models/painted_wooden_cabinet_1k.gltf", (2.6, 2.0, 0.0), 90.0)
    model("models/wooden_table_02_1k.gltf", (0.1, 1.6, 0.0))
    tea_set((0.1, 1.55, 0.8), 10.0)
    model("models/painted_wooden_stool_1k.gltf", (-1.2, 0.6, 0.0), 30.0)
    make_corpus.plane((-2.98, 0.0, 1.5), (1.6, 1.2), make_corpus.emission(
        "Window", (1.0, 0.95, 0.85), 6.0), rot=(90, 0, 90))
    make_corpus.area_light(scene, (0.0, 1.0, 2.75), 2.5, 600.0)
    make_corpus.camera(scene, (0.9, -2.4, 1.45), (-0.3, 1.8, 0.35), 24.0)


def build_tea_table(scene, outdir):
    make_corpus.black_world(scene)
    floor_plane("TableTop", pbr("LacqueredWood", "wood_floor", (1.2, 0.66), rough_scale=0.3),
                (1.8, 1.0), z=0.76)
    make_corpus.box((0.0, 0.0, 0.735), (1.8, 1.0, 0.04), make_corpus.diffuse("Edge", (0.2, 0.1, 0.05)))
    make_corpus.box((0.0, 0.0, 0.36), (0.15, 0.15, 0.72), make_corpus.diffuse("Leg", (0.1, 0.08, 0.06)))
    tea_set((0.0, 0.05, 0.76), -8.0)
    floor = make_corpus.plane((0.0, 1.0, 0.0), (8.0, 8.0), pbr("Floor", "concrete_layers", (4, 4),
                                                            rough="rough", normal="disp"))
    floor.pass_index = 0
    walls(pbr("Plaster", "painted_plaster_wall", (3, 1.4)), -4.0, 4.0, -3.0, 2.0, 2.8)
    model("models/wooden_bookshelf_worn_1k.gltf", (-0.9, 1.7, 0.0), 180.0)
    model("models/painted_wooden_cabinet_02_1k.gltf", (1.1, 1.7, 0.0), 180.0)
    make_corpus.plane((0.2, 1.98, 1.7), (1.0, 0.5), make_corpus.emission(
        "Lamp", (1.0, 0.85, 0.65), 8.0), rot=(90, 0, 0))
    make_corpus.area_light(scene, (0.5, -0.8, 2.6), 1.5, 300.0)
    make_corpus.camera(scene, (0.25, -1.15, 1.12), (0.0, 0.35, 0.74), 30.0)


def build_metal_workshop(scene, outdir):
    make_corpus.black_world(scene)
    floor_plane("MetalPlate", pbr("BlueMetalPlate", "blue_metal_plate", (5, 5), metallic="arm"),
                (8.0, 8.0), (0.0, 1.0))
    walls(pbr("Concrete", "concrete_layers", (4, 1.4), rough="rough", normal="disp"),
          -4.0, 4.0, -3.0, 5.0, 3.0)
    model("models/painted_wooden_cabinet_02_1k.gltf", (-1.6, 3.4, 0.0), 200.0)
    model("models/painted_wooden_cabinet_1k.gltf", (1.4, 3.6, 0.0), 180.0)
    model("models/painted_wooden_stool_1k.gltf", (0.3, 1.6, 0.0), 15.0)
    tea_set((1.4, 3.55, 1.18), 180.0)
    model("models/wooden_bookshelf_worn_1k.gltf", (3.6, 1.5, 0.0), 90.0)
    make_corpus.plane((0.0, 4.98, 2.4), (5.0, 0.4), make_corpus.emission(
        "Strip", (0.85, 0.9, 1.0), 10.0), rot=(90, 0, 0))
    make_corpus.area_light(scene, (0.0, 1.0, 2.9), 3.0, 900.0)
    make_corpus.camera(scene, (0.6, -2.2, 1.6), (0.0, 2.5, 0.5), 28.0)


def build_concrete_lobby(scene, outdir):
    make_corpus.black_world(scene)
    floor_plane("PolishedConcrete", pbr("PolishedConcrete", "concrete_layers", (5, 6),
                                        rough="rough", rough_scale=0.35, normal="disp",
                                        bump_distance=0.002), (10.0, 12.0), (0.0, 2.0))
    walls(pbr("Plaster", "painted_plaster_wall", (5, 1.6)), -5.0, 5.0, -4.0, 8.0, 3.5)
    model("models/sofa_03_1k.gltf", (-1.6, 5.0, 0.0), 160.0)
    model("models/wooden_table_02_1k.gltf", (0.9, 4.0, 0.0), 20.0)
    tea_set((0.9, 4.0, 0.8), 20.0)
    model("models/wooden_bookshelf_worn_1k.gltf", (3.0, 7.6, 0.0), 180.0)
    model("models/painted_wooden_cabinet_1k.gltf", (-4.6, 3.0, 0.0), -90.0)
    for x in (-2.5, 0.0, 2.5):
        make_corpus.plane((x, 3.0, 3.49), (1.2, 1.2), make_corpus.emission(
            "Panel", (1.0, 0.97, 0.9), 8.0), rot=(180, 0, 0))
    make_corpus.area_light(scene, (0.0, 2.0, 3.4), 4.0, 1200.0)
    make_corpus.camera(scene, (1.2, -2.5, 1.7), (-0.2, 4.5, 0.4), 26.0)


def build_terrace_tiles(scene, outdir):
    hdri_world(scene, hdri_exr("venice_sunset", outdir), 0.0)
    floor_plane("GlazedTiles", pbr("GlazedTiles", "clay_roof_tiles_02", (6, 6), rough="rough",
                                   rough_scale=0.45, normal="disp", bump_distance=0.01),
                (12.0, 12.0), (0.0, 3.0))
    model("models/sofa_03_1k.gltf", (-1.3, 3.2, 0.0), 200.0)
    model("models/wooden_table_02_1k.gltf", (0.6, 2.0, 0.0), -15.0)
    tea_set((0.6, 2.0, 0.8), -15.0)
    model("models/painted_wooden_stool_1k.gltf", (1.6, 1.2, 0.0))
    model("models/painted_wooden_cabinet_02_1k.gltf", (2.6, 4.5, 0.0), 160.0)
    make_corpus.camera(scene, (0.3, -1.8, 1.5), (0.0, 3.0, 0.3), 28.0)


def build_wet_riverbed(scene, outdir):
    hdri_world(scene, hdri_exr("potsdamer_platz", outdir), 0.0)
    floor_plane("WetStone", pbr("WetStone", "dry_riverbed_rock", (8, 8), rough="rough",
                                rough_scale=0.2, normal="disp", bump_distance=0.02),
                (16.0, 16.0), (0.0, 4.0))
    model("models/painted_wooden_cabinet_1k.gltf", (-1.5, 3.0, 0.0), 170.0)
    model("models/wooden_bookshelf_worn_1k.gltf", (1.4, 4.5, 0.0), 200.0)
    model("models/painted_wooden_stool_1k.gltf", (0.2, 1.6, 0.0), 40.0)
    make_corpus.camera(scene, (0.0, -2.0, 1.5), (0.0, 4.0, 0.2), 30.0)


def build_wet_deck(scene, outdir):
    hdri_world(scene, hdri_exr("kiara_1_dawn", outdir), 0.0)
    floor_plane("WetDeck", pbr("WetDeck", "wood_floor", (6, 6), rough_scale=0.35),
                (10.0, 10.0), (0.0, 3.0))
    model("models/wooden_table_02_1k.gltf", (-0.5, 2.2, 0.0), 10.0)
    tea_set((-0.5, 2.2, 0.8), 10.0)
    model("models/sofa_03_1k.gltf", (1.4, 3.8, 0.0), 200.0)
    model("models/painted_wooden_stool_1k.gltf", (0.8, 1.3, 0.0), -20.0)
    make_corpus.camera(scene, (0.5, -1.6, 1.35), (0.0, 3.0, 0.3), 30.0)


def build_product_pepper(scene, outdir):
    hdri_world(scene, hdri_exr("studio_small_03", outdir), 0.0)
    steel, sh = make_corpus.new_material("BrushedSteel")
    bsdf = sh.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.62, 0.62, 0.64, 1.0)
    bsdf.inputs["Metallic"].default_value = 1.0
    rough = _image(sh, "textures/concrete_layers_rough_1k.png",
                   sh.nodes.new("ShaderNodeTexCoord").outputs["UV"], color=False)
    sh.link(sh.map_range(rough.outputs["Color"], 0.0, 1.0, 0.08, 0.3), bsdf.inputs["Roughness"])
    floor_plane("SteelPlate", steel, (1.2, 1.2), (0.0, 0.1))
    for x, y, rz in ((-0.07, 0.05, 0.0), (0.06, 0.1, 60.0), (0.0, 0.2, 130.0)):
        model("models/bell_pepper.gltf", (x, y, 0.0), rz, pass_index=PROP)
    model("models/tea_set_01_1k.gltf", (0.16, 0.02, 0.0), -30.0, pass_index=PROP,
          keep={"tea_set_01_cup_small_01", "tea_set_01_saucer_circular_03"})
    make_corpus.plane((0.0, 0.45, 0.4), (1.2, 0.8), pbr("Backdrop", "painted_plaster_wall", (1, 0.7)),
                      rot=(90, 0, 0))
    make_corpus.camera(scene, (0.06, -0.62, 0.2), (0.03, 0.12, 0.07), 45.0, clip_start=0.01)


SAMPLES = 64  # what two busy shared cores allowed for 8 scenes (~3.5 s a sample); noise: README.md
SCENES = [
    dict(name="living_room", split="tune", units="m", samples=SAMPLES, build=build_living_room,
         description="Furnished room (Poly Haven sofa, bookshelf, cabinet, table, stool, glazed tea "
                     "set) on a rosewood-veneer floor with its normal and roughness (0.31) maps; "
                     "plaster walls, emissive window, black world."),
    dict(name="tea_table", split="tune", units="m", samples=SAMPLES, build=build_tea_table,
         description="Glazed ceramic tea set (pass_index 2) on a lacquered wooden table top "
                     "(wood_floor maps, roughness x 0.3, normal map); bookshelf, cabinet, lamp."),
    dict(name="metal_workshop", split="tune", units="m", samples=SAMPLES, build=build_metal_workshop,
         description="Painted metal floor (blue_metal_plate: roughness 0.22-0.37 and metallic, 0 "
                     "on this paint, from its ARM map; normal map), concrete walls, cabinets, stool, "
                     "tea set, emissive strip."),
    dict(name="concrete_lobby", split="holdout", units="m", samples=SAMPLES,
         build=build_concrete_lobby,
         description="Polished concrete floor (concrete_layers, roughness x 0.35, bump from its "
                     "height map), sofa, table with tea set, bookshelf, ceiling panels."),
    dict(name="terrace_tiles", split="tune", units="m", samples=SAMPLES, build=build_terrace_tiles,
         environment="venice_sunset.exr",
         description="Glazed terracotta tiles (clay_roof_tiles_02, roughness x 0.45, bump) under "
                     "the venice_sunset HDRI: sofa, table with tea set, stool, cabinet."),
    dict(name="wet_riverbed", split="holdout", units="m", samples=SAMPLES,
         build=build_wet_riverbed, environment="potsdamer_platz.exr",
         description="Wet stone ground (dry_riverbed_rock, roughness x 0.2, bump) under the "
                     "potsdamer_platz HDRI (city): cabinet, bookshelf, stool."),
    dict(name="wet_deck", split="tune", units="m", samples=SAMPLES, build=build_wet_deck,
         environment="kiara_1_dawn.exr",
         description="Rain-wet wooden deck (wood_floor, roughness x 0.35, normal map) under the "
                     "kiara_1_dawn HDRI: table with tea set, sofa, stool."),
    dict(name="product_pepper", split="holdout", units="m", samples=SAMPLES,
         build=build_product_pepper, environment="studio_small_03.exr",
         description="Product shot: three glossy bell peppers and a glazed cup (pass_index 2) on a "
                     "steel plate (metallic 1, roughness ~0.12 through a map) under the "
                     "studio_small_03 HDRI's softboxes, plaster backdrop."),
]
SCENE_BY_NAME = {s["name"]: s for s in SCENES}


# ----------------------------------------------------------------------------------------------
# Main
# ----------------------------------------------------------------------------------------------

def compact_exr(path):
    """Rewrites a Cycles render with every channel half but Depth.Z (float), ZIP. Blender writes
    Normal, IndexOB and the value AOVs float whatever the colour depth; half holds them to 2^-11
    (object indices exactly) and takes 30 % off the file; the corpus's scores move by at most
    0.021 dB (README.md, "Files")."""
    tmp = path + ".tmp.exr"
    subprocess.run(["oiiotool", "--nosoftwareattrib", path, "-d", "half", "-d", LAYER + ".Depth.Z=float",
                    "--compression", "zip", "-o", tmp], check=True)
    os.replace(tmp, path)

def write_manifest(outdir):
    entries = []
    for s in SCENES:
        entry = {k: s[k] for k in ("name", "split", "units", "description", "samples")}
        if "environment" in s:
            entry["environment"] = s["environment"]
        entries.append(entry)
    with open(os.path.join(outdir, "corpus.json"), "w") as f:
        json.dump({"scenes": entries}, f, indent=2)
        f.write("\n")


def build(spec, outdir, samples):
    bpy.ops.wm.read_factory_settings(use_empty=False)
    scene = bpy.context.scene
    reset_scene()
    spec["build"](scene, outdir)
    make_corpus.configure_corpus_render(scene, samples)
    # Fewer bounces than Cycles' defaults (12 / 4 / 4): two shared CPU cores render these textured
    # scenes at ~1.5 s per sample. The passes stay one consistent render (the G-buffer's colours
    # and the reference come from the same paths), only light after 3 glossy / 2 diffuse bounces
    # is dropped.
    scene.cycles.max_bounces, scene.cycles.diffuse_bounces = 6, 2
    scene.cycles.glossy_bounces, scene.cycles.transmission_bounces = 3, 2
    wire_material_aovs(scene)
    scene.cycles.seed = int(os.environ.get("SSRCL_CORPUS_SEED", 0))
    return scene


def render_cycles(spec, outdir):
    samples = int(os.environ.get("SSRCL_CORPUS_SAMPLES", spec["samples"]))
    scene = build(spec, outdir, samples)
    start = time.perf_counter()
    exr_path, _ = render_and_write(scene, outdir, spec["name"])
    compact_exr(exr_path)
    print("REAL %s: %d samples, %.1f s, %d bytes" % (spec["name"], samples,
                                                     time.perf_counter() - start,
                                                     os.path.getsize(exr_path)))
    if os.environ.get("SSRCL_CORPUS_PNG"):
        settings = scene.render.image_settings
        settings.file_format, settings.color_depth = 'PNG', '8'
        bpy.data.images["Render Result"].save_render(os.path.join(outdir, spec["name"] + ".png"))
    if os.environ.get("SSRCL_CORPUS_COVERAGE"):
        print("REAL %s coverage by IndexOB: %s" % (spec["name"], ", ".join(
            "%d: %.3f" % kv for kv in make_corpus.coverage(exr_path).items())))


def render_eevee_peer(spec, outdir):
    scene = build(spec, outdir, 1)
    render_eevee.configure_eevee(scene, world_probe="environment" in spec)
    # Specular Color too: Light x Color is EEVEE's pass with the Fresnel, the form Cycles' glossy
    # passes hold on these dielectric reflectors (score_corpus "eevee:form=glossy-pass").
    layer = scene.view_layers[LAYER]
    layer.use_pass_glossy_color = True
    # Only the specular passes are scored: no Normal or AOVs in the file (EEVEE writes Combined
    # regardless).
    layer.use_pass_normal = False
    while layer.aovs:  # the collection has no remove(); the operator removes the active one
        layer.active_aov_index = 0
        bpy.ops.scene.view_layer_remove_aov()
    path = os.path.join(outdir, spec["name"] + ".eevee.exr")
    scene.render.filepath = path
    scene.render.use_file_extension = False
    start = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print("EEVEE %s: %.1f s, %d bytes" % (spec["name"], time.perf_counter() - start,
                                         os.path.getsize(path)))


MOVE_STEP_M = 0.06  # sideways per frame: a slow dolly, every frame a view of the others


def render_move(spec, outdir, frames):
    scene = build(spec, outdir, int(os.environ.get("SSRCL_REAL_MOVE_SAMPLES", 32)))
    cam = scene.camera
    start = cam.location.copy()
    right = cam.matrix_world.to_quaternion() @ Vector((1.0, 0.0, 0.0))
    right = Vector((right.x, right.y, 0.0)).normalized()
    for n in range(frames):
        cam.location = start + right * (MOVE_STEP_M * (n - (frames - 1) / 2))
        bpy.context.view_layer.update()
        compact_exr(render_and_write(scene, outdir, "%s.%04d" % (spec["name"], n))[0])


def main():
    args = script_args()
    mode = args.pop(0) if args and args[0] in ("--eevee", "--move") else None
    frames = take_option(args, "--frames", 6)
    usage = ("usage: ... make_real_corpus.py -- [--eevee] <outdir> [scene names...]\n"
             "       ... make_real_corpus.py -- --move <outdir> <scene> [--frames N]")
    if mode == "--move" and len(args) != 2:
        args = []  # the usage
    if args and mode != "--eevee" and shutil.which("oiiotool") is None:
        print("oiiotool not found (apt-get install openimageio-tools): the Cycles renders are "
              "rewritten half but Depth with it", file=sys.stderr)
        sys.exit(2)
    outdir, names = outdir_and_names(args, SCENE_BY_NAME, usage)
    if mode == "--move":
        render_move(SCENE_BY_NAME[names[0]], outdir, frames)
        return
    if mode is None:
        write_manifest(outdir)
    for name in names:
        (render_eevee_peer if mode == "--eevee" else render_cycles)(SCENE_BY_NAME[name], outdir)


if __name__ == "__main__":
    main()
