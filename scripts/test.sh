#!/usr/bin/env bash
# The whole test suite, from nothing: install, build, run every test (ctest). Tests that need the
# real data in ../shared/data skip, saying so, when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --test-dir build --output-on-failure --timeout 600 -j "$(nproc)" "$@"
