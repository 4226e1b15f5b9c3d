#!/usr/bin/env bash
# Runs the libFuzzer targets (fuzz/) for a bounded time each, from the seed corpus in
# fuzz/corpus (copied: the repository's corpus is not modified). Fails on the first crash,
# sanitizer report, timeout or out-of-memory, leaving the input under <build>/fuzz-artifacts.
#   bash scripts/fuzz.sh [build dir, default build-fuzz] [seconds per target, default 30]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-fuzz}
seconds=${2:-30}
artifacts="$build/fuzz-artifacts"
mkdir -p "$artifacts"
# Leaks are checked here (libFuzzer's per-input LeakSanitizer check: no OpenCL is loaded by the
# loaders, unlike the test suite). UBSan halts on the first error.
export ASAN_OPTIONS=abort_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
for target in gbuffer camera; do
  work=$(mktemp -d)
  cp fuzz/corpus/"$target"/* "$work"/
  dict=fuzz/exr.dict
  [ "$target" = camera ] && dict=fuzz/camera.dict
  echo "fuzz_$target: ${seconds}s"
  # -rss_limit_mb: the harness skips inputs declaring over 2^20 pixels, so a legitimate input
  # stays well under 2 GB; more is a bug (an allocation a header can force).
  if ! "$build/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -dict="$dict" \
       -artifact_prefix="$artifacts/$target-" -print_final_stats=1 "$work" >"$artifacts/$target.log" 2>&1; then
    tail -n 60 "$artifacts/$target.log"
    echo "fuzz_$target FAILED: input saved under $artifacts" >&2
    rm -rf "$work"
    exit 1
  fi
  grep -E "^(Done|stat::number_of_executed_units)" "$artifacts/$target.log" || true
  rm -rf "$work"
done
