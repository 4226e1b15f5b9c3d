#!/usr/bin/env bash
# Speckle of two builds on the real corpus, measured by this build's scorer: each build's
# `ssrcl trace --output-form glossy-pass` on every scene of samples/real (its HDRI where it has one)
# and on every frame of the two camera moves (samples/real/move_tea_table, samples/real/shot_ci),
# then, in one run, PSNR, the 99th percentile of error and the fireflies over the pixels both
# passes answer (A >= 0.5: the off-screen hole left out), the mean signed error there and each
# pass's own noise (seeds 0 and 1), beside this build's medium with and without its filter (the
# same rays: their paired bias); then each move's frame-to-frame error (tPSNR).
#   bash scripts/score-speckle.sh <before build dir> [after build dir] [quality]
#       (default after: build; quality: medium; e.g. a worktree of an older commit, built)
# Passes and scores go to out/speckle/.
set -euo pipefail
cd "$(dirname "$0")/.."
before=$1
after=${2:-build}
quality=${3:-medium}
out=out/speckle
real=samples/real
mkdir -p "$out/shots/tea_table" "$out/shots/living_truck"
scenes=$(python3 -c 'import json; print(" ".join(s["name"] for s in json.load(open("samples/real/corpus.json"))["scenes"]))')
trace() {  # build, input, output, extra arguments
  local b=$1 in=$2 o=$3
  shift 3
  "$b/ssrcl" trace "$in" -o "$o" --output-form glossy-pass --quality "$quality" "$@" 2>/dev/null
}
for label in before after; do
  b=$before
  [ $label = before ] || b=$after
  mkdir -p "$out/$label/seed2"
  for s in $scenes; do
    env=$(python3 -c 'import json,sys; print([x for x in json.load(open("samples/real/corpus.json"))["scenes"] if x["name"]==sys.argv[1]][0].get("environment", ""))' "$s")
    extra=()
    [ -z "$env" ] || extra=(--environment "$real/$env")
    trace "$b" "$real/$s.exr" "$out/$label/$s.exr" "${extra[@]}"
    trace "$b" "$real/$s.exr" "$out/$label/seed2/$s.exr" "${extra[@]}" --seed 1
  done
  for shot in tea_table:move_tea_table living_truck:shot_ci; do
    name=${shot%%:*}
    mkdir -p "$out/passes/$label/$name"
    for f in "$real/${shot#*:}/$name".[0-9][0-9][0-9][0-9].exr; do
      stem=$(basename "$f" .exr)
      ln -sf "$PWD/$f" "$out/shots/$name/$stem.exr"
      ln -sf "$PWD/${f%.exr}.camera.json" "$out/shots/$name/$stem.camera.json"
      trace "$b" "$f" "$out/passes/$label/$name/$stem.refl.exr"
    done
  done
done
echo '{"shots": [{"name": "tea_table"}, {"name": "living_truck"}]}' > "$out/shots/shots.json"
"$after/bench/ssrcl_score_corpus" --corpus "$real" --noise --json "$out/scores.json" --dump "$out" --configs \
  "pass:$out/before;pass:$out/after;$quality:form=glossy-pass,denoise=0;$quality:form=glossy-pass"
"$after/bench/ssrcl_score_shots" --shots "$out/shots" --passes "$out/passes" --configs before,after \
  --json "$out/shot-scores.json"
