#!/usr/bin/env bash
# The whole test suite again, built by clang with AddressSanitizer and UndefinedBehaviorSanitizer
# (LFCAM_SANITIZE=ON) in ./build-san, with a short run of every libFuzzer target (label fuzz).
# scripts/test.sh runs it after the normal suite. Any sanitizer report fails the test that caused it.
# Extra arguments go to ctest. LFCAM_FUZZ_SECONDS (default 20) sets each fuzz target's run.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
CC=clang-14 CXX=clang++-14 cmake -S . -B build-san -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache \
  -DLFCAM_SANITIZE=ON -DLFCAM_BUILD_BENCH=OFF -DLFCAM_FUZZ_SECONDS="${LFCAM_FUZZ_SECONDS:-20}" >/dev/null
cmake --build build-san
# Leaks are reported too; a sanitizer report ends the process with an error status.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:detect_stack_use_after_return=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/fuzz/lsan.supp}
start=$SECONDS
ctest --test-dir build-san --output-on-failure --timeout 1200 -j "$(nproc)" "$@"
echo "sanitized suite (with fuzz runs): $((SECONDS - start)) s"
