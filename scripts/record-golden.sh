#!/usr/bin/env bash
# Records the golden output digests (tests/golden/runs.txt) into tests/data/golden-<target>.txt, or OUT.
#   scripts/record-golden.sh [REVISION] [BUILD_DIR] [OUT]
# Digests hold per PoCL target (the CPU kind PoCL compiles for): one file per target. Without OUT,
# this CPU's target is recorded, and on a CPU with AVX2 that is not itself Haswell, the Haswell
# target too (PoCL compiles for it when told to: POCL_LLVM_CPU_NAME=haswell, bit for bit a
# Haswell machine's output), so both recordings the suite checks move together.
# With a revision (e.g. main), that revision's CLI is built in a temporary directory from
# `git archive` and recorded: the reference behaviour a refactoring must keep bit for bit.
# Without one, this tree's build (BUILD_DIR, default build/) is recorded.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
rev=${1:-}
build=${2:-$root/build}
out=${3:-}
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
record() {  # record FILE [ENV...]
  local file=$1; shift
  env "$@" "$build/tests/ssrcl_record_golden" "$cli" "$root" "$file"
  echo "recorded $file with $cli${rev:+ (revision $rev)}${*:+ ($*)}"
}
if [[ -n $out ]]; then record "$out"; exit 0; fi
target=$("$cli" devices | grep -o 'HSTR: [^,]*' | head -n 1 | sed 's/.*-gnu-//')
[[ -n $target ]] || { echo "record-golden: no PoCL CPU device; name OUT" >&2; exit 2; }
record "$root/tests/data/golden-$target.txt"
if [[ $target != haswell ]] && grep -qw avx2 /proc/cpuinfo; then
  record "$root/tests/data/golden-haswell.txt" POCL_LLVM_CPU_NAME=haswell POCL_KERNELLIB_NAME=avx2
fi
