"""Seed-to-seed noise of a corpus reference: PSNR of GlossDir + GlossInd between two renders.

    python3 samples/corpus/seed_psnr.py samples/corpus/<name>.exr /tmp/seed1/<name>.exr [index]

Over the pixels whose IndexOB equals `index` (default 1, the main reflector) in the first file:
MSE over their R, G, B values of (GlossDir + GlossInd), peak = the 99.9th percentile of those
values in the first (reference) file, PSNR = 10 log10(peak^2 / MSE). Pure Python (minexr).
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "blender"))
import minexr  # noqa: E402

LAYER = "ViewLayer."


def gloss(exr):
    out = []
    for c in "RGB":
        d = exr.channel(LAYER + "GlossDir." + c)
        i = exr.channel(LAYER + "GlossInd." + c)
        out.append([a + b for a, b in zip(d, i)])
    return out


def main():
    ref_path, other_path = sys.argv[1], sys.argv[2]
    index = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    ref, other = minexr.ExrFile(ref_path), minexr.ExrFile(other_path)
    mask = [int(round(v)) == index for v in ref.channel(LAYER + "IndexOB.X")]
    a, b = gloss(ref), gloss(other)
    ref_vals, sq = [], 0.0
    for ca, cb in zip(a, b):
        for m, x, y in zip(mask, ca, cb):
            if m:
                ref_vals.append(x)
                sq += (x - y) ** 2
    n = len(ref_vals)
    mse = sq / n
    ref_vals.sort()
    peak = ref_vals[min(n - 1, int(0.999 * n))]
    psnr = 10.0 * math.log10(peak * peak / mse) if mse > 0 else float("inf")
    print("%s: %d px (IndexOB %d), peak %.4g, rmse %.4g, PSNR %.2f dB"
          % (os.path.basename(ref_path), n // 3, index, peak, math.sqrt(mse), psnr))


if __name__ == "__main__":
    main()
