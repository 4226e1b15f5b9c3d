"""Glossy dielectric hits (issue 24 item 4): a lacquered floor reflecting glazed ceramic and metal props.

    blender -b --factory-startup --python-exit-code 1 --python make_glazed_props_scene.py -- <outdir>

Writes <outdir>/glazed_props.exr and .camera.json (240x135, small enough for tests/data): a
lacquered dark-wood floor (Principled, metallic 0, roughness 0.1, pass_index 1) with a white
glazed sphere (roughness 0.05), an orange glazed vase (0.08) and a gold metal sphere (metallic 1,
0.1) and a dark blue glazed sphere (0.05) that shows little but reflections, all pass_index 2,
before diffuse walls, with a softbox behind the camera (so the props show a highlight toward the
camera that the floor does not see) and an emissive strip on the back wall, on screen. Every material writes the "roughness", "base_color" and "metallic" AOVs from the sockets
that drive its BSDF. Cycles' Glossy Direct + Indirect on the floor is the reference for the
glossy-pass form; on the props' reflection in it, the Fresnel of the props' own glaze decides it.
Renders with the corpus settings (make_corpus.py: no adaptive sampling, no clamps, no caustics).
SSRCL_GLAZED_SAMPLES / SSRCL_GLAZED_SEED override the sample count and seed (noise estimates).
"""
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "corpus"))
import make_corpus as corpus  # noqa: E402
from scene_common import render_and_write, reset_scene  # noqa: E402
from script_args import parse_outdir  # noqa: E402

WIDTH, HEIGHT = 240, 135
SAMPLES = 1024
MATERIAL_AOVS = (("base_color", "COLOR"), ("metallic", "VALUE"))


def write_aov(sh, name, socket, kind):
    aov = sh.nodes.new("ShaderNodeOutputAOV")
    aov.name = name
    sh.link(socket, aov.inputs[kind])


def principled(name, color, roughness, metallic):
    """Single-scatter GGX Principled BSDF at Specular 0.5 (the IOR 1.5 ssrcl's E assumes); the
    sockets that drive it also write the three AOVs. `color` is an RGB tuple or a function
    Shader -> colour socket."""
    mat, sh = corpus.new_material(name)
    bsdf = sh.nodes["Principled BSDF"]
    bsdf.distribution = 'GGX'
    bsdf.inputs["Specular"].default_value = 0.5
    for key in ("Specular Tint", "Anisotropic", "Sheen", "Clearcoat", "Subsurface", "Transmission"):
        bsdf.inputs[key].default_value = 0.0
    if callable(color):
        base = color(sh)
    else:
        node = sh.nodes.new("ShaderNodeRGB")
        node.outputs[0].default_value = (*color, 1.0)
        base = node.outputs[0]
    rough, metal = sh.value(roughness), sh.value(metallic)
    sh.link(base, bsdf.inputs["Base Color"])
    sh.link(rough, bsdf.inputs["Roughness"])
    sh.link(metal, bsdf.inputs["Metallic"])
    corpus.add_aov_output(mat, rough)
    write_aov(sh, "base_color", base, "Color")
    write_aov(sh, "metallic", metal, "Value")
    return mat


def wood(sh):
    """Dark wood whose colour follows a stretched noise (view-independent, textures the base)."""
    mix = sh.nodes.new("ShaderNodeMixRGB")
    mix.inputs["Color1"].default_value = (0.10, 0.045, 0.02, 1.0)
    mix.inputs["Color2"].default_value = (0.22, 0.11, 0.05, 1.0)
    scale = sh.nodes.new("ShaderNodeVectorMath")
    scale.operation = 'MULTIPLY'
    scale.inputs[1].default_value = (1.0, 12.0, 1.0)  # grain along X
    sh.link(sh.position(), scale.inputs[0])
    noise = sh.nodes.new("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 2.0
    noise.inputs["Detail"].default_value = 4.0
    sh.link(scale.outputs[0], noise.inputs["Vector"])
    sh.link(noise.outputs["Fac"], mix.inputs["Fac"])
    return mix.outputs["Color"]


def build_scene(scene):
    corpus.black_world(scene)
    corpus.floor(20.0, principled("LacquerFloor", wood, 0.1, 0.0))
    props = corpus.PROP_REFLECTOR_INDEX
    corpus.sphere((-0.75, 0.9, 0.35), 0.35, principled("WhiteGlaze", (0.85, 0.85, 0.8), 0.05, 0.0),
                  name="WhiteGlaze", pass_index=props)
    corpus.cylinder((0.3, 1.5, 0.4), 0.2, 0.8, principled("OrangeGlaze", (0.9, 0.35, 0.04), 0.08, 0.0),
                    name="OrangeVase", pass_index=props)
    corpus.sphere((0.95, 0.55, 0.25), 0.25, principled("Gold", (1.0, 0.77, 0.34), 0.1, 1.0),
                  name="GoldSphere", pass_index=props)
    corpus.sphere((0.0, 0.35, 0.22), 0.22, principled("DarkGlaze", (0.02, 0.03, 0.09), 0.05, 0.0),
                  name="DarkGlaze", pass_index=props)
    corpus.box((-1.6, 2.4, 0.45), (0.9, 0.9, 0.9), corpus.diffuse("Blue", corpus.BLUE), rot=(0, 0, 25))
    corpus.box((0.0, 3.5, 1.5), (8.0, 0.2, 3.0),
               corpus.checker_mat("BackWall", (0.8, 0.78, 0.7), (0.2, 0.35, 0.3), 2.0), name="BackWall")
    corpus.box((-2.6, 1.0, 1.5), (0.2, 6.0, 3.0),
               corpus.brick_mat("Brick", (0.55, 0.2, 0.12), (0.4, 0.16, 0.1), axis="y"), name="LeftWall")
    corpus.plane((0.6, 3.39, 1.2), (3.0, 0.2), corpus.emission("Strip", (1.0, 0.9, 0.75), 6.0),
                 rot=(90, 0, 0))
    # Softbox behind and above the camera, off screen: the props' highlight toward the camera.
    corpus.plane((0.0, -3.6, 2.2), (2.0, 1.2), corpus.emission("Softbox", (1.0, 0.97, 0.92), 8.0),
                 rot=(-60, 0, 0))
    corpus.area_light(scene, (0.5, 0.0, 3.5), 2.0, 300.0)
    corpus.camera(scene, (0.2, -2.6, 1.05), (0.0, 1.0, 0.2), 32.0)


def main():
    outdir = parse_outdir("make_glazed_props_scene.py")
    scene = bpy.context.scene
    reset_scene()
    build_scene(scene)
    corpus.configure_corpus_render(scene, int(os.environ.get("SSRCL_GLAZED_SAMPLES", SAMPLES)))
    scene.cycles.seed = int(os.environ.get("SSRCL_GLAZED_SEED", 0))
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    for name, kind in MATERIAL_AOVS:
        aov = scene.view_layers[corpus.LAYER].aovs.add()
        aov.name = name
        aov.type = kind
    render_and_write(scene, outdir, "glazed_props")


if __name__ == "__main__":
    main()
