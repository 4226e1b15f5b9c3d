"""Render the corpus scenes with legacy EEVEE's screen-space reflections (the peer, issue 11).

    xvfb-run -a -s "-screen 0 1280x1024x24" blender -b --factory-startup --python-exit-code 1 \
        --python samples/corpus/render_eevee.py -- <outdir> [scene names...]

Builds each scene with make_corpus.py's builders (one source of truth), switches to EEVEE with
SSR at full quality (see /work/shared/docs/eevee-peer.md) and writes <outdir>/<name>.eevee.exr
holding only the Specular Light pass (ViewLayer.GlossDir.{R,G,B}, half, ZIP): reflected radiance
with the split-sum specular colour divided out. World black for glossy rays (a Light Path
"Is Glossy Ray" mix, so EEVEE's world probe adds no environment fill), lamps specular_factor 0,
so SSR is the only thing lighting any specular.

Environment: SSRCL_EEVEE_THICKNESS (ssr_thickness in scene units, default 0.2 = EEVEE's
default), SSRCL_EEVEE_SAMPLES (taa_render_samples, default 16), SSRCL_EEVEE_NO_SSR=1 (SSR off:
the pass must then be 0, a check that nothing but SSR lights the specular).
EEVEE always writes Combined as well (use_pass_combined = False is not honoured).
"""
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_corpus  # noqa: E402  (also puts samples/blender on sys.path)
import make_env_corpus  # noqa: E402
from scene_common import HEIGHT, WIDTH, reset_scene  # noqa: E402
from script_args import outdir_and_names, script_args  # noqa: E402


def black_world_for_glossy(scene):
    """Mix the world's output with black for glossy rays (EEVEE's world probe is rendered
    with the same tree, so its reflection probe becomes black)."""
    world = scene.world
    nodes, links = world.node_tree.nodes, world.node_tree.links
    out = nodes["World Output"]
    surface = out.inputs["Surface"]
    if not surface.links:
        return
    original = surface.links[0].from_socket
    black = nodes.new("ShaderNodeBackground")
    black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    black.inputs["Strength"].default_value = 0.0
    path = nodes.new("ShaderNodeLightPath")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(path.outputs["Is Glossy Ray"], mix.inputs["Fac"])
    links.new(original, mix.inputs[1])
    links.new(black.outputs["Background"], mix.inputs[2])
    links.new(mix.outputs["Shader"], surface)


# Environment-fill scenes (make_env_corpus.py) keep their world for glossy rays: EEVEE's world
# probe filling what SSR misses is the peer of `ssrcl --environment`.
SCENE_BY_NAME = {**make_corpus.SCENE_BY_NAME, **make_env_corpus.SCENE_BY_NAME}


def configure_eevee(scene, world_probe=False):
    scene.render.engine = 'BLENDER_EEVEE'
    ee = scene.eevee
    ee.use_ssr = not os.environ.get("SSRCL_EEVEE_NO_SSR")  # check: without SSR the pass is 0
    ee.use_ssr_refraction = False
    ee.use_ssr_halfres = False
    ee.ssr_quality = 1.0
    ee.ssr_max_roughness = 1.0
    ee.ssr_thickness = float(os.environ.get("SSRCL_EEVEE_THICKNESS", 0.2))
    ee.taa_render_samples = int(os.environ.get("SSRCL_EEVEE_SAMPLES", 16))
    for light in bpy.data.lights:
        light.specular_factor = 0.0
    if not world_probe:
        black_world_for_glossy(scene)

    r = scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = WIDTH, HEIGHT, 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.film_transparent = False
    r.use_compositing = False
    r.use_sequencer = False
    for flag in ("date", "time", "render_time", "memory", "hostname", "filename", "frame",
                 "frame_range", "camera", "lens", "scene", "marker", "note", "sequencer_strip"):
        setattr(r, "use_stamp_" + flag, False)
    layer = scene.view_layers[make_corpus.LAYER]
    layer.use_pass_combined = False
    layer.use_pass_z = False
    layer.use_pass_glossy_direct = True  # EEVEE "Specular Light", stored as GlossDir
    s = r.image_settings
    s.file_format = 'OPEN_EXR_MULTILAYER'
    s.color_depth = '16'
    s.exr_codec = 'ZIP'
    s.use_preview = False


def main():
    outdir, names = outdir_and_names(script_args(), SCENE_BY_NAME,
                                     "usage: ... render_eevee.py -- <outdir> [scene names...]",
                                     default=make_corpus.SCENE_BY_NAME)
    for name in names:
        spec = SCENE_BY_NAME[name]
        bpy.ops.wm.read_factory_settings(use_empty=False)
        scene = bpy.context.scene
        reset_scene()
        spec["build"](scene)
        configure_eevee(scene, spec.get("world_probe", False))
        path = os.path.join(outdir, name + ".eevee.exr")
        scene.render.filepath = path
        scene.render.use_file_extension = False
        start = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        print("EEVEE %s: %.1f s, %d bytes" % (name, time.perf_counter() - start,
                                             os.path.getsize(path)))


if __name__ == "__main__":
    main()
