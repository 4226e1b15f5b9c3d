#!/usr/bin/env bash
# Makes the shot corpus's CI subset (samples/real/shot_ci, tests/test_shot_temporal.cpp) from the
# rendered shots (scripts/render-shots.sh): the first 3 frames of living_truck (2.4 MB) with the channels
# ssrcl and the scorer read, every one half but Depth (float), ZIP; the camera sidecars beside; each
# frame's back-face depth pass in back/ (float, as rendered: 33 KB a frame).
#   bash scripts/make-shot-ci.sh [shots dir]       (default out/shots)
set -euo pipefail
cd "$(dirname "$0")/.."
shots=${1:-out/shots}
out=samples/real/shot_ci
mkdir -p "$out/back"
keep=""
for c in Combined.R Combined.G Combined.B Depth.Z Normal.X Normal.Y Normal.Z roughness.X IndexOB.X \
         GlossDir.R GlossDir.G GlossDir.B GlossInd.R GlossInd.G GlossInd.B GlossCol.R GlossCol.G GlossCol.B \
         base_color.R base_color.G base_color.B metallic.X; do
  keep+="${keep:+,}ViewLayer.$c"
done
for f in 1 2 3; do
  s=$(printf 'living_truck.%04d' "$f")
  oiiotool --nosoftwareattrib "$shots/living_truck/$s.exr" --ch "$keep" -d half -d ViewLayer.Depth.Z=float \
    --compression zip -o "$out/$s.exr"
  cp "$shots/living_truck/$s.camera.json" "$out/"
  cp "$shots/living_truck/back/$s.exr" "$out/back/"
done
du -sb "$out"
