"""Render an animated camera move through a corpus scene, for `ssrcl batch --neighbours K` (issue 16).

    blender -b --factory-startup --python-exit-code 1 --python samples/blender/make_camera_move.py \
        -- <outdir> [<scene>] [--frames N] [--scored EVERY] [--width W]

The scene (default interior_room) is built by samples/corpus/make_corpus.py's own builder; its
camera then trucks sideways 2 m (1 m either side of where the corpus frame stands) while it pans
30 degrees (15 either side), one step per frame, over N frames (default 24). The geometry is
static: every frame is a view of every other. Frame n is written as <outdir>/<scene>.<nnnn>.exr
with its camera sidecar <scene>.<nnnn>.camera.json, the corpus's passes (Combined, Depth, Normal,
roughness AOV, glossy passes, IndexOB), at W pixels across (default 480, the corpus's 480x270).
Every EVERY-th frame (default 4, from frame 0) is a scored frame, rendered with the corpus's samples
for the scene (its glossy passes are the reference, /work/shared/docs/cycles-references.md); the
others only serve as views and take SSRCL_MOVE_SAMPLES samples (default 64).
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "corpus"))
import bpy  # noqa: E402
import make_corpus  # noqa: E402  (its scene builders and render settings)
from mathutils import Euler, Vector  # noqa: E402
from scene_common import render_and_write  # noqa: E402
from script_args import script_args, take_option  # noqa: E402

TRUCK_M = 2.0
PAN_DEGREES = 30.0


def main():
    args = script_args()
    frames = take_option(args, "--frames", 24)
    scored = take_option(args, "--scored", 4)
    width = take_option(args, "--width", 480)
    if not 1 <= len(args) <= 2 or (len(args) == 2 and args[1] not in make_corpus.SCENE_BY_NAME) \
            or frames < 2 or scored < 1 or width < 16:
        print("usage: blender -b --factory-startup --python make_camera_move.py -- <outdir> [<scene>] "
              "[--frames N>=2] [--scored EVERY>=1] [--width W>=16]\nscenes: %s" % " ".join(make_corpus.SCENE_BY_NAME),
              file=sys.stderr)
        sys.exit(2)
    outdir = os.path.abspath(args[0])
    name = args[1] if len(args) == 2 else "interior_room"
    os.makedirs(outdir, exist_ok=True)
    spec = make_corpus.SCENE_BY_NAME[name]
    bpy.ops.wm.read_factory_settings(use_empty=False)
    scene = bpy.context.scene
    make_corpus.reset_scene()
    spec["build"](scene)
    cam = scene.camera
    start = cam.location.copy()
    heading = cam.rotation_euler.copy()
    # Sideways: the camera's own x axis, kept horizontal.
    right = cam.matrix_world.to_quaternion() @ Vector((1.0, 0.0, 0.0))
    right = Vector((right.x, right.y, 0.0)).normalized()
    view_samples = int(os.environ.get("SSRCL_MOVE_SAMPLES", 64))
    make_corpus.configure_corpus_render(scene, view_samples)
    scene.render.resolution_y = round(scene.render.resolution_y * width / scene.render.resolution_x)
    scene.render.resolution_x = width
    for n in range(frames):
        s = n / (frames - 1) - 0.5  # -0.5 .. 0.5 over the move
        cam.location = start + right * (TRUCK_M * s)
        turn = Euler((0.0, 0.0, math.radians(-PAN_DEGREES * s)), 'XYZ')
        rotation = heading.to_matrix()
        rotation.rotate(turn)
        cam.rotation_euler = rotation.to_euler()
        scene.cycles.samples = spec["samples"] if n % scored == 0 else view_samples
        bpy.context.view_layer.update()
        render_and_write(scene, outdir, "%s.%04d" % (name, n))


if __name__ == "__main__":
    main()
