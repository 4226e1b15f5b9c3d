#!/usr/bin/env bash
# Runs `ssrcl batch` over the shots scripts/render-shots.sh rendered, in every configuration below,
# and scores them (bench/score_shots.cpp): mean per-frame PSNR and tPSNR per shot, frames/s, EEVEE
# and the references' noise floor.
#   bash scripts/score-shots.sh [shots dir] [config ...]      (default out/shots, every config)
#   SSRCL_SHOTS=living_truck,deck_pan bash scripts/score-shots.sh    (only these shots)
# A config name with "-back" after it (medium-batch-back) is that config with each frame's back-face
# depth pass (<shot>/back/, `make_shots.py --back-faces`).
# Passes go to out/shot-passes/<config>/<shot>/, reports to out/shot-passes/<config>/<shot>.json.
set -euo pipefail
cd "$(dirname "$0")/.."
shots=${1:-out/shots}
shift || true
build=${SSRCL_BUILD:-build}
passes=${SSRCL_SHOT_PASSES:-out/shot-passes}
declare -A args=(
  [draft]="--quality draft --temporal 0"
  [medium]="--quality medium --temporal 0"
  [high]="--quality high --temporal 0"
  [medium-t5]="--quality medium --temporal 5"
  [draft-t5]="--quality draft --temporal 5"
  [high-t5]="--quality high --temporal 5"
  [high-t3]="--quality high --temporal 3"
  [medium-t2]="--quality medium --temporal 2"
  [medium-t3]="--quality medium --temporal 3 --neighbours 0"
  [medium-c3]="--quality medium --temporal 0 --thickness 0.03"
  [medium-t3-c3]="--quality medium --temporal 3 --thickness 0.03"
  [medium-t8]="--quality medium --temporal 8"
  [medium-t3-n1]="--quality medium --temporal 3 --neighbours 1"
  [medium-t3-n2]="--quality medium --temporal 3 --neighbours 2"
  [medium-t5-n1]="--quality medium --temporal 5 --neighbours 1"
  [medium-t3-n2-r1]="--quality medium --temporal 3 --neighbours 2 --neighbour-reach 2"
  [medium-t5-n2]="--quality medium --temporal 5 --neighbours 2"
  [medium-t3-n1-r1]="--quality medium --temporal 3 --neighbours 1 --neighbour-reach 1"
  [medium-t3-ef0]="--quality medium --temporal 3 --edge-fade 0"
  [medium-t3-ef10]="--quality medium --temporal 3 --edge-fade 0.1"
  [medium-t3-ef15]="--quality medium --temporal 3 --edge-fade 0.15"
  [medium-t3-ef30]="--quality medium --temporal 3 --edge-fade 0.3"
  [medium-t3-n2-ef10]="--quality medium --temporal 3 --neighbours 2 --edge-fade 0.1"
  [draft-batch]="--quality draft"  # the batch defaults (--temporal 5, --neighbours 1 reaching 12)
  [medium-batch]="--quality medium"
  [high-batch]="--quality high"
  [medium-t3-batch]="--quality medium --temporal 3"  # the batch defaults with another window
  [medium-t4-batch]="--quality medium --temporal 4"
  [medium-t5-batch]="--quality medium --temporal 5"
  [medium-t6-batch]="--quality medium --temporal 6"
  [medium-t8-batch]="--quality medium --temporal 8"
  [medium-frameseeds]="--quality medium --temporal 0"  # each frame its own seed, as --temporal's
)
configs=("$@")
[ ${#configs[@]} -gt 0 ] || configs=(draft medium high draft-t5 medium-t2 medium-t3 medium-t5 medium-t8 high-t5 medium-frameseeds)
names=${SSRCL_SHOTS:-}
names=${names//,/ }
[ -n "$names" ] || names=$(python3 -c 'import json,sys; print(" ".join(s["name"] for s in json.load(open(sys.argv[1]))["shots"]))' "$shots/shots.json")
for c in "${configs[@]}"; do
  for s in $names; do
    env=$(python3 -c 'import json,sys; e=[x for x in json.load(open(sys.argv[1]))["shots"] if x["name"]==sys.argv[2]][0].get("environment"); print(e or "")' "$shots/shots.json" "$s")
    extra=()
    [ -z "$env" ] || extra=(--environment "$shots/$s/$env")
    base=${c%-back}
    [[ -v "args[$base]" ]] || { echo "score-shots.sh: unknown configuration '$c'" >&2; exit 2; }
    [ "$base" = "$c" ] || extra+=(--back-depth-file "$shots/$s/back/$s.####.exr")
    if [ "$base" = medium-frameseeds ]; then  # a batch per frame, --seed its index (no frames/s)
      n=$(python3 -c 'import json,sys; print([x for x in json.load(open(sys.argv[1]))["shots"] if x["name"]==sys.argv[2]][0]["frames"])' "$shots/shots.json" "$s")
      for f in $(seq 1 "$n"); do
        # shellcheck disable=SC2086
        "$build/ssrcl" batch "$shots/$s/$s.####.exr" --frames "$f" --seed $((f - 1)) -o "$passes/$c/$s/" \
          --output-form glossy-pass ${args[$base]} "${extra[@]}" --overwrite -q
      done
      continue
    fi
    # shellcheck disable=SC2086
    "$build/ssrcl" batch "$shots/$s/$s.####.exr" -o "$passes/$c/$s/" --output-form glossy-pass ${args[$base]} \
      "${extra[@]}" --overwrite -q --report "$passes/$c/$s.json"
  done
done
list=$(IFS=,; echo "${configs[*]}")
"$build/bench/ssrcl_score_shots" --shots "$shots" --passes "$passes" --configs "$list,eevee" \
  --shot "$(echo $names | tr ' ' ',')" --json "$passes/scores.json"
