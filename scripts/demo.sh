#!/usr/bin/env bash
# The main job, from nothing: install, build, and run `lfcam demo` on its built-in default.
# Writes ./lfcam-demo/index.html.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build/lfcam demo "$@"
