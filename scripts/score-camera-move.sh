#!/usr/bin/env bash
# Scores `ssrcl batch --neighbours K` on a camera move rendered by samples/blender/make_camera_move.py
# against its Cycles references: PSNR of every scored frame (those rendered with the corpus's
# samples, every 4th by default) for each K, the mean, and the batch's compute time per frame.
# The neighbours reach SSRCL_REACH frames out (default K: the adjacent frames, as
# docs/BENCHMARKS.md's table was measured; the batch's own default is 12).
#   bash scripts/score-camera-move.sh <move dir> [scene] [K ...]     (default interior_room, K = 0 1 2 4)
# Passes go to <move dir>/refl-k<K>/, batch reports to <move dir>/refl-k<K>.json.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$1
scene=${2:-interior_room}
shift $(( $# >= 2 ? 2 : 1 ))
ks=("$@")
[ ${#ks[@]} -gt 0 ] || ks=(0 1 2 4)
build=${SSRCL_BUILD:-build}
# Scored frames were rendered with the corpus's samples (their glossy passes are the references):
# every SSRCL_SCORED-th from frame 0, make_camera_move.py's --scored (default 4).
scored=()
for f in "$dir/$scene".[0-9][0-9][0-9][0-9].exr; do
  n=${f%.exr}
  n=${n##*.}
  if (( 10#$n % ${SSRCL_SCORED:-4} == 0 )); then scored+=("$f"); fi
done
for k in "${ks[@]}"; do
  out="$dir/refl-k$k"
  "$build/ssrcl" batch "$dir/$scene.####.exr" -o "$out/" --neighbours "$k" --neighbour-reach "${SSRCL_REACH:-$k}" \
    --temporal 0 --overwrite -q --report "$out.json"
  echo "== --neighbours $k"
  "$build/bench/ssrcl_score_passes" --passes "$out" "${scored[@]}"
  python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); f=[x for x in r["frames"] if x["status"]=="done"]
print("compute s/frame %.2f, device ms/frame %.0f" % (sum(x["seconds"]["compute"] for x in f)/len(f), sum(x["device_ms"] for x in f)/len(f)))' "$out.json"
done
