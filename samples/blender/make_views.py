"""Render auxiliary views of corpus scenes for `ssrcl trace --view` (issue 16).

    blender -b --factory-startup --python-exit-code 1 --python samples/blender/make_views.py \
        -- <outdir> <scene> [<scene> ...] [--views reverse,wide,cube]

For each scene of samples/corpus/make_corpus.py (built by its own builder), renders from the
scene camera's position:
  reverse  the opposite way (heading turned 180 degrees, the same pitch and lens): what lies
           behind the camera, which floors and walls in front of it reflect
  wide     the same direction with a lens 0.4 times as long (about 2.5 times the field of view):
           what lies beside and above the frame
  cube     six 90-degree square views along +-X, +-Y, +-Z (a probe from the camera position)
each as <outdir>/<scene>.<view>.exr with its camera sidecar <scene>.<view>.camera.json, the same
passes as the corpus (Combined, Depth, Normal, roughness AOV; 480x270, or 270x270 for the cube).
Only the view's G-buffer and colour are used, so it takes few samples: SSRCL_VIEW_SAMPLES,
default 64 (a Combined noisier than the corpus's 256-768, prefiltered by the trace anyway).
"""
import math
import os
import sys

from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "corpus"))
import bpy  # noqa: E402
import make_corpus  # noqa: E402  (its scene builders and render settings)
from scene_common import render_and_write  # noqa: E402
from script_args import script_args, take_option  # noqa: E402

CUBE = {"px": (1, 0, 0), "nx": (-1, 0, 0), "py": (0, 1, 0), "ny": (0, -1, 0), "pz": (0, 0, 1), "nz": (0, 0, -1)}


def aim(camera, direction):
    # Straight up or down has no heading: keep +Y as the image's up there.
    up = 'Y' if abs(direction.z) < 0.999 else 'Z'
    camera.rotation_euler = direction.to_track_quat('-Z', up).to_euler()


def view_cameras(scene, views):
    """(name, set-up function) per view; each function poses the scene camera."""
    cam = scene.camera
    forward = cam.matrix_world.to_quaternion() @ Vector((0.0, 0.0, -1.0))
    lens = cam.data.lens
    out = []
    if "reverse" in views:
        def reverse():
            aim(cam, Vector((-forward.x, -forward.y, forward.z)))
            cam.data.lens = lens
        out.append(("reverse", reverse))
    if "wide" in views:
        def wide():
            aim(cam, forward)
            cam.data.lens = 0.4 * lens
        out.append(("wide", wide))
    if "cube" in views:
        for name, d in CUBE.items():
            def face(d=d):
                aim(cam, Vector(d))
                # 90 degrees across a square image: 36 mm sensor at an 18 mm lens.
                cam.data.sensor_fit = 'HORIZONTAL'
                cam.data.lens = 18.0 * cam.data.sensor_width / 36.0
            out.append(("cube-" + name, face))
    return out


def render_views(name, outdir, views):
    spec = make_corpus.SCENE_BY_NAME[name]
    bpy.ops.wm.read_factory_settings(use_empty=False)
    scene = bpy.context.scene
    make_corpus.reset_scene()
    spec["build"](scene)
    make_corpus.configure_corpus_render(scene, int(os.environ.get("SSRCL_VIEW_SAMPLES", 64)))
    for view, pose in view_cameras(scene, views):
        pose()
        square = view.startswith("cube-")
        scene.render.resolution_x = 270 if square else 480
        scene.render.resolution_y = 270
        bpy.context.view_layer.update()
        render_and_write(scene, outdir, "%s.%s" % (name, view))


def main():
    args = script_args()
    views = take_option(args, "--views", ["reverse", "wide"], lambda v: v.split(","))
    unknown = [n for n in args[1:] if n not in make_corpus.SCENE_BY_NAME] + \
              [v for v in views if v not in ("reverse", "wide", "cube")]
    if len(args) < 2 or unknown:
        print("usage: blender -b --factory-startup --python make_views.py -- <outdir> <scene>... "
              "[--views reverse,wide,cube]\nunknown: %s\nscenes: %s"
              % (" ".join(unknown), " ".join(make_corpus.SCENE_BY_NAME)), file=sys.stderr)
        sys.exit(2)
    outdir = os.path.abspath(args[0])
    os.makedirs(outdir, exist_ok=True)
    for name in args[1:]:
        render_views(name, outdir, views)


if __name__ == "__main__":
    main()
