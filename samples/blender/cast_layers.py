"""The solids along each pixel's viewing line of corpus scenes, by ray casts through the pixel
centres (Blender's scene.ray_cast, face orientation counting entries and exits): the first solid's
front and back, and the second solid's behind it, as planar depths. What docs/BENCHMARKS.md "A
second layer behind the first" measured with; no renderer pass holds the second layer, and the
trace reads no such input.

    blender -b --factory-startup --python-exit-code 1 --python samples/blender/cast_layers.py \
        -- corpus|real <outdir> [scene names...]

Writes <outdir>/<name>.layer1.raw and <name>.layer2.raw: float32 (front, back) per pixel, rows
top-down, 0 where there is none (layer 1 checks the casts against the Depth and back-face passes:
on every corpus scene they agree within 1% and 2% on every pixel).
"""
import os
import sys
import time

import bpy
import numpy as np
from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import render_back_faces  # noqa: E402  (its path setup, build_scene and the command line)


def layers(scene, outdir, name):
    """Casts every pixel's viewing line and writes the two layers' files."""
    dg = bpy.context.evaluated_depsgraph_get()
    cam = scene.camera
    W = scene.render.resolution_x * scene.render.resolution_percentage // 100
    H = scene.render.resolution_y * scene.render.resolution_percentage // 100
    # view_frame: top-right, bottom-right, bottom-left, top-left
    tr, br, bl, tl = [cam.matrix_world @ v for v in cam.data.view_frame(scene=scene)]
    eye = cam.matrix_world.translation
    fwd = (cam.matrix_world.to_3x3() @ Vector((0, 0, -1))).normalized()
    out1 = np.zeros((H, W, 2), np.float32)
    out2 = np.zeros((H, W, 2), np.float32)
    t0 = time.perf_counter()
    for y in range(H):
        v = (y + 0.5) / H
        left = tl + (bl - tl) * v
        right = tr + (br - tr) * v
        for x in range(W):
            u = (x + 0.5) / W
            p = left + (right - left) * u
            d = (p - eye).normalized()
            cosz = d.dot(fwd)
            origin = eye.copy()
            depth = 0
            state = 0  # 0 before the first solid, 1 inside it, 2 between, 3 inside the second
            f0 = b0 = f1 = b1 = 0.0
            for _ in range(16):
                hit, loc, nrm = scene.ray_cast(dg, origin, d)[:3]
                if not hit:
                    break
                dist = (loc - eye).dot(d)
                front = nrm.dot(d) < 0.0
                depth += 1 if front else -1
                z = dist * cosz
                if state == 0:
                    if not front:
                        break  # the visible surface is a back face
                    f0, state = z, 1
                elif state == 1 and depth <= 0:
                    b0, state = z, 2
                    depth = 0
                elif state == 2:
                    if not front:
                        break
                    f1, state = z, 3
                elif state == 3 and depth <= 0:
                    b1 = z
                    break
                origin = loc + d * 1e-4
            out1[y, x] = (f0, b0 if state >= 2 else 0.0)
            if b1 > 0.0:
                out2[y, x] = (f1, b1)
    out1.tofile(os.path.join(outdir, name + ".layer1.raw"))
    out2.tofile(os.path.join(outdir, name + ".layer2.raw"))
    print("LAYERS %s %dx%d: %.1f s, second layer on %d pixels, first back on %d" % (
        name, W, H, time.perf_counter() - t0, int((out2[..., 1] > 0).sum()), int((out1[..., 1] > 0).sum())))


def main():
    render_back_faces.for_each_corpus_scene(
        "cast_layers.py", lambda corpus, spec, outdir, scratch: layers(
            render_back_faces.build_scene(corpus, spec, scratch), outdir, spec["name"]))


if __name__ == "__main__":
    main()
