"""Render the shot corpus: 12-frame moves through six real-asset scenes (make_real_corpus.py),
Cycles references of every frame, a second-seed Cycles render of the first frame (the references'
noise floor), each frame's back-face depth pass and EEVEE (legacy SSR, the real-time peer) of the
same frames.

    blender -b --factory-startup --python-exit-code 1 --python samples/real/make_shots.py \
        -- [--back-faces] <outdir> [shot names...]
    xvfb-run -a -s "-screen 0 1280x1024x24" blender -b --factory-startup --python-exit-code 1 \
        --python samples/real/make_shots.py -- --eevee <outdir> [shot names...]

scripts/render-shots.sh runs all three (out/shots by default; never committed). Writes, per shot:
  <outdir>/<shot>/<shot>.NNNN.exr + .camera.json   Cycles, frames 1..FRAMES, seed = frame number
  <outdir>/<shot>/seed2/<shot>.0001.exr            frame 1 again, another seed (noise floor)
  <outdir>/<shot>/back/<shot>.NNNN.exr             the back-face depth of every frame (ViewLayer.Depth.Z,
                                                   what `ssrcl batch --back-depth-file` reads)
  <outdir>/<shot>/eevee/<shot>.NNNN.exr            EEVEE Specular Light + Color of every frame
  <outdir>/shots.json                              the shots (scene, move, frames, samples)

Each frame has its own seed: the references' noise is independent from frame to frame, as it is
between two renders of one frame, so the second seed of frame 1 measures the noise that the
temporal metric sees in the references (scored by bench/score_shots). A rerun into the same
outdir skips the frames already written, so an interrupted render resumes.

Shots (camera moves small enough that every frame sees most of its neighbours' surfaces):
  living_truck  living_room (interior), camera trucks sideways 4 cm a frame
  deck_pan      wet_deck (exterior, HDRI), camera pans 0.5 degree a frame about the vertical
  tea_slide     tea_table, camera still, the glazed tea set slides 1.2 cm a frame along x

Environment: SSRCL_SHOT_SAMPLES (Cycles samples, default 64), SSRCL_SHOT_FRAMES (default 12),
SSRCL_SHOT_WIDTH / SSRCL_SHOT_HEIGHT (default 240 x 135), SSRCL_EEVEE_SAMPLES (TAA, default 32).
"""
import json
import math
import os
import shutil
import sys
import time

import bpy
from mathutils import Matrix, Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_real_corpus as real  # noqa: E402  (scenes, render settings, compact_exr)
import render_eevee  # noqa: E402  (configure_eevee; make_real_corpus put samples/corpus on the path)
from script_args import outdir_and_names, script_args  # noqa: E402  (samples/blender: on the path too)
from scene_common import render_and_write  # noqa: E402
from ssrcl_addon import back_faces  # noqa: E402

FRAMES = int(os.environ.get("SSRCL_SHOT_FRAMES", 12))
SAMPLES = int(os.environ.get("SSRCL_SHOT_SAMPLES", 64))
WIDTH = int(os.environ.get("SSRCL_SHOT_WIDTH", 240))
HEIGHT = int(os.environ.get("SSRCL_SHOT_HEIGHT", 135))
SECOND_SEED = 1000  # frame 1's second render; frames use seeds 1..FRAMES
START = {}  # object name -> its matrix_world before the move (build)


def truck(scene, frame, step=0.04):
    """Camera moves sideways (its right vector, level) `step` m a frame, centred on the scene's."""
    cam = scene.camera
    right = cam.matrix_world.to_quaternion() @ Vector((1.0, 0.0, 0.0))
    right = Vector((right.x, right.y, 0.0)).normalized()
    cam.location = START[cam.name].to_translation() + right * (step * (frame - (FRAMES + 1) / 2))


def pan(scene, frame, step_deg=0.5):
    """Camera turns about the world vertical through its own position, `step_deg` a frame."""
    cam = scene.camera
    turn = Matrix.Rotation(math.radians(step_deg * (frame - (FRAMES + 1) / 2)), 4, 'Z')
    start = START[cam.name]
    loc = start.to_translation()
    cam.matrix_world = Matrix.Translation(loc) @ turn @ Matrix.Translation(-loc) @ start


def dolly(scene, frame, step=0.06):
    """Camera moves forward (its view direction, level) `step` m a frame, centred on the scene's."""
    cam = scene.camera
    forward = cam.matrix_world.to_quaternion() @ Vector((0.0, 0.0, -1.0))
    forward = Vector((forward.x, forward.y, 0.0)).normalized()
    cam.location = START[cam.name].to_translation() + forward * (step * (frame - (FRAMES + 1) / 2))


def slide(scene, frame, step=0.012):
    """The glossy props (pass_index 2: the tea set) slide along x, `step` m a frame."""
    for o in scene.objects:
        if o.pass_index == real.PROP and o.parent is None:
            o.location = START[o.name].to_translation() + Vector((step * (frame - 1), 0.0, 0.0))


SHOTS = [
    dict(name="living_truck", scene="living_room", move=truck, kind="interior, camera truck"),
    dict(name="deck_pan", scene="wet_deck", move=pan, kind="exterior HDRI, camera pan"),
    dict(name="tea_slide", scene="tea_table", move=slide, kind="moving object, camera still"),
    # Held out: chosen after the defaults, to check them on moves and speeds they were not set on.
    dict(name="lobby_truck", scene="concrete_lobby", move=lambda s, f: truck(s, f, 0.10),
         kind="interior, fast camera truck (held out)"),
    dict(name="riverbed_dolly", scene="wet_riverbed", move=dolly, kind="exterior HDRI, camera dolly (held out)"),
    dict(name="workshop_pan", scene="metal_workshop", move=lambda s, f: pan(s, f, 1.5),
         kind="interior, fast camera pan (held out)"),
]
SHOT_BY_NAME = {s["name"]: s for s in SHOTS}


def build(shot, outdir, samples):
    spec = real.SCENE_BY_NAME[shot["scene"]]
    scene = real.build(spec, outdir, samples)
    r = scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = WIDTH, HEIGHT, 100
    START.clear()
    for o in scene.objects:
        START[o.name] = o.matrix_world.copy()
    return spec, scene


def place(shot, scene, frame):
    shot["move"](scene, frame)
    bpy.context.view_layer.update()


def render_cycles(shot, outdir):
    d = os.path.join(outdir, shot["name"])
    os.makedirs(os.path.join(d, "seed2"), exist_ok=True)
    spec, scene = build(shot, d, SAMPLES)
    for frame in list(range(1, FRAMES + 1)) + [0]:
        second = frame == 0  # the last render: frame 1 with another seed
        place(shot, scene, 1 if second else frame)
        scene.cycles.seed = SECOND_SEED if second else frame
        stem = "%s.%04d" % (shot["name"], 1 if second else frame)
        frame_dir = os.path.join(d, "seed2") if second else d
        if os.path.exists(os.path.join(frame_dir, stem + ".camera.json")):
            continue  # written by an earlier, interrupted run (the camera is written last)
        start = time.perf_counter()
        exr = render_and_write(scene, frame_dir, stem)[0]
        if shutil.which("oiiotool"):  # halves the files; they stay out of git either way
            real.compact_exr(exr)
        print("SHOT %s %s: %d samples, %.1f s" % (shot["name"], os.path.relpath(exr, outdir),
                                                 SAMPLES, time.perf_counter() - start), flush=True)
    return spec


def render_each_frame(shot, scene, d, label):
    """Renders frames 1..FRAMES of the shot into d/<shot>.NNNN.exr, each at its own seed (as the
    references), skipping those an earlier, interrupted run wrote."""
    for frame in range(1, FRAMES + 1):
        place(shot, scene, frame)
        scene.cycles.seed = frame
        path = os.path.join(d, "%s.%04d.exr" % (shot["name"], frame))
        if os.path.exists(path):
            continue
        scene.render.filepath = path + ".tmp.exr"  # renamed once whole: a killed write is not skipped
        start = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        os.replace(scene.render.filepath, path)
        print("%s %s %04d: %.1f s" % (label, shot["name"], frame, time.perf_counter() - start), flush=True)


def render_back_faces(shot, outdir):
    """Each frame's back-face depth as render_back_faces.py renders a corpus scene's: the file's only
    layer is the back-face one (ViewLayer.Depth.Z), one sample at the frame's own seed, so its Z
    comes from the sub-pixel position of the reference's first sample."""
    d = os.path.join(outdir, shot["name"], "back")
    os.makedirs(d, exist_ok=True)
    _, scene = build(shot, d, back_faces.SAMPLES)
    back_faces.make_back_only_render(scene, real.LAYER)
    render_each_frame(shot, scene, d, "BACK")


def render_peer(shot, outdir):
    d = os.path.join(outdir, shot["name"], "eevee")
    os.makedirs(d, exist_ok=True)
    spec, scene = build(shot, d, 1)
    render_eevee.configure_eevee(scene, world_probe="environment" in spec)
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    scene.eevee.taa_render_samples = int(os.environ.get("SSRCL_EEVEE_SAMPLES", 32))
    layer = scene.view_layers[real.LAYER]
    layer.use_pass_glossy_color = True  # Light x Color = the glossy-pass form (make_real_corpus)
    layer.use_pass_normal = False
    while layer.aovs:
        layer.active_aov_index = 0
        bpy.ops.scene.view_layer_remove_aov()
    scene.render.use_file_extension = False
    render_each_frame(shot, scene, d, "EEVEE")


def write_manifest(outdir, shot):
    """Adds or replaces the shot's entry in <outdir>/shots.json (shots may differ in samples)."""
    path = os.path.join(outdir, "shots.json")
    entries = json.load(open(path))["shots"] if os.path.exists(path) else []
    entry = dict(name=shot["name"], scene=shot["scene"], kind=shot["kind"], frames=FRAMES,
                 samples=SAMPLES, width=WIDTH, height=HEIGHT,
                 environment=real.SCENE_BY_NAME[shot["scene"]].get("environment"))
    entries = [e for e in entries if e["name"] != shot["name"]] + [entry]
    entries.sort(key=lambda e: [s["name"] for s in SHOTS].index(e["name"]))
    with open(path, "w") as f:
        json.dump({"shots": entries}, f, indent=2)
        f.write("\n")


def main():
    args = script_args()
    mode = args.pop(0) if args and args[0] in ("--eevee", "--back-faces") else None
    outdir, names = outdir_and_names(args, SHOT_BY_NAME,
                                     "usage: ... make_shots.py -- [--eevee|--back-faces] <outdir> [shots...]",
                                     kind="shot")
    shots = [SHOT_BY_NAME[n] for n in names]
    for shot in shots:
        if mode == "--eevee":
            render_peer(shot, outdir)
        elif mode == "--back-faces":
            render_back_faces(shot, outdir)
        else:
            render_cycles(shot, outdir)
            write_manifest(outdir, shot)


if __name__ == "__main__":
    main()
