"""Write the ssrcl camera sidecar JSON for a Blender scene camera (perspective or orthographic).

Standalone:  blender -b scene.blend --python export_camera.py -- out.camera.json
Animation:   blender -b scene.blend --python export_camera.py -- 'shot.####.camera.json' --frames 1-240
             (one sidecar per frame, '#'s replaced by the zero-padded frame number, so that
             shot.1001.exr finds shot.1001.camera.json; ranges as ssrcl batch: 1-240, 1-240x2, 1,5,9)
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
    if camera.data.type not in ('PERSP', 'ORTHO'):
        # A panoramic camera has no clip matrix: its rays are not straight lines on screen.
        raise RuntimeError("only perspective and orthographic cameras are supported, got %s" % camera.data.type)

    render = scene.render
    scale = render.resolution_percentage / 100.0
    width = int(render.resolution_x * scale)
    height = int(render.resolution_y * scale)

    depsgraph = bpy.context.evaluated_depsgraph_get()
    cam_eval = camera.evaluated_get(depsgraph)
    # calc_matrix_camera goes through the same viewplane code the renderer uses
    # (BKE_camera_params_compute_viewplane): sensor fit, lens shift and pixel aspect are included,
    # and the result is a glFrustum-style (or, for ORTHO, glOrtho-style) matrix built from
    # clip_start/clip_end, which ssrcl reads by its last row.
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


def parse_frames(text):
    """'1-240', '1-240x2', '1,5,10-20' -> sorted frame numbers."""
    frames = set()
    for part in text.split(","):
        span, _, step = part.partition("x")
        first, _, last = span.partition("-")
        first, last, step = int(first), int(last or first), int(step or 1)
        if last < first or step < 1:
            raise ValueError("bad frame range '%s'" % part)
        frames.update(range(first, last + 1, step))
    return sorted(frames)


def frame_path(pattern, frame):
    """Replaces the run of '#' in `pattern` by `frame`, zero-padded to the run's length."""
    start = pattern.find("#")
    if start < 0:
        raise ValueError("'%s' has no '#' run for the frame number" % pattern)
    end = start
    while end < len(pattern) and pattern[end] == "#":
        end += 1
    return pattern[:start] + str(frame).zfill(end - start) + pattern[end:]


def main(args):
    usage = ("usage: blender -b scene.blend --python export_camera.py -- out.camera.json\n"
             "       blender -b scene.blend --python export_camera.py -- 'shot.####.camera.json' --frames 1-240")
    if len(args) == 1:
        write_camera_json(args[0])
        print("wrote", args[0])
        return 0
    if len(args) == 3 and args[1] == "--frames":
        try:
            frames = parse_frames(args[2])
            paths = [frame_path(args[0], f) for f in frames]
        except ValueError as e:
            print("export_camera.py: %s" % e, file=sys.stderr)
            return 2
        scene = bpy.context.scene
        for frame, path in zip(frames, paths):
            scene.frame_set(frame)  # evaluates animation, so the depsgraph holds this frame's camera
            write_camera_json(path, scene)
        print("wrote %d sidecars: %s ... %s" % (len(paths), paths[0], paths[-1]))
        return 0
    print(usage, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(_argv_after_dashes()))
