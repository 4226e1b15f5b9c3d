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
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import export_camera  # noqa: E402  (needs the path tweak above)

WIDTH, HEIGHT = 480, 270
SAMPLES = 64
AOV_NAME = "roughness"


def reset_scene():
    # --factory-startup still ships the default cube, light and camera; start from nothing.
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras):
        for block in list(coll):
            coll.remove(block)


def make_material(name, color, roughness, metallic=0.0):
    """Principled BSDF that also writes its roughness to the AOV, so the AOV matches the BSDF."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    links = mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness

    # One Value node drives both the BSDF and the AOV so they cannot drift apart.
    rough = nodes.new("ShaderNodeValue")
    rough.outputs[0].default_value = roughness
    links.new(rough.outputs[0], bsdf.inputs["Roughness"])
    aov = nodes.new("ShaderNodeOutputAOV")
    aov.name = AOV_NAME  # on this node type, "name" is the AOV it writes to
    links.new(rough.outputs[0], aov.inputs["Value"])
    return mat


def add_object(kind, location, material, size=1.0, rotation_z=0.0):
    if kind == "sphere":
        bpy.ops.mesh.primitive_uv_sphere_add(radius=size, location=location, segments=48,
                                             ring_count=24)
        bpy.ops.object.shade_smooth()
    elif kind == "cube":
        bpy.ops.mesh.primitive_cube_add(size=2.0 * size, location=location,
                                        rotation=(0.0, 0.0, rotation_z))
    elif kind == "cylinder":  # size = (radius, height)
        bpy.ops.mesh.primitive_cylinder_add(radius=size[0], depth=size[1], location=location,
                                            vertices=48)
        bpy.ops.object.shade_smooth()
    obj = bpy.context.active_object
    obj.data.materials.append(material)
    return obj


def build_world(scene):
    # Vertical gradient sky so an upside-down reflection of the sky is recognisable.
    world = bpy.data.worlds.new("Sky")
    scene.world = world
    world.use_nodes = True
    nodes = world.node_tree.nodes
    links = world.node_tree.links
    background = nodes["Background"]
    coords = nodes.new("ShaderNodeTexCoord")
    separate = nodes.new("ShaderNodeSeparateXYZ")
    ramp = nodes.new("ShaderNodeValToRGB")
    elements = ramp.color_ramp.elements
    elements[0].position = 0.0
    elements[0].color = (0.55, 0.65, 0.80, 1.0)  # horizon: pale blue
    elements[1].position = 0.6
    elements[1].color = (0.12, 0.25, 0.60, 1.0)  # towards zenith: deeper blue
    # For the world, "Generated" is the normalised view direction; its Z is the elevation sine.
    links.new(coords.outputs["Generated"], separate.inputs[0])
    links.new(separate.outputs["Z"], ramp.inputs["Fac"])
    links.new(ramp.outputs["Color"], background.inputs["Color"])
    background.inputs["Strength"].default_value = 1.0


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

    # Camera 1.6 m high looking ~12 degrees down: about three quarters floor, the rest sky.
    cam_data = bpy.data.cameras.new("Camera")
    cam_data.lens = 24.0
    cam_data.sensor_fit = 'AUTO'
    cam_data.clip_start = 0.1
    cam_data.clip_end = 1000.0  # beyond the floor edge, so the floor is never clipped
    camera = bpy.data.objects.new("Camera", cam_data)
    camera.location = (0.0, -8.0, 1.6)
    camera.rotation_euler = (math.radians(78.0), 0.0, 0.0)
    scene.collection.objects.link(camera)
    scene.camera = camera


def configure_render(scene):
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = SAMPLES
    scene.cycles.use_denoising = False
    scene.cycles.seed = 0
    scene.render.resolution_x = WIDTH
    scene.render.resolution_y = HEIGHT
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = 1.0
    scene.render.pixel_aspect_y = 1.0
    scene.render.film_transparent = False
    scene.render.use_compositing = False  # write the raw render passes, untouched
    scene.render.use_sequencer = False

    # Keep the file reproducible: no date/time/host/render-time metadata in the EXR header.
    for flag in ("date", "time", "render_time", "memory", "hostname", "filename", "frame",
                 "frame_range", "camera", "lens", "scene", "marker", "note",
                 "sequencer_strip"):
        setattr(scene.render, "use_stamp_" + flag, False)

    layer = scene.view_layers["ViewLayer"]
    layer.use_pass_combined = True
    layer.use_pass_z = True
    layer.use_pass_normal = True
    layer.use_pass_glossy_direct = True
    layer.use_pass_glossy_indirect = True
    layer.use_pass_glossy_color = True
    aov = layer.aovs.add()
    aov.name = AOV_NAME
    aov.type = 'VALUE'

    settings = scene.render.image_settings
    settings.file_format = 'OPEN_EXR_MULTILAYER'
    settings.color_depth = '16'  # half for colour passes; Blender keeps data passes float
    settings.exr_codec = 'ZIP'
    settings.use_preview = False


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 1:
        print("usage: blender -b --factory-startup --python make_mirror_scene.py -- <outdir>",
              file=sys.stderr)
        sys.exit(2)
    outdir = os.path.abspath(args[0])
    os.makedirs(outdir, exist_ok=True)

    scene = bpy.context.scene
    reset_scene()
    build_scene(scene)
    configure_render(scene)

    exr_path = os.path.join(outdir, "mirror.exr")
    scene.render.filepath = exr_path
    scene.render.use_file_extension = False
    start = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print("render + write took %.1f s" % (time.perf_counter() - start))

    json_path = os.path.join(outdir, "mirror.camera.json")
    export_camera.write_camera_json(json_path, scene)
    print("wrote", exr_path, "and", json_path)


if __name__ == "__main__":
    main()
