#!/usr/bin/env bash
# Scores every quality preset (and Blender EEVEE, where samples/corpus holds its renders) on every
# scene of the Cycles corpus and prints one table: PSNR per scene, means over the tuning and the
# held-out scenes, device time, the share of error on low-confidence pixels and the 99th
# percentile of per-pixel error. Extra arguments go to the scorer, e.g.
#   bash scripts/score-corpus.sh --configs 'medium;medium:thickness=0.01' --scenes night_street
#   bash scripts/score-corpus.sh --json corpus.json --plot docs/corpus-pareto.svg
# (reference traces 256 rays per pixel: the default list takes about 15 minutes on 2 cores.)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh >/dev/null
exec build/bench/ssrcl_score_corpus --corpus samples/corpus "$@"
