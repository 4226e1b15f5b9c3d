#!/usr/bin/env bash
# Installs a build into a temporary prefix, then builds and runs tests/consumer (the README's C++
# example) against it on the installed mirror sample, once through find_package(ssrcl) and once
# through pkg-config; and checks that libssrcl.so exports
# the API only; and that the installed CLI finds its bundled samples (share/ssrcl/samples), no
# source path compiled in.   tests/consumer/run.sh <build dir>
set -euo pipefail
build=$(cd "$1" && pwd)
src=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/ssrcl-consumer.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
cmake -S "$src" -B "$tmp/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$tmp/build" >/dev/null
sample=$tmp/prefix/share/ssrcl/samples/mirror/mirror.exr
"$tmp/build/ssrcl_consumer" "$sample" "$tmp/cmake.refl.exr"

libdir=$(dirname "$(find "$tmp/prefix" -name 'libssrcl.so' | head -n1)")
export PKG_CONFIG_PATH=$libdir/pkgconfig
# shellcheck disable=SC2046
c++ -std=c++17 "$src/main.cpp" $(pkg-config --cflags --libs ssrcl) -o "$tmp/pkg_consumer"
LD_LIBRARY_PATH=$libdir "$tmp/pkg_consumer" "$sample" "$tmp/pkg.refl.exr"

soname=$(objdump -p "$libdir/libssrcl.so" | awk '/SONAME/ {print $2}')
[[ $soname == libssrcl.so.[0-9]* ]] || { echo "unversioned SONAME: $soname"; exit 1; }
foreign=$(nm -DC --defined-only "$libdir/libssrcl.so" | cut -d' ' -f3- |
          grep -v -E '^(ssrcl::|typeinfo for ssrcl::|typeinfo name for ssrcl::|vtable for ssrcl::)' |
          grep -v -E '^ssrcl::detail::' || true)
internal=$(nm -DC --defined-only "$libdir/libssrcl.so" | cut -d' ' -f3- | grep -E '^ssrcl::detail::' || true)
if [[ -n $foreign || -n $internal ]]; then
  echo "libssrcl.so exports more than the API:"
  echo "$foreign$internal" | head -20
  exit 1
fi
LD_LIBRARY_PATH=$libdir "$tmp/prefix/bin/ssrcl" bench --sample mirror --quality draft --tracers hiz --no-reference \
  --repetitions 1 >/dev/null
if strings "$tmp/prefix/bin/ssrcl" | grep -qF "$(cd "$src/../.." && pwd)"; then
  echo "the installed CLI has the source directory compiled in"
  exit 1
fi
echo "consumer: built and ran against the installed package ($soname)"
