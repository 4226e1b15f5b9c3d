"""Where every asset of the real-asset corpus comes from, and how to get it (issue 24).

    python3 samples/real/sources.py <mirror dir> [<assets dir>]

<mirror dir> holds bare git copies of the repositories below, one per repository, named
<owner>+<name>/repo (`git clone --bare https://github.com/<owner>/<name> <owner>+<name>/repo`
makes one). Every file is read at the recorded commit with `git cat-file blob` and written to
<assets dir>/<local name> (default samples/real/assets, which git ignores: the raw assets are
not committed, only the renders made from them). A blob the snapshot lacks is an error naming
the repository, commit and path.

Licences: the Poly Haven assets are CC0 (https://polyhaven.com/license), whatever repository
carries them; RobotLocomotion's veggies/ and dishes/ models are Toyota Research Institute's,
under the BSD-3-Clause-style licence in veggies/LICENSE and dishes/LICENSE.
"""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_ASSETS = os.path.join(HERE, "assets")

DRAKE = ("RobotLocomotion/models", "4723170e1c8ee8bc59c342bb5c491ab8f263f1fb")
SOCK = ("Snootic/sock-gallery", "0654ab8594876a0e9d671a0d68dabe116a647894")
DREI = ("pmndrs/drei-assets", "456060a26bbeb8fdf79326f224b6d99b8bcce736")
SHAIYON = ("shaiyon/shaiyonV2", "dc42cda9320de5c389dbdf3bde2d5a1f39d769d2")

POLYHAVEN = "CC0 (Poly Haven)"
TRI = "BSD-3-Clause-style (Toyota Research Institute, LICENSE beside the model)"

# (repository, commit), path in the repository, local path under the assets dir, licence.
# glTF models keep their relative layout (textures/...), so the .gltf finds its .bin and images.
_TUTORIAL = "tutorials/models/assets/"
ASSETS = []


def _add(source, path, local, licence):
    ASSETS.append(dict(repo=source[0], commit=source[1], path=path, local=local, licence=licence))


for _model, _maps in (("tea_set_01", "nor_gl diff arm"), ("sofa_03", "nor_gl diff rough"),
                      ("wooden_table_02", "nor_gl diff arm"),
                      ("wooden_bookshelf_worn", "nor_gl diff arm"),
                      ("painted_wooden_cabinet", "nor_gl diff arm"),
                      ("painted_wooden_cabinet_02", "nor_gl diff arm"),
                      ("painted_wooden_stool", "nor_gl diff arm")):
    _add(DRAKE, _TUTORIAL + _model + "_1k.gltf", "models/%s_1k.gltf" % _model, POLYHAVEN)
    _add(DRAKE, _TUTORIAL + _model + ".bin", "models/%s.bin" % _model, POLYHAVEN)
    for _map in _maps.split():
        _ext = "jpg"
        _name = "textures/%s_%s_1k.%s" % (_model, _map, _ext)
        _add(DRAKE, _TUTORIAL + _name, "models/" + _name, POLYHAVEN)
for _map, _ext in (("diff", "jpg"), ("nor_gl", "png"), ("rough", "png")):
    _name = "textures/rosewood_veneer1_%s_1k.%s" % (_map, _ext)
    _add(DRAKE, _TUTORIAL + _name, _name, POLYHAVEN)
_add(DRAKE, "veggies/assets/yellow_bell_pepper_no_stem_low.gltf", "models/bell_pepper.gltf", TRI)
_add(DRAKE, "veggies/assets/yellow_bell_pepper_no_stem_low.bin",
     "models/yellow_bell_pepper_no_stem_low.bin", TRI)
for _map in ("color", "normal", "occlusion_roughness_metallic"):
    _add(DRAKE, "veggies/assets/bell_pepper_no_stem_%s.png" % _map,
         "models/bell_pepper_no_stem_%s.png" % _map, TRI)
_add(DRAKE, "dishes/assets/evo_bowl.gltf", "models/evo_bowl.gltf", TRI)
_add(DRAKE, "dishes/assets/evo_bowl.bin", "models/evo_bowl.bin", TRI)
_add(DRAKE, "dishes/assets/plate_8in.gltf", "models/plate_8in.gltf", TRI)
_add(DRAKE, "dishes/assets/plate_8in.bin", "models/plate_8in.bin", TRI)

for _tex, _maps in (("wood_floor", "diff arm nor_gl"), ("blue_metal_plate", "diff arm nor_gl"),
                    ("painted_plaster_wall", "diff arm nor_gl")):
    _dir = {"wood_floor": "floor", "blue_metal_plate": "lamp", "painted_plaster_wall": "wall"}[_tex]
    for _map in _maps.split():
        _name = "%s_%s_1k.jpg" % (_tex, _map)
        _add(SOCK, "src/assets/textures/%s/%s" % (_dir, _name), "textures/" + _name, POLYHAVEN)

# The snapshot of shaiyonV2 lacks these textures' normal maps: the scenes bump with disp.
for _tex in ("clay_roof_tiles_02", "concrete_layers", "dry_riverbed_rock"):
    for _map, _ext in (("diff", "jpg"), ("disp", "png"), ("rough", "png")):
        _name = "%s_%s_1k.%s" % (_tex, _map, _ext)
        _add(SHAIYON, "public/textures/" + _name, "textures/" + _name, POLYHAVEN)

for _hdri in ("potsdamer_platz", "venice_sunset", "kiara_1_dawn", "studio_small_03"):
    _add(DREI, "hdri/%s_1k.hdr" % _hdri, "hdri/%s_1k.hdr" % _hdri, POLYHAVEN)


def asset_path(local, assets_dir=None):
    """Absolute path of an asset by its local name; a clear error if it was never fetched."""
    path = os.path.join(assets_dir or os.environ.get("SSRCL_REAL_ASSETS", DEFAULT_ASSETS), local)
    if not os.path.exists(path):
        raise FileNotFoundError("%s: missing; run `python3 samples/real/sources.py <mirror dir>` "
                                "first (see samples/real/README.md)" % path)
    return path


def fetch(mirror_dir, assets_dir):
    for a in ASSETS:
        git_dir = os.path.join(mirror_dir, a["repo"].replace("/", "+"), "repo")
        if not os.path.isdir(git_dir):
            raise SystemExit("sources.py: no bare git copy of %s at %s" % (a["repo"], git_dir))
        spec = "%s:%s" % (a["commit"], a["path"])
        out = os.path.join(assets_dir, a["local"])
        os.makedirs(os.path.dirname(out), exist_ok=True)
        blob = subprocess.run(["git", "--git-dir", git_dir, "cat-file", "blob", spec],
                              capture_output=True)
        if blob.returncode != 0:
            raise SystemExit("sources.py: %s %s: %s" % (a["repo"], spec,
                                                        blob.stderr.decode().strip()))
        with open(out, "wb") as f:
            f.write(blob.stdout)
    print("wrote %d assets to %s" % (len(ASSETS), assets_dir))


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        sys.exit(2)
    fetch(os.path.abspath(sys.argv[1]),
          os.path.abspath(sys.argv[2]) if len(sys.argv) == 3 else DEFAULT_ASSETS)
