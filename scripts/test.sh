#!/usr/bin/env bash
# The whole test suite, from nothing: install, build, run every test (ctest), the browser tests of
# the viewer included, then the same suite built by clang with AddressSanitizer and
# UndefinedBehaviorSanitizer plus a short run of every fuzz target (scripts/test_sanitized.sh).
# Tests that need the real data in ../shared/data skip, saying so, when it is absent.
# LFCAM_SANITIZED=0 skips the sanitized half (a quicker local run; CI runs both).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --test-dir build --output-on-failure --timeout 600 -j "$(nproc)" "$@"
if [ "${LFCAM_SANITIZED:-1}" != 0 ]; then
  scripts/test_sanitized.sh "$@"
fi
