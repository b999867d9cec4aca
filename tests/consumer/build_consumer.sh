#!/usr/bin/env bash
# Installs lfcam from BUILD_DIR into a scratch prefix, then configures, builds and runs the consumer
# in tests/consumer against it with find_package(lfcam), as a user of the library would.
set -euo pipefail
build_dir=$1
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cmake --install "$build_dir" --prefix "$scratch/prefix" >/dev/null
cmake -S "$(dirname "$0")" -B "$scratch/build" -G Ninja -DCMAKE_PREFIX_PATH="$scratch/prefix" >/dev/null
cmake --build "$scratch/build" >/dev/null
"$scratch/build/consumer"
