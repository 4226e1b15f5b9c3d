"""Render the back-face depth pass of corpus scenes into separate small files (the scene EXRs stay
as they are): <outdir>/<name>.back.exr, float Z only (ViewLayer.Depth.Z, what
`ssrcl trace --back-depth-file` reads by default), ZIP, the scene's own camera and sample-0 jitter.

    blender -b --factory-startup --python-exit-code 1 --python samples/blender/render_back_faces.py \
        -- corpus|real <outdir> [scene names...]

corpus: samples/corpus/make_corpus.py's scenes; real: samples/real/make_real_corpus.py's (needs
its assets). No names renders every scene of that corpus; each takes a few seconds.
"""
import os
import sys
import tempfile
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "corpus"))
sys.path.insert(0, os.path.join(HERE, "..", "real"))
from ssrcl_addon import back_faces  # noqa: E402
from script_args import outdir_and_names, script_args  # noqa: E402


def build_scene(corpus, spec, scratch):
    if corpus == "real":
        import make_real_corpus
        return make_real_corpus.build(spec, scratch, back_faces.SAMPLES)
    import make_corpus
    bpy.ops.wm.read_factory_settings(use_empty=False)
    scene = bpy.context.scene
    make_corpus.reset_scene()
    spec["build"](scene)
    make_corpus.configure_corpus_render(scene, back_faces.SAMPLES)
    scene.cycles.seed = 0
    return scene


def render_back(corpus, spec, outdir, scratch):
    scene = build_scene(corpus, spec, scratch)
    back_faces.make_back_only_render(scene)
    path = os.path.join(outdir, spec["name"] + ".back.exr")
    scene.render.filepath = path
    start = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print("BACK %s: %.1f s, %d bytes" % (spec["name"], time.perf_counter() - start, os.path.getsize(path)))


def for_each_corpus_scene(script_name, action):
    """Runs action(corpus, spec, outdir, scratch) on the scenes the command line names (`corpus|real
    <outdir> [scene names...]`, every scene of that corpus without names); exits 2 with the usage
    on a bad command line."""
    args = script_args()
    usage = ("usage: blender -b --factory-startup --python %s -- corpus|real <outdir> "
             "[scene names...]" % script_name)
    if len(args) < 2 or args[0] not in ("corpus", "real"):
        print(usage, file=sys.stderr)
        sys.exit(2)
    corpus = args[0]
    module = __import__("make_real_corpus" if corpus == "real" else "make_corpus")
    outdir, names = outdir_and_names(args[1:], module.SCENE_BY_NAME, usage)
    with tempfile.TemporaryDirectory() as scratch:  # what a real scene's build writes (its HDRI)
        for name in names:
            action(corpus, module.SCENE_BY_NAME[name], outdir, scratch)


def main():
    for_each_corpus_scene("render_back_faces.py", render_back)


if __name__ == "__main__":
    main()
