"""The "glossy" sample with coloured specular: the validation render of `--output-form glossy-pass`.

    blender -b --factory-startup --python-exit-code 1 --python make_tinted_glossy_scene.py -- <outdir>

Writes <outdir>/tinted_glossy.exr and .camera.json: make_glossy_scene.py's scene and passes, with
the floor's Principled BSDF at Specular 0.5 (Blender's default, the IOR 1.5 ssrcl's E assumes),
base colour copper (0.95, 0.64, 0.54), metallic 1 left of image column 320 and 0.25 right of it,
and two more AOVs ssrcl reads by default for that form: "base_color" (colour) and "metallic"
(value), fed from the same sockets as the BSDF. Cycles' Glossy Direct + Indirect then hold the
Fresnel-tinted reflection that `ssrcl trace --output-form glossy-pass` predicts.
"""
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_glossy_scene  # noqa: E402
from scene_common import WIDTH, render_and_write, reset_scene  # noqa: E402
from script_args import parse_outdir  # noqa: E402

BASE_COLOR = (0.95, 0.64, 0.54)
METALLIC_LEFT, METALLIC_RIGHT, METALLIC_EDGE_COLUMN = 1.0, 0.25, 320


def tint_floor(scene):
    mat = bpy.data.materials["GlossyFloor"]
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Specular"].default_value = 0.5

    base = nodes.new("ShaderNodeRGB")
    base.outputs[0].default_value = (*BASE_COLOR, 1.0)
    links.new(base.outputs[0], bsdf.inputs["Base Color"])

    # Metallic by image column, as make_glossy_scene picks its roughness stripes.
    right = nodes.new("ShaderNodeMath")
    right.operation = 'GREATER_THAN'
    links.new(make_glossy_scene.image_ndc_x(scene, nodes, links), right.inputs[0])
    right.inputs[1].default_value = 2.0 * METALLIC_EDGE_COLUMN / WIDTH - 1.0
    metallic = nodes.new("ShaderNodeMapRange")  # 0 -> left value, 1 -> right value
    links.new(right.outputs[0], metallic.inputs["Value"])
    metallic.inputs["To Min"].default_value = METALLIC_LEFT
    metallic.inputs["To Max"].default_value = METALLIC_RIGHT
    links.new(metallic.outputs["Result"], bsdf.inputs["Metallic"])

    for name, socket, kind in (("base_color", base.outputs[0], "Color"),
                               ("metallic", metallic.outputs["Result"], "Value")):
        aov = nodes.new("ShaderNodeOutputAOV")
        aov.name = name
        links.new(socket, aov.inputs[kind])
        layer_aov = scene.view_layers[0].aovs.add()
        layer_aov.name = name
        layer_aov.type = 'COLOR' if kind == "Color" else 'VALUE'


def main():
    outdir = parse_outdir("make_tinted_glossy_scene.py")
    scene = bpy.context.scene
    reset_scene()
    make_glossy_scene.build_scene(scene)
    make_glossy_scene.configure_glossy_render(scene)
    tint_floor(scene)
    scene.cycles.samples = int(os.environ.get("SSRCL_GLOSSY_SAMPLES", make_glossy_scene.SAMPLES))
    scene.cycles.seed = int(os.environ.get("SSRCL_GLOSSY_SEED", 0))
    render_and_write(scene, outdir, "tinted_glossy")


if __name__ == "__main__":
    main()
