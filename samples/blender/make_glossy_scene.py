"""Build and render the ssrcl "glossy" sample with Cycles.

    blender -b --factory-startup --python-exit-code 1 --python make_glossy_scene.py -- <outdir>

Writes <outdir>/glossy.exr (multilayer EXR: Combined, Depth, Normal, Glossy Direct/Indirect/Color
and the "roughness" value AOV on view layer "ViewLayer") and <outdir>/glossy.camera.json.

The floor is a rough metal with F0 = 1 (Principled BSDF, metallic 1, base colour white,
single-scatter GGX), so its glossy passes are the plain GGX integral with no Fresnel tint.
Its roughness comes in three stripes that run away from the camera; their edges are the floor
lines that project onto image columns 160 and 320 exactly, so every image column band holds one
roughness: columns 0-159 -> 0.125, 160-319 -> 0.25, 320-479 -> 0.4375 (values chosen to be
exact binary fractions, so the filtered AOV is bit-exact inside a stripe). Lambertian objects
(view-independent, so their screen colour is their reflected radiance) stand in every stripe,
and a wide emissive bar behind them spans all three, giving the blurred reflections strong signal.
The sun lights the objects but is invisible to glossy rays, so the floor's glossy passes hold
only what the floor reflects: sky, emitter and objects.
"""
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import export_camera  # noqa: E402  (needs the path tweak above)
from scene_common import (HEIGHT, WIDTH, add_aov_output, add_object,  # noqa: E402
                          build_camera, build_world, configure_render, render_and_write,
                          reset_scene)
from script_args import parse_outdir  # noqa: E402

SAMPLES = 1024
# Floor stripes, left to right in the image: roughness per band and the image columns where
# the next band starts (pixel centres x + 0.5 < edge belong to the band on the left).
STRIPE_ROUGHNESS = (0.125, 0.25, 0.4375)
STRIPE_EDGE_COLUMNS = (160, 320)
# AOV value for the Lambertian objects and the emitter (no GGX lobe at all: "fully rough").
OBJECT_AOV_ROUGHNESS = 1.0


def make_diffuse_material(name, color):
    """Lambertian (Diffuse BSDF, roughness 0 = Lambert, not Oren-Nayar): view-independent."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*color, 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0
    links.new(diffuse.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
    rough = nodes.new("ShaderNodeValue")
    rough.outputs[0].default_value = OBJECT_AOV_ROUGHNESS
    add_aov_output(mat, rough.outputs[0])
    return mat


def make_emission_material(name, color, strength):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*color, 1.0)
    emission.inputs["Strength"].default_value = strength
    links.new(emission.outputs["Emission"], nodes["Material Output"].inputs["Surface"])
    rough = nodes.new("ShaderNodeValue")
    rough.outputs[0].default_value = OBJECT_AOV_ROUGHNESS
    add_aov_output(mat, rough.outputs[0])
    return mat


def image_ndc_x(scene, nodes, links):
    """A shader socket holding the image NDC x of the shaded point of a world-space object:
    clip_x / clip_w, dot products of the object position with rows of the camera's P V."""
    cam = export_camera.camera_dict(scene)
    view, proj = cam["view"], cam["projection"]
    clip = [[sum(proj[r][k] * view[k][c] for k in range(4)) for c in range(4)] for r in range(4)]
    coords = nodes.new("ShaderNodeTexCoord")

    def row_dot(row):
        dot = nodes.new("ShaderNodeVectorMath")
        dot.operation = 'DOT_PRODUCT'
        links.new(coords.outputs["Object"], dot.inputs[0])
        dot.inputs[1].default_value = row[:3]
        add = nodes.new("ShaderNodeMath")
        add.operation = 'ADD'
        links.new(dot.outputs["Value"], add.inputs[0])
        add.inputs[1].default_value = row[3]
        return add.outputs[0]

    ndc_x = nodes.new("ShaderNodeMath")
    ndc_x.operation = 'DIVIDE'
    links.new(row_dot(clip[0]), ndc_x.inputs[0])
    links.new(row_dot(clip[3]), ndc_x.inputs[1])
    return ndc_x.outputs[0]


def make_floor_material(scene):
    """F0 = 1 single-scatter GGX metal whose roughness is picked per stripe.

    A floor point p = (x, y, 0) lies in the image at NDC x = clip_x / clip_w with
    clip = P V p; the stripe edges are the floor lines where that equals the NDC of image
    columns 160 and 320. The shader evaluates clip_x and clip_w as dot products of the object
    position (the floor's object space is world space) with rows of P V, so the stripes are
    fixed on the floor (camera-independent at render time) yet line up with those columns.
    roughness = i0 r0 + i1 r1 + i2 r2 with 0/1 indicators i_k, which is exact in float.
    """
    edges_ndc = [2.0 * col / WIDTH - 1.0 for col in STRIPE_EDGE_COLUMNS]

    mat = bpy.data.materials.new("GlossyFloor")
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.distribution = 'GGX'  # single-scatter GGX (not 'MULTI_GGX')
    bsdf.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)  # F0 = 1: no Fresnel
    bsdf.inputs["Metallic"].default_value = 1.0
    for name in ("Specular", "Specular Tint", "Anisotropic", "Sheen", "Clearcoat",
                 "Subsurface", "Transmission"):
        bsdf.inputs[name].default_value = 0.0

    def math(op, a, b):
        node = nodes.new("ShaderNodeMath")
        node.operation = op
        for i, v in enumerate((a, b)):
            if isinstance(v, float):
                node.inputs[i].default_value = v
            else:
                links.new(v, node.inputs[i])
        return node.outputs[0]

    ndc_x = image_ndc_x(scene, nodes, links)
    left = math('LESS_THAN', ndc_x, edges_ndc[0])      # 1 in the left stripe, else 0
    right = math('GREATER_THAN', ndc_x, edges_ndc[1])  # 1 in the right stripe, else 0
    middle = math('SUBTRACT', math('SUBTRACT', 1.0, left), right)
    roughness = math('ADD', math('ADD', math('MULTIPLY', left, STRIPE_ROUGHNESS[0]),
                                 math('MULTIPLY', middle, STRIPE_ROUGHNESS[1])),
                     math('MULTIPLY', right, STRIPE_ROUGHNESS[2]))
    # The same socket drives the BSDF (Cycles: alpha = roughness^2) and the AOV.
    links.new(roughness, bsdf.inputs["Roughness"])
    add_aov_output(mat, roughness)
    return mat


def build_scene(scene):
    build_world(scene)
    # The sky is invisible to glossy rays, so the floor's glossy passes hold only what screen-space
    # reflections can find in principle (the objects and the emitter): every floor pixel can then
    # be compared with an SSR pass whose missing part is black, with no environment to guess.
    scene.world.cycles_visibility.glossy = False
    build_camera(scene)

    # Floor: 1000 m square at z = 0, every pixel below the horizon is floor.
    bpy.ops.mesh.primitive_plane_add(size=1000.0, location=(0.0, 0.0, 0.0))
    floor = bpy.context.active_object
    floor.name = "GlossyFloor"
    floor.data.materials.append(make_floor_material(scene))

    # Lambertian objects, two per stripe, standing on the floor (z of centre = half height):
    # (kind, centre, name, colour, size, z rotation).
    objects = [
        # left stripe (roughness 0.125)
        ("sphere", (-3.4, 0.0, 0.7), "Red", (0.85, 0.06, 0.04), 0.7, 0.0),
        ("cube", (-7.8, 5.0, 0.6), "Green", (0.06, 0.70, 0.10), 0.6, math.radians(25)),
        # middle stripe (roughness 0.25)
        ("sphere", (-0.75, -1.5, 0.5), "Yellow", (0.90, 0.75, 0.04), 0.5, 0.0),
        ("cylinder", (0.9, 3.5, 1.6), "Blue", (0.06, 0.15, 0.85), (0.45, 3.2), 0.0),
        # right stripe (roughness 0.4375)
        ("cube", (4.2, 1.0, 0.7), "Orange", (0.95, 0.35, 0.03), 0.7, math.radians(20)),
        ("sphere", (8.8, 6.0, 0.9), "Magenta", (0.80, 0.05, 0.65), 0.9, 0.0),
    ]
    for kind, loc, name, color, size, rot in objects:
        obj = add_object(kind, loc, make_diffuse_material(name, color), size=size,
                         rotation_z=rot)
        obj.name = name + kind.capitalize()

    # Wide emissive bar floating 0.4-2.2 m above the floor behind the objects, facing the
    # camera and spanning all three stripes: the same bright source blurred by three roughnesses.
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, 11.0, 1.3),
                                     rotation=(math.radians(90.0), 0.0, 0.0))
    bar = bpy.context.active_object
    bar.name = "EmissiveBar"
    bar.scale = (24.0, 1.8, 1.0)  # 24 m wide, 1.8 m high (local y is world z after the turn)
    bar.data.materials.append(make_emission_material("Emitter", (1.0, 0.85, 0.6), 6.0))

    # Sun 45 degrees up from behind the camera (as in the mirror sample) lights the objects'
    # visible faces. It is invisible to glossy rays: otherwise the far GGX tail of its
    # highlight (sun behind the camera, not in the image) would add ~12 % to the roughest
    # stripe's glossy passes, light that screen-space reflections cannot find. The objects are
    # Lambertian, so for them nothing changes.
    sun_data = bpy.data.lights.new("Sun", type='SUN')
    sun_data.energy = 3.0
    sun_data.angle = math.radians(2.0)
    sun = bpy.data.objects.new("Sun", sun_data)
    sun.rotation_euler = (math.radians(45), 0.0, math.radians(-35))
    sun.visible_glossy = False
    scene.collection.objects.link(sun)


def configure_glossy_render(scene):
    configure_render(scene, SAMPLES)
    # Every pixel gets exactly SAMPLES samples: no adaptive stopping, so noise is uniform and
    # the AOV average of identical values stays exact.
    scene.cycles.use_adaptive_sampling = False
    # No biasing shortcuts: glossy passes are the reference the SSR result is compared with.
    scene.cycles.sample_clamp_direct = 0.0
    scene.cycles.sample_clamp_indirect = 0.0  # default 10 would clip paths via the emitter
    scene.cycles.blur_glossy = 0.0  # "Filter Glossy" would widen lobes after diffuse bounces
    # Light that reaches an object via the glossy floor (sun and emitter caustics) is all
    # fireflies at these sample counts; drop it. The objects' radiance stays view-independent
    # (the same paths are cut whether the object is seen directly or in the floor), and paths
    # that start with the floor's glossy bounce are not caustics, so the floor is unaffected.
    scene.cycles.caustics_reflective = False
    scene.cycles.caustics_refractive = False


def main():
    outdir = parse_outdir("make_glossy_scene.py")
    scene = bpy.context.scene
    reset_scene()
    build_scene(scene)
    configure_glossy_render(scene)
    # Overrides for quick previews and noise estimates (the committed file uses neither).
    scene.cycles.samples = int(os.environ.get("SSRCL_GLOSSY_SAMPLES", SAMPLES))
    scene.cycles.seed = int(os.environ.get("SSRCL_GLOSSY_SEED", 0))
    render_and_write(scene, outdir, "glossy")


if __name__ == "__main__":
    main()
