"""Check that a Blender sample's G-buffer agrees with its camera sidecar.

    python3 check_sample.py mirror/mirror.exr mirror/mirror.camera.json [--preview out.png]
    python3 check_sample.py glossy/glossy.exr glossy/glossy.camera.json \
        --floor-roughness 0.125,0.25,0.4375 --stripe-columns 160,320
    blender -b --factory-startup --python check_sample.py -- mirror/mirror.exr ...

Floor pixels are those whose whole filter footprint has finite depth and a roughness AOV within
the range of --floor-roughness (default 0, the mirror; the samples' objects use other values).
Unprojects every floor pixel from its depth with the JSON camera and reports how far the
recovered point is from the z = 0 plane; also checks floor normals, the background depth, the
roughness AOV (exactly the floor value; with --stripe-columns, the value of the stripe whose
image columns hold the pixel, and in between next to a stripe edge) and that
Combined == (GlossDir + GlossInd) * GlossCol on the floor. Conventions tested: pixel (x, y)
centre is (x + 0.5, y + 0.5), y = 0 is the top row of the EXR, NDC x = 2 (x + 0.5) / W - 1,
NDC y = 1 - 2 (y + 0.5) / H, Depth.Z = planar depth = -z_camera.
Exits 1 if a check fails.
"""
import collections
import json
import math
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import minexr  # noqa: E402

LAYER = "ViewLayer."
BACKGROUND_DEPTH = 1e10
FLOOR_Z_TOL = 1e-3       # metres, relative to depth (see report: depth comes from one sample)
NORMAL_TOL = 1e-4
GLOSSY_REL_TOL = 0.01
# Filtered passes (Normal, AOV, colours) mix in samples from up to this many pixels away
# (Cycles' default 1.5 px Blackman-Harris filter; measured: 1 px is not enough, 2 px is).
MARGIN = 2


def invert4(m):
    """Gauss-Jordan inverse; the view matrix is rigid but this keeps no assumption about it."""
    a = [list(map(float, row)) + [1.0 if i == j else 0.0 for j in range(4)]
         for i, row in enumerate(m)]
    for col in range(4):
        pivot = max(range(col, 4), key=lambda r: abs(a[r][col]))
        a[col], a[pivot] = a[pivot], a[col]
        p = a[col][col]
        a[col] = [v / p for v in a[col]]
        for r in range(4):
            if r != col:
                f = a[r][col]
                a[r] = [vr - f * vc for vr, vc in zip(a[r], a[col])]
    return [row[4:] for row in a]


def unproject(ndc_x, ndc_y, depth, proj, inv_view):
    """Camera-space point at planar depth `depth` through NDC (x, y), then to world space.

    With a GL matrix whose last row is (0, 0, -1, 0), clip w = -z_cam = depth, so
    ndc_x * depth = P00 x + P01 y + P02 z + P03 (same for y); a 2x2 solve handles lens shift.
    """
    z = -depth
    bx = ndc_x * depth - proj[0][2] * z - proj[0][3]
    by = ndc_y * depth - proj[1][2] * z - proj[1][3]
    det = proj[0][0] * proj[1][1] - proj[0][1] * proj[1][0]
    x = (bx * proj[1][1] - proj[0][1] * by) / det
    y = (proj[0][0] * by - bx * proj[1][0]) / det
    cam = (x, y, z, 1.0)
    return [sum(inv_view[r][c] * cam[c] for c in range(4)) for r in range(3)]


def write_png(path, width, height, rgb_rows):
    """8-bit sRGB-ish preview (clamped, gamma 2.2) so the sample can be eyeballed."""
    raw = bytearray()
    for row in rgb_rows:
        raw.append(0)  # filter type None
        for v in row:
            raw.append(int(round(255.0 * min(max(v, 0.0), 1.0) ** (1.0 / 2.2))))

    def chunk(tag, body):
        return (struct.pack(">I", len(body)) + tag + body
                + struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(bytes(raw), 9)))
        f.write(chunk(b"IEND", b""))


def interior(W, H, pred):
    """Pixels whose whole (2 MARGIN + 1)^2 neighbourhood satisfies pred."""
    r = range(-MARGIN, MARGIN + 1)
    return [y * W + x for y in range(MARGIN, H - MARGIN) for x in range(MARGIN, W - MARGIN)
            if all(pred((y + dy) * W + x + dx) for dy in r for dx in r)]


def percentile(values, q):
    s = sorted(values)
    return s[min(len(s) - 1, int(q * (len(s) - 1) + 0.5))] if s else float("nan")


def take_option(argv, name, default):
    """Remove `name value` from argv; return (value or default, argv)."""
    if name not in argv:
        return default, argv
    i = argv.index(name)
    if i + 1 >= len(argv):
        raise SystemExit("%s needs a value" % name)
    return argv[i + 1], argv[:i] + argv[i + 2:]


def main(argv):
    preview, argv = take_option(argv, "--preview", None)
    floor_values, argv = take_option(argv, "--floor-roughness", "0")
    stripe_columns, argv = take_option(argv, "--stripe-columns", "")
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    exr_path, json_path = argv
    floor_values = [float(v) for v in floor_values.split(",")]
    stripe_columns = [int(c) for c in stripe_columns.split(",")] if stripe_columns else []
    if len(stripe_columns) != len(floor_values) - 1:
        print("need one --stripe-columns edge between each two --floor-roughness values",
              file=sys.stderr)
        return 2

    exr = minexr.ExrFile(exr_path)
    with open(json_path) as f:
        cam = json.load(f)
    W, H = exr.width, exr.height
    ok = True

    print("file: %s (%d bytes), %dx%d, compression %s"
          % (exr_path, os.path.getsize(exr_path), W, H, exr.compression))
    for name, ptype in exr.channel_types():
        print("  %-24s %s" % (name, ptype))
    if (cam["width"], cam["height"]) != (W, H):
        print("FAIL camera size %dx%d != EXR %dx%d" % (cam["width"], cam["height"], W, H))
        return 1
    proj, view = cam["projection"], cam["view"]
    if [abs(v) for v in proj[3]] != [0.0, 0.0, 1.0, 0.0] or proj[3][2] != -1.0:
        print("FAIL projection last row is not (0, 0, -1, 0): %s" % proj[3])
        return 1
    inv_view = invert4(view)

    depth = exr.channel(LAYER + "Depth.Z")
    nx, ny, nz = (exr.channel(LAYER + "Normal." + c) for c in "XYZ")
    rough = exr.channel(LAYER + "roughness.X")
    comb = [exr.channel(LAYER + "Combined." + c) for c in "RGB"]
    gdir = [exr.channel(LAYER + "GlossDir." + c) for c in "RGB"]
    gind = [exr.channel(LAYER + "GlossInd." + c) for c in "RGB"]
    gcol = [exr.channel(LAYER + "GlossCol." + c) for c in "RGB"]

    # Background: Cycles writes a huge constant depth and a zero normal there. Depth is not
    # filtered (one value per pixel), but Normal is, so only pixels away from geometry are 0.
    sky = [i for i in range(W * H) if depth[i] >= 1e9]
    sky_depths = sorted(set(depth[i] for i in sky))
    clean_sky = interior(W, H, lambda i: depth[i] >= 1e9)
    print("\nbackground: %d px = %.1f%% of the image, depth value(s) %s, "
          "max |normal| %d+ px from geometry %.3g"
          % (len(sky), 100.0 * len(sky) / (W * H), sky_depths[:3], MARGIN,
             max((abs(nx[i]) + abs(ny[i]) + abs(nz[i]) for i in clean_sky), default=0.0)))
    if sky_depths and sky_depths != [BACKGROUND_DEPTH]:
        print("  note: background depth is not exactly %g" % BACKGROUND_DEPTH)

    # Floor = roughness AOV within the floor's values (the objects use others) and finite depth,
    # over the pixel's whole filter footprint, which drops pixels mixing floor with objects or
    # with the sky. (Normal = +Z alone would also take the tops of cubes.)
    lo, hi = min(floor_values) - 1e-6, max(floor_values) + 1e-6
    floor = interior(W, H, lambda i: lo <= rough[i] <= hi and depth[i] < 1e9)
    if not floor:
        print("FAIL no floor pixels with roughness AOV in %s" % floor_values)
        return 1
    print("floor: %d px = %.1f%% of the image, depth %.3f .. %.3f m"
          % (len(floor), 100.0 * len(floor) / (W * H),
             min(depth[i] for i in floor), max(depth[i] for i in floor)))
    common = collections.Counter(round(v, 4) for v in rough).most_common(8)
    print("roughness AOV, most common values (value, pixels): %s" % common)

    # Unproject floor pixels; planar depth should land on z = 0. Also try the radial-distance
    # reading of Depth to show which one Cycles writes.
    errs, rel_errs, radial_errs = [], [], []
    for i in floor:
        x, y = i % W, i // W
        ndc_x = 2.0 * (x + 0.5) / W - 1.0
        ndc_y = 1.0 - 2.0 * (y + 0.5) / H
        d = depth[i]
        p = unproject(ndc_x, ndc_y, d, proj, inv_view)
        errs.append(abs(p[2]))
        rel_errs.append(abs(p[2]) / d)
        # If d were the distance along the ray, the planar depth would be d / |ray(z=-1)|.
        ray = unproject(ndc_x, ndc_y, 1.0, proj, [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0],
                                                  [0, 0, 0, 1]])
        planar = d / math.sqrt(ray[0] ** 2 + ray[1] ** 2 + 1.0)
        radial_errs.append(abs(unproject(ndc_x, ndc_y, planar, proj, inv_view)[2]))
    near = [e for e, i in zip(errs, floor) if depth[i] < 20.0]
    print("\nfloor unprojection |z_world| (planar depth): max %.3g m, median %.3g m, "
          "99th pct %.3g m; max |z|/depth %.3g; max over depth < 20 m: %.3g m"
          % (max(errs), percentile(errs, 0.5), percentile(errs, 0.99), max(rel_errs),
             max(near) if near else float("nan")))
    print("  same with Depth read as radial distance: max %.3g m, median %.3g m"
          % (max(radial_errs), percentile(radial_errs, 0.5)))
    if max(rel_errs) > FLOOR_Z_TOL:
        ok = False
        print("FAIL floor does not unproject to z = 0")

    # Roughness AOV on the floor: column band k (x + 0.5 between edges k-1 and k) holds value k.
    # The AOV is filtered, so a pixel within MARGIN columns of an edge may hold a blend.
    def band(x):
        return sum(1 for edge in stripe_columns if x + 0.5 > edge)
    print("\nfloor roughness AOV per stripe (image columns: value):")
    for k, value in enumerate(floor_values):
        first = stripe_columns[k - 1] if k else 0
        last = stripe_columns[k] - 1 if k < len(stripe_columns) else W - 1
        inner = [i for i in floor if all(band(i % W + d) == k
                                         for d in range(-MARGIN, MARGIN + 1))]
        exact = sum(1 for i in inner if rough[i] == value)
        dev = max((abs(rough[i] - value) for i in inner), default=0.0)
        rows = sorted(set(i // W for i in inner))
        print("  columns %3d-%3d: %-7g %6d px (rows %s-%s) exact %d, max |AOV - value| %.3g"
              % (first, last, value, len(inner), rows[0] if rows else "-",
                 rows[-1] if rows else "-", exact, dev))
        if exact != len(inner):
            ok = False
            print("FAIL roughness AOV does not match the stripe value")
    edge_px = [i for i in floor if len(set(band(i % W + d)
                                           for d in range(-MARGIN, MARGIN + 1))) > 1]
    outside = 0
    for i in edge_px:
        near = [floor_values[band(i % W + d)] for d in range(-MARGIN, MARGIN + 1)]
        outside += not (min(near) - 1e-6 <= rough[i] <= max(near) + 1e-6)
    if edge_px:
        print("  %d px within %d columns of a stripe edge, %d outside the neighbouring values"
              % (len(edge_px), MARGIN, outside))
        if outside:
            ok = False
            print("FAIL roughness AOV next to a stripe edge is not a blend of the two stripes")

    dev = max(math.sqrt(nx[i] ** 2 + ny[i] ** 2 + (nz[i] - 1.0) ** 2) for i in floor)
    print("floor normals: max |n - (0,0,1)| = %.3g" % dev)
    if dev > NORMAL_TOL:
        ok = False
        print("FAIL floor normals are not world +Z")

    # A metallic floor has no diffuse lobe, so all its light is glossy and
    # Cycles' light-pass convention gives Combined = (GlossDir + GlossInd) * GlossCol.
    worst, total = 0.0, 0.0
    for i in floor:
        for c in range(3):
            recon = (gdir[c][i] + gind[c][i]) * gcol[c][i]
            rel = abs(recon - comb[c][i]) / max(comb[c][i], 1e-3)
            worst = max(worst, rel)
            total += rel
    print("floor Combined vs (GlossDir + GlossInd) * GlossCol: max rel err %.3g, mean %.3g"
          % (worst, total / (3 * len(floor))))
    print("floor GlossCol mean: %s" % [round(sum(gcol[c][i] for i in floor) / len(floor), 4)
                                       for c in range(3)])
    if worst > GLOSSY_REL_TOL:
        ok = False
        print("FAIL glossy passes do not add up to Combined on the floor")

    if preview:
        rows = [[comb[c][y * W + x] for x in range(W) for c in range(3)] for y in range(H)]
        write_png(preview, W, H, rows)
        print("\npreview written to", preview)

    print("\nOK" if ok else "\nFAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    sys.exit(main(args))
