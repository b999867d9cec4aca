#!/usr/bin/env bash
# The whole test suite, from nothing: install, build, run every test (ctest), the browser tests of
# the viewer included. Tests that need the real data in ../shared/data skip, saying so, when it is
# absent. CI (.ci/run) runs this first, then scripts/test_sanitized.sh (the same suite under
# AddressSanitizer and UndefinedBehaviorSanitizer, plus short runs of every fuzz target).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --test-dir build --output-on-failure --timeout 600 -j "$(nproc)" "$@"
