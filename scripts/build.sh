#!/usr/bin/env bash
# Installs the dependencies (scripts/setup.sh), then configures and builds lfcam in ./build, and
# installs its Python package where Debian's python3 finds it (/usr/local/lib/python3.X/dist-packages),
# so that `python3 -c "import lfcam"` works from any folder.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache >/dev/null
cmake --build build
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
$SUDO cmake --install build --component python --prefix /usr/local >/dev/null
