"""Headless end-to-end test of the ssrcl Blender add-on (samples/blender/ssrcl_addon).

    blender -b --factory-startup --python-exit-code 1 --python test_ssrcl_addon.py -- SSRCL [WORKDIR]

Enables the add-on, builds the bundled mirror scene (samples/blender/make_mirror_scene.py) with
its roughness AOV outputs removed (a scene as a user has it), animates the camera over two
frames, presses Set Up, renders the two frames small and checks: the passes in each EXR, each
frame's camera sidecar against the camera itself, ssrcl's pass against Cycles' own glossy passes
of the mirror floor, the compositor wiring and what it computes, and that ssrcl failures reach
the user as operator errors. Any failed check raises, so Blender exits 1.
"""
import json
import math
import os
import sys
import tempfile

import addon_utils
import bpy

SAMPLES_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "samples",
                           "blender")
sys.path.insert(0, os.path.abspath(SAMPLES_DIR))
import make_mirror_scene  # noqa: E402
import minexr  # noqa: E402
from scene_common import reset_scene  # noqa: E402
from ssrcl_addon import compositor  # noqa: E402

WIDTH, HEIGHT = 192, 108
FRAMES = (1, 2)
CAMERA_X = {1: 0.0, 2: 0.4}  # the camera moves, so each frame needs its own sidecar
LAYER = "ViewLayer."
# Object roughness values of the mirror scene (make_mirror_scene.py); the floor is 0.
OBJECT_ROUGHNESS = (0.5, 0.6, 0.3, 0.7, 0.4, 0.55)


def check(condition, message):
    if not condition:
        raise AssertionError(message)
    print("ok:", message)


def build_scene(scene, outdir):
    reset_scene()
    make_mirror_scene.build_scene(scene)
    for mat in bpy.data.materials:  # the add-on must wire these itself
        for node in [n for n in mat.node_tree.nodes if n.bl_idname == "ShaderNodeOutputAOV"]:
            mat.node_tree.nodes.remove(node)
    lambert = bpy.data.materials.new("NoPrincipled")  # a material with no GGX lobe
    lambert.use_nodes = True
    tree = lambert.node_tree
    tree.nodes.remove(tree.nodes["Principled BSDF"])
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    tree.links.new(diffuse.outputs[0], tree.nodes["Material Output"].inputs["Surface"])

    camera = scene.camera
    for frame in FRAMES:
        camera.location.x = CAMERA_X[frame]
        camera.keyframe_insert("location", index=0, frame=frame)
    scene.frame_start, scene.frame_end = FRAMES[0], FRAMES[-1]

    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = 16
    scene.cycles.use_denoising = False
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    scene.render.resolution_percentage = 100
    scene.render.filepath = os.path.join(outdir, "shot_")
    return lambert


def check_passes(exr_path):
    exr = minexr.ExrFile(exr_path)
    names = {name for name, _ in exr.channel_types()}
    for channel in ("Depth.Z", "Normal.X", "Normal.Y", "Normal.Z", "roughness.X", "GlossDir.R",
                    "GlossInd.R", "GlossCol.R"):
        check(LAYER + channel in names, "%s has %s" % (os.path.basename(exr_path), channel))
    rough = exr.channel(LAYER + "roughness.X")
    bottom = rough[(HEIGHT - 1) * WIDTH:]
    check(set(bottom) == {0.0}, "roughness AOV is 0 on the mirror floor (bottom row)")
    # The AOV is a float32 mean of identical samples inside an object: its value within 1e-6.
    found = [r for r in OBJECT_ROUGHNESS if any(abs(v - r) < 1e-6 for v in rough)]
    check(found == list(OBJECT_ROUGHNESS), "every object's roughness is in the AOV")
    return exr


def check_sidecar(scene, exr_path, frame):
    with open(os.path.splitext(exr_path)[0] + ".camera.json") as f:
        sidecar = json.load(f)
    scene.frame_set(frame)
    camera = scene.camera
    # Independent of export_camera: the view is the camera's inverted world matrix, and a
    # horizontal-fit perspective has P00 = 2 lens / sensor width, P11 = P00 * W / H.
    view = camera.matrix_world.inverted()
    worst = max(abs(sidecar["view"][r][c] - view[r][c]) for r in range(4) for c in range(4))
    check(worst < 1e-5, "frame %d sidecar view matches the camera (max diff %.2g)" % (frame, worst))
    p00 = 2.0 * camera.data.lens / camera.data.sensor_width
    proj = sidecar["projection"]
    check(abs(proj[0][0] - p00) < 1e-5 and abs(proj[1][1] - p00 * WIDTH / HEIGHT) < 1e-5
          and proj[3] == [0.0, 0.0, -1.0, 0.0], "frame %d sidecar projection matches the lens"
          % frame)
    check((sidecar["width"], sidecar["height"]) == (WIDTH, HEIGHT), "sidecar size")


def check_reflection(render, pass_path):
    """ssrcl's RGB is the reflected radiance times A; Cycles' Glossy Direct + Indirect on the
    metal mirror floor is the same radiance times the Fresnel F = mix(0.8, 1, FH) (base colour 0.8;
    README "Glossy passes"). Where ssrcl found the whole reflection (A = 1), their ratio must lie
    near [0.8, 1]."""
    out = minexr.ExrFile(pass_path)
    rgba = [out.channel(c) for c in "RGBA"]
    check(all(math.isfinite(v) for ch in rgba for v in ch), "pass values are finite")
    check(all(0.0 <= a <= 1.0 for a in rgba[3]), "pass A in [0, 1]")
    rough = render.channel(LAYER + "roughness.X")
    depth = render.channel(LAYER + "Depth.Z")
    gloss = [[d + i for d, i in zip(render.channel(LAYER + "GlossDir." + c),
                                    render.channel(LAYER + "GlossInd." + c))] for c in "RGB"]
    floor = [i for i in range(WIDTH * HEIGHT) if rough[i] == 0.0 and depth[i] < 1e9]
    found = [i for i in floor if rgba[3][i] >= 0.999]
    check(len(found) > 0.05 * len(floor), "ssrcl found reflections on %d of %d floor pixels"
          % (len(found), len(floor)))
    ratios = sorted(sum(g[i] for g in gloss) / sum(c[i] for c in rgba[:3]) for i in found
                    if sum(c[i] for c in rgba[:3]) > 0.05)
    median = ratios[len(ratios) // 2]
    check(0.75 <= median <= 1.05, "Cycles glossy / ssrcl reflection on the floor: median %.3f "
          "over %d px (Fresnel 0.8..1)" % (median, len(ratios)))
    return rgba


def check_compositor(scene, frames_and_passes):
    tree = scene.node_tree
    image_node = tree.nodes[compositor.IMAGE_NODE]
    group_node = tree.nodes[compositor.GROUP_NODE]
    check(os.path.samefile(bpy.path.abspath(image_node.image.filepath), frames_and_passes[0][1]),
          "Image node holds the first frame's pass")
    check(image_node.image.source == 'SEQUENCE' and image_node.frame_start == FRAMES[0]
          and image_node.frame_duration == len(FRAMES), "Image node plays the pass sequence")
    link = group_node.inputs["Reflection"].links[0]
    check(link.from_node == image_node and link.from_socket.name == "Image",
          "Image node -> group's Reflection input")
    check(group_node.node_tree.name == compositor.GROUP_NAME, "group node uses the ssrcl group")
    check(tree.nodes[compositor.VIEWER_NODE].inputs["Image"].links[0].from_node == group_node,
          "group -> Viewer")


def check_composite_values(scene, rgba, outdir):
    """Runs the compositor (a re-render of frame 1) with the group feeding the Composite output,
    saves it, and compares it with rgb + env * (1 - A) computed here from the pass file. (A
    background render does not update Viewer nodes, so the saved Composite is what is read.)"""
    env = (0.2, 0.4, 0.8)
    tree = scene.node_tree
    group_node = tree.nodes[compositor.GROUP_NODE]
    group_node.inputs["Environment"].default_value = (*env, 1.0)
    tree.links.new(group_node.outputs["Image"], tree.nodes["Composite"].inputs["Image"])
    scene.render.use_compositing = True
    scene.ssrcl.enabled = False  # this render only runs the compositor
    scene.frame_set(FRAMES[0])
    bpy.ops.render.render()
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth, settings.exr_codec = 'OPEN_EXR', '32', 'ZIP'
    path = os.path.join(outdir, "composite.exr")
    bpy.data.images["Render Result"].save_render(path, scene=scene)
    settings.file_format = 'OPEN_EXR_MULTILAYER'
    composite = minexr.ExrFile(path)
    rgb = [composite.channel(c) for c in "RGB"]
    worst = max(abs(rgb[c][i] - (rgba[c][i] + env[c] * (1.0 - rgba[3][i])))
                for c in range(3) for i in range(WIDTH * HEIGHT))
    check(worst < 1e-4, "composite = rgb + env * (1 - A) (max diff %.2g)" % worst)


def check_errors_reported(scene, prefs):
    """ssrcl failures reach the user as operator errors, naming the cause."""
    good = prefs.executable
    prefs.executable = "/nonexistent/ssrcl"
    try:
        bpy.ops.ssrcl.trace_render()
        raise AssertionError("a missing ssrcl was not reported")
    except RuntimeError as e:
        check("cannot run ssrcl '/nonexistent/ssrcl'" in str(e), "missing ssrcl reported: %s" % e)
    prefs.executable = good
    scene.ssrcl.view_layer = "NoSuchLayer"
    try:
        bpy.ops.ssrcl.trace_render()
        raise AssertionError("ssrcl's refusal was not reported")
    except RuntimeError as e:
        check("exit 2" in str(e) and "NoSuchLayer" in str(e), "ssrcl's error reported: %s" % e)
    check("exit 2" in scene.ssrcl.status, "and shown in the panel")
    scene.ssrcl.view_layer = "ViewLayer"


def check_still_render(scene, outdir):
    """A render that wrote no file (F12): the trace saves the Render Result, then traces it."""
    bpy.ops.ssrcl.trace_render()
    path = os.path.join(outdir, "ssrcl", "shot_%04d.exr" % scene.frame_current)
    check(scene.ssrcl.status == "traced 1 frame(s): " + path, "status: " + scene.ssrcl.status)
    node = scene.node_tree.nodes[compositor.IMAGE_NODE]
    check(node.image.source == 'FILE' and os.path.samefile(node.image.filepath, path),
          "Image node holds the still's pass")


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) not in (1, 2):
        raise SystemExit("usage: ... --python test_ssrcl_addon.py -- SSRCL [WORKDIR]")
    outdir = args[1] if len(args) == 2 else tempfile.mkdtemp(prefix="ssrcl-addon-")
    os.makedirs(outdir, exist_ok=True)

    addon_utils.enable("ssrcl_addon", default_set=True, handle_error=None)
    prefs = bpy.context.preferences.addons["ssrcl_addon"].preferences
    prefs.executable = os.path.abspath(args[0])

    scene = bpy.context.scene
    lambert = build_scene(scene, outdir)
    bpy.ops.ssrcl.setup()
    aov = next(n for n in lambert.node_tree.nodes if n.bl_idname == "ShaderNodeOutputAOV")
    check(aov.name == "roughness" and aov.inputs["Value"].links[0].from_socket.default_value
          == 1.0, "a material without a Principled BSDF writes roughness 1")
    bpy.ops.render.render(animation=True)
    check(scene.ssrcl.status.startswith("traced 2 frame(s)"), "status: " + scene.ssrcl.status)

    frames_and_passes = []
    for frame in FRAMES:
        exr_path = os.path.join(outdir, "shot_%04d.exr" % frame)
        render = check_passes(exr_path)
        check_sidecar(scene, exr_path, frame)
        pass_path = os.path.join(outdir, "ssrcl", "shot_%04d.exr" % frame)
        rgba = check_reflection(render, pass_path)
        frames_and_passes.append((frame, pass_path))
        if frame == FRAMES[0]:
            first_rgba = rgba
    check_compositor(scene, frames_and_passes)
    check_composite_values(scene, first_rgba, outdir)
    check_errors_reported(scene, prefs)
    check_still_render(scene, outdir)
    print("ssrcl add-on test: all checks passed")


main()
