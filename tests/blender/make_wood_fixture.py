"""Builds tests/data/wood_floor_scene.blend, the add-on test's real-asset scene (issue 24).

    blender -b --factory-startup --python-exit-code 1 --python tests/blender/make_wood_fixture.py \
        -- [OUT.blend]

A room corner on Poly Haven's wood_floor (its diff, nor_gl and arm maps: base colour, normal map,
roughness from the ARM map's G, times 0.6 for a waxed floor; dielectric) with two Poly Haven glTF
props standing on it (painted_wooden_stool, painted_wooden_cabinet_02, their own materials), a
plaster wall and an area light, as samples/real/make_real_corpus.py builds its scenes (the same
helpers). No AOVs: the add-on's Set Up adds them. Sources and licences: samples/real/sources.py
(CC0); the assets must be fetched first (samples/real/README.md).

To stay small in git every image is scaled down to at most 128 pixels and packed as JPEG (the
maps lose detail, not their kind: the floor keeps its grain, normal map and varying roughness),
and the .blend is saved compressed. The test renders it itself at 192x108.
"""
import os
import sys
import tempfile

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(ROOT, "samples", "real"))
import make_real_corpus as real  # noqa: E402
from make_real_corpus import make_corpus  # noqa: E402

IMAGE_SIZE = 128
DEFAULT_OUT = os.path.join(ROOT, "tests", "data", "wood_floor_scene.blend")


def build(scene):
    real.reset_scene()
    make_corpus.black_world(scene)
    real.floor_plane("WoodFloor", real.pbr("WoodFloor", "wood_floor", (3, 3), rough_scale=0.6),
                     (6.0, 6.0), (0.0, 1.5))
    real.walls(real.pbr("Plaster", "painted_plaster_wall", (3, 1.4)), -3.0, 3.0, -1.5, 3.0, 2.6,
               skip=("front", "left"))
    real.model("models/painted_wooden_stool_1k.gltf", (-0.5, 1.2, 0.0), 20.0)
    real.model("models/painted_wooden_cabinet_02_1k.gltf", (0.9, 2.5, 0.0), 180.0)
    make_corpus.plane((-0.6, 2.98, 1.7), (1.2, 0.5), make_corpus.emission(
        "Lamp", (1.0, 0.85, 0.65), 6.0), rot=(90, 0, 0))
    make_corpus.area_light(scene, (0.0, 0.5, 2.5), 2.0, 400.0)
    make_corpus.camera(scene, (0.3, -1.3, 1.2), (0.0, 1.6, 0.3), 30.0)
    scene.render.engine = 'CYCLES'
    scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise


def shrink_and_pack(size, workdir):
    """Every image at most `size` pixels wide and high, written as JPEG into `workdir`, read back
    and packed (packing the scaled buffer itself would store a PNG, several times larger)."""
    for image in list(bpy.data.images):
        if image.source != 'FILE':
            continue
        w, h = image.size
        scale = min(1.0, size / max(w, h))
        image.scale(max(1, int(w * scale)), max(1, int(h * scale)))
        path = os.path.join(workdir, bpy.path.clean_name(image.name) + ".jpg")
        image.file_format = 'JPEG'
        image.filepath_raw = path
        image.save()
        image.filepath = path
        image.reload()
        image.pack()


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    out = os.path.abspath(args[0] if args else DEFAULT_OUT)
    bpy.ops.wm.read_factory_settings(use_empty=False)
    scene = bpy.context.scene
    build(scene)
    with tempfile.TemporaryDirectory() as workdir:
        shrink_and_pack(IMAGE_SIZE, workdir)
    bpy.ops.outliner.orphans_purge(do_recursive=True)
    bpy.ops.wm.save_as_mainfile(filepath=out, compress=True)
    print("wrote %s, %d bytes" % (out, os.path.getsize(out)))


main()
