"""Scene-building helpers shared by the ssrcl Blender sample generators.

Used by make_mirror_scene.py and make_glossy_scene.py (run inside Blender: needs bpy).
Everything here is generic: empty the factory scene, materials that also write their roughness
to the "roughness" value AOV, primitive objects, the gradient sky, the render/EXR settings and
the render-and-write step.
"""
import math
import os
import sys
import time

import bpy

if __package__:  # imported from the ssrcl add-on, which links this file: no sys.path change
    from . import export_camera
else:
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import export_camera  # noqa: E402  (needs the path tweak above)

WIDTH, HEIGHT = 480, 270
AOV_NAME = "roughness"


def reset_scene():
    # --factory-startup still ships the default cube, light and camera; start from nothing.
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras):
        for block in list(coll):
            coll.remove(block)


def add_aov_output(mat, socket, name=AOV_NAME, kind="Value"):
    """Write `socket` to the AOV `name` of material `mat` through the AOV node's `kind` input
    ("Value" for a value AOV, "Color" for a colour one); by default the roughness value AOV."""
    aov = mat.node_tree.nodes.new("ShaderNodeOutputAOV")
    aov.name = name  # on this node type, "name" is the AOV it writes to
    mat.node_tree.links.new(socket, aov.inputs[kind])
    return aov


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
    add_aov_output(mat, rough.outputs[0])
    return mat


def add_object(kind, location, material, size=1.0, rotation_z=0.0):
    """kind: "sphere" (size = radius), "cube" (size = half edge) or "cylinder"
    (size = (radius, height)); location is the centre."""
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
    else:
        raise ValueError("unknown object kind %r" % kind)
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


def configure_render(scene, samples):
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = samples
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


def render_and_write(scene, outdir, stem):
    """Render the scene camera to <outdir>/<stem>.exr and write <outdir>/<stem>.camera.json."""
    exr_path = os.path.join(outdir, stem + ".exr")
    scene.render.filepath = exr_path
    scene.render.use_file_extension = False
    start = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print("render + write took %.1f s" % (time.perf_counter() - start))

    json_path = os.path.join(outdir, stem + ".camera.json")
    export_camera.write_camera_json(json_path, scene)
    print("wrote", exr_path, "and", json_path)
    return exr_path, json_path


def build_camera(scene):
    """Both samples' camera: 1.6 m high looking ~12 degrees down, about three quarters floor."""
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
    bpy.context.view_layer.update()  # the glossy floor's shader reads the camera's matrix_world
