"""Write the ssrcl camera sidecar JSON for a Blender scene camera.

Standalone:  blender -b scene.blend --python export_camera.py -- out.camera.json
As a module: import export_camera; export_camera.write_camera_json(path, scene)

JSON layout (what ssrcl::loadCameraJson reads):
  "view":       4x4 row-major world->camera (column-vector convention: p_cam = V @ p_world)
  "projection": 4x4 row-major OpenGL clip matrix (camera looks down -Z, NDC z in [-1, 1])
  "width", "height": render size in pixels; "near", "far": clip distances
"""
import json
import os
import sys

import bpy


def _rows(matrix):
    # mathutils indexes matrices by row (M[r][c]) in column-vector convention, so this is row-major.
    # "+ 0.0" turns -0.0 into 0.0 for a tidier file.
    return [[float(matrix[r][c]) + 0.0 for c in range(4)] for r in range(4)]


def camera_dict(scene=None, camera=None):
    scene = scene or bpy.context.scene
    camera = camera or scene.camera
    if camera is None or camera.type != 'CAMERA':
        raise RuntimeError("scene has no camera object")
    if camera.data.type != 'PERSP':
        # ssrcl unprojects with a perspective clip matrix; ortho/panoramic would need other maths.
        raise RuntimeError("only perspective cameras are supported, got %s" % camera.data.type)

    render = scene.render
    scale = render.resolution_percentage / 100.0
    width = int(render.resolution_x * scale)
    height = int(render.resolution_y * scale)

    depsgraph = bpy.context.evaluated_depsgraph_get()
    cam_eval = camera.evaluated_get(depsgraph)
    # calc_matrix_camera goes through the same viewplane code the renderer uses
    # (BKE_camera_params_compute_viewplane): sensor fit, lens shift and pixel aspect are included,
    # and the result is a glFrustum-style matrix built from clip_start/clip_end.
    projection = cam_eval.calc_matrix_camera(
        depsgraph, x=width, y=height,
        scale_x=render.pixel_aspect_x, scale_y=render.pixel_aspect_y)
    # Blender cameras look down local -Z with +Y up, i.e. already the OpenGL eye-space convention.
    # normalized() drops any object scale so the view matrix stays rigid.
    view = cam_eval.matrix_world.normalized().inverted()

    return {
        "view": _rows(view),
        "projection": _rows(projection),
        "width": width,
        "height": height,
        "near": float(cam_eval.data.clip_start),
        "far": float(cam_eval.data.clip_end),
    }


def write_camera_json(path, scene=None, camera=None):
    data = camera_dict(scene, camera)
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    # One matrix row per line keeps the file readable and diffable.
    fields = []
    for key, value in data.items():
        if key in ("view", "projection"):
            rows = ",\n    ".join(json.dumps(row) for row in value)
            fields.append('  "%s": [\n    %s\n  ]' % (key, rows))
        else:
            fields.append('  "%s": %s' % (key, json.dumps(value)))
    with open(path, "w") as f:
        f.write("{\n" + ",\n".join(fields) + "\n}\n")
    return data


def _argv_after_dashes():
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


if __name__ == "__main__":
    args = _argv_after_dashes()
    if len(args) != 1:
        print("usage: blender -b scene.blend --python export_camera.py -- out.camera.json",
              file=sys.stderr)
        sys.exit(2)
    write_camera_json(args[0])
    print("wrote", args[0])
