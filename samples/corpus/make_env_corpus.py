"""Build and render the environment-fill corpus (issue 13 item 4): corpus scenes lit by an HDRI.

    blender -b --factory-startup --python-exit-code 1 --python samples/corpus/make_env_corpus.py \
        -- <outdir> [scene names...]

Writes <outdir>/sky.exr (a synthetic 512x256 equirectangular HDR, half float: sky gradient, sun
disc, coloured blocks on the horizon; no download needed), then for each scene builds one of
make_corpus.py's scenes, replaces its world with that HDR through an Environment Texture node
with the default vector (Blender's world mapping, the one `ssrcl --environment` assumes), this
time visible to glossy rays, and renders it as make_corpus.py does (<name>.exr, <name>.camera.json).
<outdir>/corpus.json lists the scenes for bench/score_corpus.cpp; the committed set lives in
samples/corpus/environment/. EEVEE renders of the same scenes with its world probe:
render_eevee.py -- <outdir> env_plaza ... (it keeps these scenes' world for glossy rays).

SSRCL_CORPUS_SAMPLES / SSRCL_CORPUS_SEED / SSRCL_CORPUS_PNG as in make_corpus.py.
"""
import math
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import make_corpus  # noqa: E402  (also puts samples/blender on sys.path)
from script_args import outdir_and_names, script_args  # noqa: E402

ENV_WIDTH, ENV_HEIGHT = 512, 256
# The HDR the scenes use; main() points it at the one it writes. render_eevee.py uses the default.
environment_path = os.path.join(HERE, "environment", "sky.exr")


def sky_radiance(width, height):
    """Equirectangular RGB, rows top (zenith) to bottom, in Blender's mapping: column u covers
    azimuth phi = pi (1 - 2u) measured from +X towards +Y (u = 0.5 looks along +X, u = 0.25
    along +Y), row v covers elevation pi (0.5 - v)."""
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    phi = np.pi * (1.0 - 2.0 * u)[None, :]
    elev = (np.pi * (0.5 - v))[:, None]
    sky_t = np.clip(np.sin(elev), 0.0, 1.0)
    horizon, zenith, ground = np.array([1.1, 0.95, 0.8]), np.array([0.25, 0.45, 1.0]), np.array([0.16, 0.13, 0.1])
    rgb = np.where((elev >= 0)[..., None],
                   horizon + (zenith - horizon) * np.sqrt(sky_t)[..., None],
                   np.broadcast_to(ground, (height, 1, 3)))
    rgb = np.broadcast_to(rgb, (height, width, 3)).copy()
    # Coloured blocks standing on the horizon, so a wrong azimuth or a flipped image shows.
    blocks = [(-150, 25, 14, (1.2, 0.15, 0.1)), (-60, 18, 9, (0.1, 0.9, 0.2)),
              (20, 30, 20, (0.15, 0.3, 1.4)), (95, 14, 6, (1.3, 1.0, 0.1)), (160, 20, 12, (1.0, 0.1, 0.9))]
    deg_phi, deg_elev = np.degrees(phi), np.degrees(elev)
    for centre, width_deg, height_deg, colour in blocks:
        dphi = (deg_phi - centre + 180.0) % 360.0 - 180.0
        mask = (np.abs(dphi) < width_deg / 2) & (deg_elev >= -1.0) & (deg_elev < height_deg)
        rgb[mask] = colour
    # Sun disc (3 degrees across) at azimuth 120 (behind-left of a camera looking down +Y),
    # elevation 35: a bright, small feature rough lobes must blur, not point-sample.
    sun_dir = np.array([math.cos(math.radians(35)) * math.cos(math.radians(120)),
                        math.cos(math.radians(35)) * math.sin(math.radians(120)), math.sin(math.radians(35))])
    dirs = np.stack([np.cos(elev) * np.cos(phi), np.cos(elev) * np.sin(phi),
                     np.broadcast_to(np.sin(elev), (height, width))], axis=-1)
    rgb[dirs @ sun_dir > math.cos(math.radians(1.5))] = (60.0, 55.0, 45.0)
    return rgb.astype(np.float32)


def write_sky(path):
    rgb = sky_radiance(ENV_WIDTH, ENV_HEIGHT)
    img = bpy.data.images.new("sky", ENV_WIDTH, ENV_HEIGHT, alpha=True, float_buffer=True)
    rgba = np.ones((ENV_HEIGHT, ENV_WIDTH, 4), np.float32)
    rgba[..., :3] = rgb[::-1]  # Blender's pixel rows run bottom to top
    img.pixels.foreach_set(rgba.ravel())
    settings = bpy.context.scene.render.image_settings  # save_render honours these: half RGB, ZIP
    settings.file_format, settings.color_mode = 'OPEN_EXR', 'RGB'
    settings.color_depth, settings.exr_codec = '16', 'ZIP'
    img.save_render(path, scene=bpy.context.scene)
    bpy.data.images.remove(img)


def environment_world(scene, rotation_z=0.0):
    """World = Environment Texture of environment_path, visible to every ray. Default vector, or
    with `rotation_z` degrees a Mapping node (Rotation Z) on Generated coordinates: what
    `ssrcl --environment-rotation` reproduces."""
    world = bpy.data.worlds.new("HDRI")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    tex = nodes.new("ShaderNodeTexEnvironment")
    tex.image = bpy.data.images.load(environment_path, check_existing=True)
    links.new(tex.outputs["Color"], nodes["Background"].inputs["Color"])
    if rotation_z:
        mapping = nodes.new("ShaderNodeMapping")
        mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(rotation_z))
        links.new(nodes.new("ShaderNodeTexCoord").outputs["Generated"], mapping.inputs["Vector"])
        links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world


def lit_by_environment(build):
    def builder(scene):
        build(scene)
        environment_world(scene)
    return builder


SCENES = [
    dict(name="env_plaza", split="holdout", units="m", samples=128,
         build=lit_by_environment(make_corpus.build_exterior_plaza), world_probe=True,
         description="exterior_plaza lit by the HDRI: rough ground (0.08-0.45) reflecting "
                     "buildings on screen and sky and horizon blocks off screen."),
    dict(name="env_metal_props", split="holdout", units="m", samples=128,
         build=lit_by_environment(make_corpus.build_metal_props), world_probe=True,
         description="metal_props lit by the HDRI: glossy floor (0.2) and metal props (0.1) "
                     "reflecting the open sky above and behind the camera."),
    dict(name="env_tiles", split="holdout", units="m", samples=128,
         build=lit_by_environment(make_corpus.build_mirror_glossy_tiles), world_probe=True,
         description="mirror_glossy_tiles lit by the HDRI: mirror (0.02) and glossy (0.35) "
                     "tiles reflecting a wall and the sky."),
]
SCENE_BY_NAME = {s["name"]: s for s in SCENES}


def build_mapping_check(rotation_z):
    """Nothing but the world, seen through a 16 mm lens turned to azimuth 60 and tilted up 10
    degrees: horizon blocks and the sun in view, so tests/test_environment.cpp can check the
    documented mapping (and rotation) against what Cycles shows."""
    def builder(scene):
        environment_world(scene, rotation_z)
        target = (math.cos(math.radians(60)), math.sin(math.radians(60)), math.tan(math.radians(10)))
        make_corpus.camera(scene, (0.0, 0.0, 0.0), target, 16.0)
    return builder


# Not scored (no reflector): renders of the world alone, the mapping's check against Blender.
MAPPING_CHECKS = [dict(name="env_mapping", samples=16, build=build_mapping_check(0.0)),
                  dict(name="env_mapping_rot30", samples=16, build=build_mapping_check(30.0))]


def main():
    global environment_path
    args = script_args()
    outdir, names = outdir_and_names(args, SCENE_BY_NAME,
                                     "usage: ... make_env_corpus.py -- <outdir> [scene names...]")
    environment_path = os.path.join(outdir, "sky.exr")
    write_sky(environment_path)
    make_corpus.write_manifest(outdir, SCENES)
    for name in names:
        make_corpus.render_scene(SCENE_BY_NAME[name], outdir)
    if not args[1:]:
        for spec in MAPPING_CHECKS:
            make_corpus.render_scene(spec, outdir)


if __name__ == "__main__":
    main()
