#!/usr/bin/env bash
# Renders the shot corpus (samples/real/make_shots.py) into an ignored folder: Cycles references
# of every frame, a second seed of each shot's first frame, each frame's back-face depth pass
# (seconds a shot), then EEVEE of the same frames.
#   scripts/render-shots.sh [outdir] [shot names...]      (outdir default: out/shots)
# Needs Blender 3.4, xvfb-run (EEVEE) and the assets (samples/real/README.md, "Regenerate").
# SSRCL_SHOT_SAMPLES / _FRAMES / _WIDTH / _HEIGHT and SSRCL_EEVEE_SAMPLES: make_shots.py.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out/shots}
shift || true
script=$root/samples/real/make_shots.py
nice -n 10 blender -b --factory-startup --python-exit-code 1 --python "$script" -- "$out" "$@"
nice -n 10 blender -b --factory-startup --python-exit-code 1 --python "$script" -- --back-faces "$out" "$@"
nice -n 10 xvfb-run -a -s "-screen 0 1280x1024x24" blender -b --factory-startup \
    --python-exit-code 1 --python "$script" -- --eevee "$out" "$@"
