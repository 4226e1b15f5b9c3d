#!/usr/bin/env bash
# Runs test_ssrcl_addon.py in headless Blender against the built ssrcl CLI, in a fresh WORKDIR.
#   run_addon_test.sh SSRCL WORKDIR
# Exits 77 (skipped) where Blender is not on PATH.
set -euo pipefail
command -v blender >/dev/null || { echo "SKIP: blender is not on PATH"; exit 77; }
ssrcl=$(realpath "$1") work=$2
rm -rf "$work" && mkdir -p "$work"
exec blender -b --factory-startup --python-exit-code 1 \
  --python "$(dirname "$(realpath "$0")")/test_ssrcl_addon.py" -- "$ssrcl" "$work"
