#!/usr/bin/env bash
# Records the golden output digests (tests/golden/runs.txt) into tests/data/golden.txt, or OUT.
#   scripts/record-golden.sh [REVISION] [BUILD_DIR] [OUT]
# Digests hold per device: record one file per CPU kind, e.g. tests/data/golden-haswell.txt.
# With a revision (e.g. main), that revision's CLI is built in a temporary directory from
# `git archive` and recorded: the reference behaviour a refactoring must keep bit for bit.
# Without one, this tree's build (BUILD_DIR, default build/) is recorded.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
rev=${1:-}
build=${2:-$root/build}
out=${3:-$root/tests/data/golden.txt}
cmake --build "$build" --target ssrcl_record_golden ssrcl_cli -j2 >/dev/null
cli=$build/ssrcl
if [[ -n $rev ]]; then
  tmp=$(mktemp -d "${TMPDIR:-/tmp}/ssrcl-golden.XXXXXX")
  trap 'rm -rf "$tmp"' EXIT
  mkdir "$tmp/src"
  git -C "$root" archive "$rev" | tar -x -C "$tmp/src"
  cmake -S "$tmp/src" -B "$tmp/build" -DCMAKE_BUILD_TYPE=Release -DSSRCL_BUILD_TESTS=OFF >/dev/null
  cmake --build "$tmp/build" --target ssrcl_cli -j2 >/dev/null
  cli=$tmp/build/ssrcl
fi
"$build/tests/ssrcl_record_golden" "$cli" "$root" "$out"
echo "recorded $out with $cli${rev:+ (revision $rev)}"
