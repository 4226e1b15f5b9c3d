#!/usr/bin/env bash
# The README's first command: install what is needed, build, and compute the reflection pass of
# the bundled Blender sample into out/mirror.refl.exr.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
mkdir -p out
./build/ssrcl devices
./build/ssrcl trace samples/blender/mirror/mirror.exr -o out/mirror.refl.exr --stats
echo "wrote out/mirror.refl.exr"
