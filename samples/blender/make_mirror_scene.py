"""Build and render the ssrcl "mirror" sample with Cycles.

    blender -b --factory-startup --python-exit-code 1 --python make_mirror_scene.py -- <outdir>

Writes <outdir>/mirror.exr (multilayer EXR: Combined, Depth, Normal, Glossy Direct/Indirect/Color
and a "roughness" value AOV on view layer "ViewLayer") and <outdir>/mirror.camera.json.
A mirror floor under coloured diffuse objects gives strong, easy-to-read reflections; some
objects are cut by the frame edge so the off-screen failure case of SSR is in the picture.
"""
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_common import (add_object, build_camera, build_world, configure_render,  # noqa: E402
                          make_material, render_and_write, reset_scene)
from script_args import parse_outdir  # noqa: E402

SAMPLES = 64


def build_scene(scene):
    build_world(scene)

    # Floor: large enough that its far edge sits within ~1 px of the horizon, so every pixel
    # below the horizon is floor. The light grey tint keeps reflections distinguishable from
    # the directly seen objects. Roughness 0 makes it a perfect mirror (GGX alpha = 0).
    bpy.ops.mesh.primitive_plane_add(size=1000.0, location=(0.0, 0.0, 0.0))
    floor = bpy.context.active_object
    floor.name = "MirrorFloor"
    floor.data.materials.append(
        make_material("Mirror", (0.8, 0.8, 0.8), roughness=0.0, metallic=1.0))

    # Saturated diffuse-ish objects standing on the floor (z of centre = half height):
    # (kind, centre, name, colour, roughness, size, z rotation).
    objects = [
        ("sphere", (-1.2, 1.0, 0.8), "Red", (0.80, 0.05, 0.04), 0.5, 0.8, 0.0),
        ("cube", (1.6, 2.4, 0.7), "Green", (0.05, 0.60, 0.08), 0.6, 0.7, math.radians(30)),
        ("sphere", (0.6, -1.6, 0.5), "Yellow", (0.85, 0.70, 0.03), 0.3, 0.5, 0.0),
        # Tall pillar cut by the top edge: the mirror shows its top, the screen does not.
        ("cylinder", (-0.6, 5.0, 3.0), "Blue", (0.05, 0.12, 0.80), 0.7, (0.6, 6.0), 0.0),
        # Cut by the left and right frame edges.
        ("sphere", (-7.4, 3.0, 1.2), "Magenta", (0.75, 0.04, 0.60), 0.4, 1.2, 0.0),
        ("cube", (4.1, -0.6, 0.9), "Orange", (0.90, 0.30, 0.02), 0.55, 0.9, math.radians(15)),
    ]
    for kind, loc, name, color, rough, size, rot in objects:
        obj = add_object(kind, loc, make_material(name, color, rough), size=size, rotation_z=rot)
        obj.name = name + kind.capitalize()

    # Sun 45 degrees up, from behind the camera and to the side, so lit and shaded faces of
    # the objects both show up in the reflections.
    sun_data = bpy.data.lights.new("Sun", type='SUN')
    sun_data.energy = 3.0
    sun_data.angle = math.radians(2.0)
    sun = bpy.data.objects.new("Sun", sun_data)
    sun.rotation_euler = (math.radians(45), 0.0, math.radians(-35))
    scene.collection.objects.link(sun)

    build_camera(scene)


def main():
    outdir = parse_outdir("make_mirror_scene.py")
    scene = bpy.context.scene
    reset_scene()
    build_scene(scene)
    configure_render(scene, SAMPLES)
    render_and_write(scene, outdir, "mirror")


if __name__ == "__main__":
    main()
