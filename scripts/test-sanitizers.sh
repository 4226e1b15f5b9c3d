#!/usr/bin/env bash
# Issue 6 in CI, after scripts/test.sh:
#   1. the whole test suite built with AddressSanitizer + UndefinedBehaviorSanitizer (gcc,
#      -DSSRCL_SANITIZE=ON, build-sanitize/), halting on the first error;
#   2. the libFuzzer targets built with clang (-DSSRCL_FUZZ=ON -DSSRCL_SANITIZE=ON, build-fuzz/),
#      run for SSRCL_FUZZ_SECONDS (default 30) each (scripts/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs=$(nproc)

# -O0 -g builds three times faster than -O1 under the sanitizers; the tests' heavy double-precision
# scene code is built -O2 regardless (see CMakeLists.txt). ctest runs one test per executable here.
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O0 -g" -DSSRCL_SANITIZE=ON >/dev/null
cmake --build build-sanitize -j"$jobs"
# Every ASan check, leaks included; OpenCL drivers' process-lifetime allocations are suppressed
# (scripts/lsan.supp says why: PoCL showed none, GPU drivers do). UBSan: the build already halts
# on the first error (-fno-sanitize-recover=undefined); the options add the stack.
export ASAN_OPTIONS=detect_leaks=1
# use_tls=0: LeakSanitizer's own scan of the threads' dynamic TLS crashes ("Tracer caught signal
# 11" at a bogus DTLS range, then exit 1) once `batch --temporal --neighbours` has run on glibc 2.36;
# leaving TLS out of the roots can only add leak reports, never hide one.
export LSAN_OPTIONS=suppressions=$PWD/scripts/lsan.supp:print_suppressions=0:use_tls=0
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
(cd build-sanitize && ctest --output-on-failure -j"$jobs" --timeout 600)

# The fuzzers with ASan + UBSan too; the library and the two targets only (clang 14 cannot build
# every test: tests/test_ggx_sampler.cpp captures a structured binding, a C++20 feature).
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DSSRCL_FUZZ=ON \
      -DSSRCL_SANITIZE=ON -DSSRCL_BUILD_TESTS=OFF >/dev/null
cmake --build build-fuzz -j"$jobs" --target fuzz_gbuffer fuzz_camera
bash scripts/fuzz.sh build-fuzz "${SSRCL_FUZZ_SECONDS:-30}"
